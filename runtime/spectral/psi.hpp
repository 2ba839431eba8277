// Ψ: the spectral-embedding MLP 3 → 64 → 64 → K with a smooth activation (method.md §4.1), built
// on the field's Mlp (runtime/field) and living in a slice of a flat parameter buffer. Also the
// host-side access to its last linear layer, into which the Rayleigh–Ritz readout is folded.
#pragma once
#include <memory>

#include "field/mlp.hpp"
#include "spectral/psi_spec.hpp"
#include "spectral/rayleigh_ritz.hpp"

namespace sgnlf::spectral {

// Ψ's MLP: 3 → width (× hidden) → k, spec's activation, linear output.
field::MlpSpec psi_mlp_spec(const PsiSpec& spec);

// Initialises Ψ's slice: Mlp::init_params, then the bias/first-layer rules of PsiSpec.
void init_psi_params(const field::Mlp& mlp, const PsiSpec& spec, std::vector<float>& params, size_t offset,
                     uint64_t seed);

// Reads/writes the last layer y = W h + b of Ψ's slice in host parameters (W K×H row-major).
void psi_last_layer(const field::Mlp& mlp, const std::vector<float>& params, size_t offset,
                    std::vector<float>& W, std::vector<float>& b);
void set_psi_last_layer(const field::Mlp& mlp, std::vector<float>& params, size_t offset,
                        const std::vector<float>& W, const std::vector<float>& b);
// Folds a readout into Ψ's slice of host parameters (rayleigh_ritz.hpp).
void fold_into_psi(const field::Mlp& mlp, std::vector<float>& params, size_t offset, const RitzResult& ritz);

}  // namespace sgnlf::spectral
