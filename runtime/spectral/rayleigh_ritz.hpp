// Rayleigh–Ritz readout of the learned span (method.md §4.1): solve P c = λ S c with Eigen's
// GeneralizedSelfAdjointEigenSolver. The eigenfunctions ψ = Cᵀ (y − μ) are orthonormal in the
// area-weighted inner product (CᵀSC = I) and sorted by eigenvalue; folding C and μ into Ψ's
// last linear layer (W' = CᵀW, b' = Cᵀ(b − μ)) makes the network output them directly.
#pragma once
#include <Eigen/Core>

#include <vector>

#include "spectral/surface.hpp"

namespace sgnlf::spectral {

struct RitzResult {
  Eigen::VectorXd eigenvalues;  // ascending
  Eigen::MatrixXd C;            // K×K, column i = coefficients of eigenfunction i
  Eigen::VectorXd mean;         // μ removed before C
};

RitzResult rayleigh_ritz(const Eigen::MatrixXd& S, const Eigen::MatrixXd& P,
                         const Eigen::VectorXd& mean);

// Folds the readout into a last layer y = W h + b with W K×H row-major floats, b K floats.
void fold_readout(const RitzResult& ritz, std::vector<float>& W, std::vector<float>& b, int hidden);

// Per-group comparison of learned eigenvalues (ascending) with the analytic groups: the learned
// values are assigned to groups by sorted position; a group cut by K is compared on its
// available members.
struct GroupError {
  double analytic = 0;
  int multiplicity = 0;  // analytic multiplicity
  int used = 0;          // learned eigenvalues in this group (≤ multiplicity)
  double learned_mean = 0;
  double rel_err = 0;    // |learned_mean − analytic| / analytic
};
std::vector<GroupError> compare_groups(const Eigen::VectorXd& learned,
                                       const std::vector<SpectrumGroup>& analytic);

}  // namespace sgnlf::spectral
