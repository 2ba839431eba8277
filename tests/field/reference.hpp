// Host reference implementations of the field kernels, for tests only (the runtime never calls
// them). Plain loops in the order the formulas read; float arithmetic with double accumulation
// where the device sums long series.
#pragma once
#include <cstdint>
#include <vector>

#include "field/hash_grid.hpp"
#include "field/mlp.hpp"

namespace sgnlf::test::ref {

// Hash grid (runtime/field/hash_grid.hpp layout). table = the module slice.
std::vector<float> hashgrid_fwd(const field::HashGridConfig& cfg, const std::vector<float>& table,
                                const std::vector<float>& x, const std::vector<float>& weights);
std::vector<float> hashgrid_bwd(const field::HashGridConfig& cfg, size_t n_params,
                                const std::vector<float>& x, const std::vector<float>& weights,
                                const std::vector<float>& d_enc);
std::vector<float> hashgrid_bwd_dx(const field::HashGridConfig& cfg,
                                   const std::vector<float>& table, const std::vector<float>& x,
                                   const std::vector<float>& weights,
                                   const std::vector<float>& d_enc);

// MLP (runtime/field/mlp.hpp layout). params = the module slice.
std::vector<float> mlp_fwd(const field::MlpSpec& spec, const std::vector<float>& params,
                           const std::vector<float>& in, int n);
// Returns dL/dparams (module slice layout); fills d_in (N × n_in).
std::vector<float> mlp_bwd(const field::MlpSpec& spec, const std::vector<float>& params,
                           const std::vector<float>& in, int n, const std::vector<float>& d_out,
                           std::vector<float>& d_in);

// Direction encoding and head input (runtime/field/dir_encoding.hpp layout).
std::vector<float> direnc_fwd(const std::vector<float>& dir, int n_freq);
std::vector<float> direnc_bwd(const std::vector<float>& dir, int n_freq,
                              const std::vector<float>& d_enc);
std::vector<float> head_input_fwd(const std::vector<float>& dens, const std::vector<float>& enc,
                                  int n_rays, int samples, int n_geo, int geo_start,
                                  int dens_stride, int enc_dim);

// Adam (kernels/optim/adam.cl), in place, for one group at step t.
void adam_step(std::vector<float>& p, const std::vector<float>& g, std::vector<float>& m,
               std::vector<float>& v, size_t offset, size_t count, float lr, int64_t t,
               float beta1, float beta2, float eps, float weight_decay);

}  // namespace sgnlf::test::ref
