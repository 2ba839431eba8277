// Rayleigh–Ritz readout, folding into the last layer, group comparison (rayleigh_ritz.hpp).
#include "spectral/rayleigh_ritz.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "core/error.hpp"

namespace sgnlf::spectral {

RitzResult rayleigh_ritz(const Eigen::MatrixXd& S, const Eigen::MatrixXd& P,
                         const Eigen::VectorXd& mean) {
  require(S.rows() == S.cols() && P.rows() == S.rows() && P.cols() == S.cols() &&
              mean.size() == S.rows(),
          "rayleigh_ritz: S, P must be K×K and mean K");
  const Eigen::MatrixXd Ss = 0.5 * (S + S.transpose()), Ps = 0.5 * (P + P.transpose());
  Eigen::LLT<Eigen::MatrixXd> llt(Ss);
  if (llt.info() != Eigen::Success) throw NumericError("rayleigh_ritz: S is not positive definite");
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Ps, Ss);
  if (es.info() != Eigen::Success) throw NumericError("rayleigh_ritz: eigensolver failed");
  RitzResult r;
  r.eigenvalues = es.eigenvalues();  // ascending; eigenvectors normalised so that CᵀSC = I
  r.C = es.eigenvectors();
  r.mean = mean;
  return r;
}

void fold_readout(const RitzResult& ritz, std::vector<float>& W, std::vector<float>& b, int hidden) {
  const int k = int(ritz.C.rows());
  require(W.size() == size_t(k) * hidden && b.size() == size_t(k), "fold_readout: W must be K×H, b K");
  Eigen::MatrixXd Wd = Eigen::Map<Eigen::Matrix<float, -1, -1, Eigen::RowMajor>>(W.data(), k, hidden)
                           .cast<double>();
  Eigen::VectorXd bd = Eigen::Map<Eigen::VectorXf>(b.data(), k).cast<double>();
  const Eigen::MatrixXd W2 = ritz.C.transpose() * Wd;
  const Eigen::VectorXd b2 = ritz.C.transpose() * (bd - ritz.mean);
  Eigen::Map<Eigen::Matrix<float, -1, -1, Eigen::RowMajor>>(W.data(), k, hidden) = W2.cast<float>();
  Eigen::Map<Eigen::VectorXf>(b.data(), k) = b2.cast<float>();
}

std::vector<GroupError> compare_groups(const Eigen::VectorXd& learned,
                                       const std::vector<SpectrumGroup>& analytic) {
  std::vector<GroupError> out;
  int pos = 0;
  for (const auto& g : analytic) {
    if (pos >= learned.size()) break;
    GroupError e;
    e.analytic = g.value;
    e.multiplicity = g.multiplicity;
    double sum = 0;
    for (int i = 0; i < g.multiplicity && pos < learned.size(); ++i, ++pos, ++e.used) sum += learned[pos];
    e.learned_mean = sum / e.used;
    e.rel_err = std::fabs(e.learned_mean - g.value) / g.value;
    out.push_back(e);
  }
  return out;
}

}  // namespace sgnlf::spectral
