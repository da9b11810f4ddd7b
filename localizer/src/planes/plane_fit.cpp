// The least-squares plane of a support and what the particle filter needs to know of it:
// the minimal parameters (paper, Eq. plane_error) and their covariance.
#include "plane_steps.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace bimloc::planes::detail {
namespace {

// Floor of the residual standard deviation: a noise-free scan must not give a singular
// covariance (a perfect fit is not infinitely certain of the wall it stands for).
constexpr double kMinResidualSigma_m = 0.001;
// Variance given to a direction the points leave unconstrained, and the cap on every
// direction: an angle known to no better than +-pi carries no information.
constexpr double kUninformativeVariance = M_PI * M_PI;

// Covariance of (azimuth, elevation, d): sigma^2 (J^T J)^-1, J the Jacobian of the residuals
// r_i = n(az, el)·p_i + d with n = (cos el cos az, cos el sin az, sin el), i.e. the inverse
// Gauss-Newton Hessian of the fit, scaled by the residual variance.
Eigen::Matrix3d minimalCovariance(const Cloud& cloud, const Indices& support, const Eigen::Vector3d& n, double d) {
  const double az = std::atan2(n.y(), n.x()), el = std::asin(std::clamp(n.z(), -1.0, 1.0));
  const Eigen::Vector3d dn_daz(-std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), 0.0);
  const Eigen::Vector3d dn_del(-std::sin(el) * std::cos(az), -std::sin(el) * std::sin(az), std::cos(el));
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
  double sum_r2 = 0;
  for (const int i : support) {
    const Eigen::Vector3d p = cloud[i].cast<double>();
    const Eigen::Vector3d j(dn_daz.dot(p), dn_del.dot(p), 1.0);
    hessian += j * j.transpose();
    const double r = n.dot(p) + d;
    sum_r2 += r * r;
  }
  const double dof = std::max(1.0, double(support.size()) - 3.0);
  const double sigma2 = std::max(sum_r2 / dof, kMinResidualSigma_m * kMinResidualSigma_m);
  // Inverse through the eigenvectors, so that a direction without information (the azimuth of
  // a horizontal plane) gets a bounded variance instead of an overflow.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(hessian);
  Eigen::Vector3d variances;
  for (int k = 0; k < 3; ++k) {
    const double lambda = eig.eigenvalues()[k];
    variances[k] = lambda > 0 ? std::min(sigma2 / lambda, kUninformativeVariance) : kUninformativeVariance;
  }
  return eig.eigenvectors() * variances.asDiagonal() * eig.eigenvectors().transpose();
}

// The stretch along a plane where its support stands as a wall: u bins (one voxel wide) whose
// points span more than kStandingM of height. A 4 cm band around a wall also takes in the
// strip where it crosses a floor, a ceiling or a slab's edge, one height at each u, and a run
// bridges gaps of 0.5 m: past the wall's end, the extent can carry on over such a strip. A
// wall seen by two rings or more has points at several heights in every bin. When no bin does
// (a plane too far or too low for that), the whole extent [u_min, u_max].
constexpr double kStandingBinM = 0.1;
constexpr double kStandingM = 0.15;

std::pair<double, double> standingSpan(const Cloud& cloud, const Indices& support, const Eigen::Vector3d& h, double u_min,
                                       double u_max) {
  // The lowest and highest point of each bin along [u_min, u_max].
  const std::size_t n = static_cast<std::size_t>(std::floor((u_max - u_min) / kStandingBinM)) + 1;
  std::vector<std::pair<double, double>> heights(n, {INFINITY, -INFINITY});
  for (const int i : support) {
    const Eigen::Vector3d p = cloud[i].cast<double>();
    const std::size_t bin = std::min(n - 1, static_cast<std::size_t>(std::max(0.0, std::floor((h.dot(p) - u_min) / kStandingBinM))));
    heights[bin].first = std::min(heights[bin].first, p.z()), heights[bin].second = std::max(heights[bin].second, p.z());
  }
  double lo = INFINITY, hi = -INFINITY;
  for (std::size_t bin = 0; bin < n; ++bin)
    if (heights[bin].second - heights[bin].first > kStandingM) {
      const double u = u_min + static_cast<double>(bin) * kStandingBinM;
      lo = std::min(lo, u), hi = std::max(hi, std::min(u + kStandingBinM, u_max));
    }
  if (!(hi > lo)) return {u_min, u_max};
  return {lo, hi};
}

}  // namespace

