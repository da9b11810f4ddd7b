#include "sim/metrics/umeyama.hpp"

#include <Eigen/SVD>

#include <limits>
#include <stdexcept>
#include <string>

namespace bimloc::sim {

Similarity umeyama(const Eigen::Matrix3Xd& from, const Eigen::Matrix3Xd& to, bool with_scale) {
  const auto n = from.cols();
  if (n != to.cols()) throw std::invalid_argument("Umeyama alignment: point sets of different sizes");
  if (n < 2) throw std::invalid_argument("Umeyama alignment needs at least 2 poses, got " + std::to_string(n));
  const Eigen::Vector3d mean_x = from.rowwise().mean(), mean_y = to.rowwise().mean();  // eqs. 34, 35
  const Eigen::Matrix3Xd x = from.colwise() - mean_x, y = to.colwise() - mean_y;
  const double sigma_x = x.squaredNorm() / static_cast<double>(n);                       // eq. 36
  const Eigen::Matrix3d cov = y * x.transpose() / static_cast<double>(n);                // eq. 38
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d d = svd.singularValues();
  int rank = 0;
  for (int i = 0; i < 3; ++i) rank += d[i] > std::numeric_limits<double>::epsilon();
  if (rank < 2)
    throw std::invalid_argument("Umeyama alignment is not possible: the associated positions are degenerate (on a line or a "
                                "point), the rotation is undetermined; use --align none");
  Eigen::Matrix3d s = Eigen::Matrix3d::Identity();  // eq. 43: a rotation, never a reflection
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0) s(2, 2) = -1;
  Similarity out;
  out.rotation = svd.matrixU() * s * svd.matrixV().transpose();  // eq. 40
  out.scale = with_scale ? (d.asDiagonal() * s).trace() / sigma_x : 1.0;  // eq. 42
  out.translation = mean_y - out.scale * out.rotation * mean_x;  // eq. 41
  return out;
}

}  // namespace bimloc::sim
