// Ψ spec and last-layer access (psi.hpp).
#include "spectral/psi.hpp"

#include "core/error.hpp"
#include "core/rng.hpp"

namespace sgnlf::spectral {

field::MlpSpec psi_mlp_spec(const PsiSpec& spec) {
  spec.validate();
  return field::make_mlp_spec(3, spec.width, spec.hidden, spec.k, spec.activation, field::Activation::None);
}

void init_psi_params(const field::Mlp& mlp, const PsiSpec& spec, std::vector<float>& params, size_t offset,
                     uint64_t seed) {
  mlp.init_params(params, offset, seed);
  Rng rng(seed, 0x5bd1u);
  const auto& layers = mlp.spec().layers;
  int n_in = mlp.spec().n_in;
  for (size_t l = 0; l < layers.size(); ++l) {
    const int pad = field::Mlp::pad16(layers[l].width);
    const size_t base = offset + mlp.layer_offset(int(l));
    if (l == 0)
      for (size_t i = 0; i < size_t(n_in) * pad; ++i) params[base + i] *= float(spec.first_layer_scale);
    if (l + 1 < layers.size())
      for (int o = 0; o < layers[l].width; ++o)
        params[base + size_t(n_in) * pad + o] = float(spec.bias_init * (2 * rng.uniform_double() - 1));
    n_in = layers[l].width;
  }
}

void psi_last_layer(const field::Mlp& mlp, const std::vector<float>& params, size_t offset,
                    std::vector<float>& W, std::vector<float>& b) {
  const int last = int(mlp.spec().layers.size()) - 1;
  const int k = mlp.spec().n_out();
  const int h = last == 0 ? mlp.spec().n_in : mlp.spec().layers[size_t(last - 1)].width;
  const int pad = field::Mlp::pad16(k);
  const size_t base = offset + mlp.layer_offset(last);
  require(params.size() >= offset + mlp.n_params(), "psi_last_layer: params too short");
  W.assign(size_t(k) * h, 0.0f);
  b.assign(size_t(k), 0.0f);
  for (int i = 0; i < h; ++i)
    for (int o = 0; o < k; ++o) W[size_t(o) * h + i] = params[base + size_t(i) * pad + o];
  for (int o = 0; o < k; ++o) b[size_t(o)] = params[base + size_t(h) * pad + o];
}

void set_psi_last_layer(const field::Mlp& mlp, std::vector<float>& params, size_t offset,
                        const std::vector<float>& W, const std::vector<float>& b) {
  const int last = int(mlp.spec().layers.size()) - 1;
  const int k = mlp.spec().n_out();
  const int h = last == 0 ? mlp.spec().n_in : mlp.spec().layers[size_t(last - 1)].width;
  const int pad = field::Mlp::pad16(k);
  const size_t base = offset + mlp.layer_offset(last);
  require(W.size() == size_t(k) * h && b.size() == size_t(k), "set_psi_last_layer: bad W/b size");
  for (int i = 0; i < h; ++i)
    for (int o = 0; o < k; ++o) params[base + size_t(i) * pad + o] = W[size_t(o) * h + i];
  for (int o = 0; o < k; ++o) params[base + size_t(h) * pad + o] = b[size_t(o)];
}

void fold_into_psi(const field::Mlp& mlp, std::vector<float>& params, size_t offset, const RitzResult& ritz) {
  std::vector<float> W, b;
  psi_last_layer(mlp, params, offset, W, b);
  const int last = int(mlp.spec().layers.size()) - 1;
  const int h = last == 0 ? mlp.spec().n_in : mlp.spec().layers[size_t(last - 1)].width;
  fold_readout(ritz, W, b, h);
  set_psi_last_layer(mlp, params, offset, W, b);
}

}  // namespace sgnlf::spectral
