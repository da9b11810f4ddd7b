#include "marginalization.hpp"

#include "prior_factors.hpp"
#include "window_solver.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <memory>

namespace bimloc::sgraph::detail {
namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct Linearized {
  Eigen::VectorXd r;
  std::vector<Eigen::MatrixXd> J;  // one per parameter block
};

// Residual and Jacobians of a cost function at `blocks`, with a Huber kernel of scale `huber`
// (0: none) applied as a weight sqrt(rho'(|r|^2)) on both (iteratively reweighted least squares).
Linearized linearize(const ceres::CostFunction& cost, const std::vector<double*>& blocks, double huber) {
  const int m = cost.num_residuals();
  Linearized out;
  out.r.resize(m);
  std::vector<RowMatrix> jacobians;
  std::vector<double*> pointers;
  for (int size : cost.parameter_block_sizes()) jacobians.emplace_back(m, size);
  for (auto& j : jacobians) pointers.push_back(j.data());
  cost.Evaluate(blocks.data(), out.r.data(), pointers.data());
  double w = 1.0;
  const double s = out.r.squaredNorm();
  if (huber > 0 && s > huber * huber) w = std::sqrt(huber / std::sqrt(s));
  out.r *= w;
  for (auto& j : jacobians) out.J.emplace_back(w * j);
  return out;
}

void capEvidence(WallNode& node, const SGraphConfig& c) {
  const double cap_m = 1.0 / std::pow(c.wall_evidence_min_sigma_m, 2), cap_rad = 1.0 / std::pow(c.wall_evidence_min_sigma_deg * M_PI / 180.0, 2);
  const Eigen::Matrix3d& H = node.evidence_information;
  double scale = 1.0;
  if (H(0, 0) > cap_m) scale = std::min(scale, cap_m / H(0, 0));
  if (H(1, 1) > cap_rad) scale = std::min(scale, cap_rad / H(1, 1));
  if (H(2, 2) > cap_m) scale = std::min(scale, cap_m / H(2, 2));
  node.evidence_information *= scale;  // the same mean, less certain
  node.evidence_vector *= scale;
}

}  // namespace

void marginalizeOldest(Graph& g, const SGraphConfig& c) {
  if (g.window.size() < 2) return;
  Keyframe& k0 = g.window[0];
  Keyframe& k1 = g.window[1];
  Eigen::Matrix3d H00 = Eigen::Matrix3d::Zero(), H01 = Eigen::Matrix3d::Zero(), H11 = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b0 = Eigen::Vector3d::Zero(), b1 = Eigen::Vector3d::Zero();

  const std::unique_ptr<ceres::CostFunction> prior(PosePrior::create(g.anchor_mean, g.anchor_sqrt_information));
  const Linearized a = linearize(*prior, {k0.pose.data()}, 0.0);
  H00 += a.J[0].transpose() * a.J[0];
  b0 += a.J[0].transpose() * a.r;

  const std::unique_ptr<ceres::CostFunction> odometry(odometryCost(k0, k1, c));
  const Linearized o = linearize(*odometry, {k0.pose.data(), k1.pose.data()}, c.huber_odometry_sigmas);
  H00 += o.J[0].transpose() * o.J[0];
  H01 += o.J[0].transpose() * o.J[1];
  H11 += o.J[1].transpose() * o.J[1];
  b0 += o.J[0].transpose() * o.r;
  b1 += o.J[1].transpose() * o.r;

  struct PlaneTerm {
    int node;
    Linearized lin;
  };
  std::vector<PlaneTerm> planes;
  for (const PlaneMeasurement& m : k0.planes) {
    WallNode& node = g.nodes[static_cast<std::size_t>(m.node)];
    if (!node.active) continue;
    const std::unique_ptr<ceres::CostFunction> cost(planeCost(g, k0, m));
    planes.push_back({m.node, linearize(*cost, {k0.pose.data(), node.params.data()}, c.huber_plane_sigmas)});
    const Linearized& l = planes.back().lin;
    H00 += l.J[0].transpose() * l.J[0];
    b0 += l.J[0].transpose() * l.r;
  }

  // Schur complement of k0: the prior of k1, centred where the eliminated factors put it.
  const Eigen::Matrix3d H00_inverse = (H00 + 1e-12 * Eigen::Matrix3d::Identity()).inverse();
  Eigen::Matrix3d H = H11 - H01.transpose() * H00_inverse * H01;
  const Eigen::Vector3d b = b1 - H01.transpose() * H00_inverse * b0;
  H = 0.5 * (H + H.transpose()) + 1e-9 * Eigen::Matrix3d::Identity();
  const Eigen::LLT<Eigen::Matrix3d> llt(H);
  if (llt.info() == Eigen::Success) {
    Eigen::Vector3d mean = k1.planar() - llt.solve(b);
    mean.z() = wrapAngle(mean.z());
    g.anchor_mean = mean;
    g.anchor_sqrt_information = llt.matrixL().transpose();
  } else {  // cannot happen with a positive odometry sigma; keep k1 where it is, loosely
    g.anchor_mean = k1.planar();
    g.anchor_sqrt_information = Eigen::Vector3d(1.0 / c.initial_sigma_xy_m, 1.0 / c.initial_sigma_xy_m,
                                                1.0 / (c.initial_sigma_yaw_deg * M_PI / 180.0)).asDiagonal();
  }

  // Each plane factor into its wall's evidence, with the keyframe's uncertainty added to it:
  // the uncertainty the keyframe has without this very factor (its prior, its odometry link,
  // its other walls), so that the measurement does not vouch for itself.
  for (const PlaneTerm& t : planes) {
    WallNode& node = g.nodes[static_cast<std::size_t>(t.node)];
    const Eigen::Matrix3d H_others = H00 - t.lin.J[0].transpose() * t.lin.J[0] + 1e-12 * Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d C = Eigen::Matrix3d::Identity() + t.lin.J[0] * H_others.inverse() * t.lin.J[0].transpose();
    const Eigen::Matrix3d W = C.inverse();
    const Eigen::Matrix3d& J = t.lin.J[1];
    const Eigen::Vector3d theta(node.params[0], node.params[1], node.params[2]);
    node.evidence_information += J.transpose() * W * J;
    node.evidence_vector += J.transpose() * W * (J * theta - t.lin.r);
    capEvidence(node, c);
  }

  KeyframeInfo& info = g.history[static_cast<std::size_t>(k0.id)];
  info.T_map_base = k0.T_map_base();
  info.in_window = false;
  g.window.pop_front();
}

}  // namespace bimloc::sgraph::detail
