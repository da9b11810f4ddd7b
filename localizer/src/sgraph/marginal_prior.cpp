#include "marginal_prior.hpp"

#include "wall_geometry.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace bimloc::sgraph::detail {
namespace {

// x [-] x0: the keyframe's heading is an angle, the nodes' parameters are small offsets.
Eigen::VectorXd difference(const Eigen::VectorXd& x, const Eigen::VectorXd& x0) {
  Eigen::VectorXd dx = x - x0;
  dx[2] = wrapAngle(dx[2]);
  return dx;
}

}  // namespace

Eigen::VectorXd MarginalPrior::residual(const Eigen::VectorXd& x) const { return r0 + J * difference(x, x0); }

MarginalPrior posePrior(const Eigen::Vector3d& mean, const Eigen::Vector3d& sigma) {
  MarginalPrior p;
  p.x0 = mean;
  p.J = sigma.cwiseInverse().asDiagonal();
  p.r0 = Eigen::Vector3d::Zero();
  return p;
}

MarginalPrior priorFromInformation(const Eigen::MatrixXd& H, const Eigen::VectorXd& b, const Eigen::VectorXd& x0,
                                   std::vector<int> nodes, double relative_floor) {
  // H = V L V': J = sqrt(L) V', r0 = sqrt(L)^-1 V' b, so that J'J = H and J'r0 = b on the kept
  // directions (an eigen-decomposition rather than a Cholesky factor: a wall seen from one side
  // says nothing of its thickness, and H is then singular in that direction).
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(0.5 * (H + H.transpose()));
  const Eigen::VectorXd& lambda = eigen.eigenvalues();
  const double floor = relative_floor * std::max(lambda.maxCoeff(), 0.0);
  int kept = 0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) kept += lambda[i] > floor && lambda[i] > 0;
  MarginalPrior p;
  p.nodes = std::move(nodes);
  p.x0 = x0;
  p.J.resize(kept, H.cols());
  p.r0.resize(kept);
  int row = 0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    if (!(lambda[i] > floor && lambda[i] > 0)) continue;
    const double s = std::sqrt(lambda[i]);
    const Eigen::VectorXd v = eigen.eigenvectors().col(i);
    p.J.row(row) = s * v.transpose();
    p.r0[row] = v.dot(b) / s;
    ++row;
  }
  return p;
}

void eliminate(Eigen::MatrixXd& H, Eigen::VectorXd& b, int begin, int size) {
  const int n = static_cast<int>(H.rows()), end = begin + size;
  std::vector<int> keep;
  for (int i = 0; i < n; ++i)
    if (i < begin || i >= end) keep.push_back(i);
  const int k = static_cast<int>(keep.size());
  Eigen::MatrixXd Hkk(k, k), Hkm(k, size);
  Eigen::VectorXd bk(k);
  for (int i = 0; i < k; ++i) {
    bk[i] = b[keep[i]];
    for (int j = 0; j < k; ++j) Hkk(i, j) = H(keep[i], keep[j]);
    for (int j = 0; j < size; ++j) Hkm(i, j) = H(keep[i], begin + j);
  }
  const Eigen::MatrixXd Hmm = H.block(begin, begin, size, size);
  const Eigen::VectorXd bm = b.segment(begin, size);
  // A direction of the eliminated block nothing constrains carries nothing to the others: the
  // pseudo-inverse (eigen-decomposition) rather than an inverse that would blow it up.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(0.5 * (Hmm + Hmm.transpose()));
  const double floor = 1e-12 * std::max(eigen.eigenvalues().maxCoeff(), 1e-300);
  Eigen::VectorXd inverse = eigen.eigenvalues();
  for (Eigen::Index i = 0; i < inverse.size(); ++i) inverse[i] = inverse[i] > floor ? 1.0 / inverse[i] : 0.0;
  const Eigen::MatrixXd Hmm_inverse = eigen.eigenvectors() * inverse.asDiagonal() * eigen.eigenvectors().transpose();
  H = Hkk - Hkm * Hmm_inverse * Hkm.transpose();
  H = 0.5 * (H + H.transpose());
  b = bk - Hkm * Hmm_inverse * bm;
}

MarginalPriorFactor::MarginalPriorFactor(const MarginalPrior& prior) : prior_(prior) {
  set_num_residuals(static_cast<int>(prior_.J.rows()));
  mutable_parameter_block_sizes()->assign(1 + prior_.nodes.size(), 3);
}

bool MarginalPriorFactor::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const int n = prior_.dimension(), m = static_cast<int>(prior_.J.rows());
  Eigen::VectorXd x(n);
  for (int block = 0; block < n / 3; ++block)
    for (int i = 0; i < 3; ++i) x[3 * block + i] = parameters[block][i];
  Eigen::Map<Eigen::VectorXd>(residuals, m) = prior_.residual(x);
  if (jacobians == nullptr) return true;
  for (int block = 0; block < n / 3; ++block) {
    if (jacobians[block] == nullptr) continue;
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(jacobians[block], m, 3) = prior_.J.middleCols(3 * block, 3);
  }
  return true;
}

}  // namespace bimloc::sgraph::detail