PlaneFit fitPlane(const Cloud& cloud, const Indices& support) {
  PlaneFit fit;
  if (support.empty()) return fit;
  // One pass of first and second moments, in double about the first point (no cancellation:
  // the spread of a support is metres, its offset from the sensor tens of metres at most).
  const Eigen::Vector3d origin = cloud[support.front()].cast<double>();
  // The first moments in three scalars, not an Eigen 3-vector: its sum compiled to two scalar
  // stores read back by one 16-byte add, a failed store-to-load forwarding at every point (perf
  // annotate: nearly all of this loop's time). The same additions, in the same order.
  double sx = 0, sy = 0, sz = 0;
  // The second moments' six distinct entries (q_i q_j and q_j q_i are the same product): the
  // same sums as q q^T's nine, at two thirds of the work.
  double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
  for (const int i : support) {
    const Eigen::Vector3f& p = cloud[i];
    const double qx = double(p.x()) - origin.x(), qy = double(p.y()) - origin.y(), qz = double(p.z()) - origin.z();
    sx += qx, sy += qy, sz += qz;
    xx += qx * qx, xy += qx * qy, xz += qx * qz;
    yy += qy * qy, yz += qy * qz, zz += qz * qz;
  }
  const Eigen::Vector3d sum(sx, sy, sz);
  Eigen::Matrix3d sum2;
  sum2 << xx, xy, xz, xy, yy, yz, xz, yz, zz;
  const double n = double(support.size());
  fit.centroid = origin + sum / n;
  const Eigen::Matrix3d scatter = sum2 - sum * sum.transpose() / n;
  // Eigenvalues ascending: the first eigenvector is the direction of least spread.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  fit.normal = eig.eigenvectors().col(0).normalized();
  fit.d = -fit.normal.dot(fit.centroid);
  return fit;
}

ObservedPlane describePlane(const Cloud& cloud, const Indices& support, const PlaneFit& fit) {
  ObservedPlane plane;
  plane.normal = fit.normal;
  plane.d = fit.d;
  if (plane.d < 0) plane.normal = -plane.normal, plane.d = -plane.d;  // towards the sensor origin
  plane.centroid = fit.centroid;
  plane.inliers = static_cast<int>(support.size());
  if (support.empty()) return plane;

  const Eigen::Vector3d h = planeHorizontal(plane.normal);
  double u_min = INFINITY, u_max = -INFINITY, z_min = INFINITY, z_max = -INFINITY, sum_r2 = 0;
  for (const int i : support) {
    const Eigen::Vector3d p = cloud[i].cast<double>();
    u_min = std::min(u_min, h.dot(p)), u_max = std::max(u_max, h.dot(p));
    z_min = std::min(z_min, p.z()), z_max = std::max(z_max, p.z());
    const double r = plane.normal.dot(p) + plane.d;
    sum_r2 += r * r;
  }
  plane.extent_m = u_max - u_min;
  const auto [wall_lo, wall_hi] = standingSpan(cloud, support, h, u_min, u_max);
  plane.wall_span_m = wall_hi - wall_lo;
  plane.wall_span_middle = plane.centroid + h * (0.5 * (wall_lo + wall_hi) - h.dot(plane.centroid));
  plane.height_extent_m = z_max - z_min;
  plane.height_middle = plane.centroid + Eigen::Vector3d::UnitZ() * (0.5 * (z_min + z_max) - plane.centroid.z());
  plane.rms_m = std::sqrt(sum_r2 / double(support.size()));
  plane.covariance = minimalCovariance(cloud, support, plane.normal, plane.d);
  return plane;
}

}  // namespace bimloc::planes::detail

namespace bimloc::planes {

Eigen::Vector3d minimalPlane(const Eigen::Vector3d& normal, double d) {
  return {std::atan2(normal.y(), normal.x()), std::asin(std::clamp(normal.z(), -1.0, 1.0)), d};
}

}  // namespace bimloc::planes
