#include "marginalization.hpp"

#include "window_solver.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>

namespace bimloc::sgraph::detail {
namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The normal equations of the factors being eliminated: 1/2 dx'H dx + b'dx over the blocks
// (x, y, yaw) of k0 and k1, then (s, alpha, tau) of each node, at the current estimate.
struct System {
  std::vector<int> nodes;
  Eigen::MatrixXd H;
  Eigen::VectorXd b;

  int offset(int node) {  // the node's block, added when new
    const auto it = std::find(nodes.begin(), nodes.end(), node);
    if (it != nodes.end()) return 6 + 3 * static_cast<int>(it - nodes.begin());
    nodes.push_back(node);
    const auto n = static_cast<Eigen::Index>(6 + 3 * nodes.size());
    H.conservativeResizeLike(Eigen::MatrixXd::Zero(n, n));
    b.conservativeResizeLike(Eigen::VectorXd::Zero(n));
    return static_cast<int>(n) - 3;
  }

  // Adds r'r/2 of a residual r with Jacobian blocks J_i at offsets o_i.
  void add(const Eigen::VectorXd& r, const std::vector<Eigen::MatrixXd>& J, const std::vector<int>& offsets) {
    for (std::size_t i = 0; i < J.size(); ++i) {
      b.segment(offsets[i], J[i].cols()) += J[i].transpose() * r;
      for (std::size_t j = 0; j < J.size(); ++j) H.block(offsets[i], offsets[j], J[i].cols(), J[j].cols()) += J[i].transpose() * J[j];
    }
  }
};

// Residual and Jacobians of a cost function at `blocks`, with a Huber kernel of scale `huber`
// applied as a weight sqrt(rho'(|r|^2)) on both (iteratively reweighted least squares).
void addFactor(System& s, const ceres::CostFunction& cost, const std::vector<double*>& blocks, const std::vector<int>& offsets,
               double huber) {
  const int m = cost.num_residuals();
  Eigen::VectorXd r(m);
  std::vector<RowMatrix> jacobians;
  std::vector<double*> pointers;
  for (int size : cost.parameter_block_sizes()) jacobians.emplace_back(m, size);
  for (auto& j : jacobians) pointers.push_back(j.data());
  if (!cost.Evaluate(blocks.data(), r.data(), pointers.data()) || !r.allFinite()) return;
  double w = 1.0;
  const double norm = r.norm();
  if (norm > huber) w = std::sqrt(huber / norm);
  std::vector<Eigen::MatrixXd> J;
  for (auto& j : jacobians) J.emplace_back(w * j);
  s.add(w * r, J, offsets);
}

// Beyond the bound, the walls the window no longer sees leave the prior, least recently seen
// first; merged (inactive) nodes always do.
void forgetWalls(Graph& g, System& s, const SGraphConfig& c) {
  std::set<int> in_window;
  for (const Keyframe& kf : g.window)
    for (const PlaneMeasurement& m : kf.planes) in_window.insert(m.node);
  const auto drop = [&](std::size_t i) {
    eliminate(s.H, s.b, 3 + 3 * static_cast<int>(i), 3);
    s.nodes.erase(s.nodes.begin() + static_cast<std::ptrdiff_t>(i));
  };
  for (std::size_t i = s.nodes.size(); i-- > 0;)
    if (!g.nodes[static_cast<std::size_t>(s.nodes[i])].active) drop(i);
  while (static_cast<int>(s.nodes.size()) > c.prior_max_walls) {
    std::size_t oldest = s.nodes.size();
    for (std::size_t i = 0; i < s.nodes.size(); ++i) {
      if (in_window.count(s.nodes[i])) continue;
      if (oldest == s.nodes.size() || g.nodes[static_cast<std::size_t>(s.nodes[i])].last_keyframe <
                                          g.nodes[static_cast<std::size_t>(s.nodes[oldest])].last_keyframe)
        oldest = i;
    }
    if (oldest == s.nodes.size()) break;  // all seen by the window: the window bounds them
    drop(oldest);
  }
}

}  // namespace

void marginalizeOldest(Graph& g, const SGraphConfig& c) {
  if (g.window.size() < 2) return;
  Keyframe& k0 = g.window[0];
  Keyframe& k1 = g.window[1];
  System s;
  s.H = Eigen::MatrixXd::Zero(6, 6);
  s.b = Eigen::VectorXd::Zero(6);

  // The prior, on k0 and its nodes: linear already, J'J and J'r at the current estimate.
  const MarginalPrior& prior = g.prior;
  std::vector<int> offsets{0};
  std::vector<double*> blocks{k0.pose.data()};
  for (int node : prior.nodes) {
    offsets.push_back(s.offset(node));
    blocks.push_back(g.nodes[static_cast<std::size_t>(node)].params.data());
  }
  if (prior.J.rows() > 0) {
    std::vector<Eigen::MatrixXd> J;
    for (std::size_t i = 0; i < blocks.size(); ++i) J.emplace_back(prior.J.middleCols(3 * static_cast<Eigen::Index>(i), 3));
    Eigen::VectorXd x(prior.dimension());
    for (std::size_t i = 0; i < blocks.size(); ++i) x.segment<3>(3 * static_cast<Eigen::Index>(i)) = Eigen::Vector3d(blocks[i]);
    s.add(prior.residual(x), J, offsets);
  }
  // Its odometry link and its plane factors.
  const std::unique_ptr<ceres::CostFunction> odometry(odometryCost(k0, k1, c));
  addFactor(s, *odometry, {k0.pose.data(), k1.pose.data()}, {0, 3}, c.huber_odometry_sigmas);
  for (const PlaneMeasurement& m : k0.planes) {
    WallNode& node = g.nodes[static_cast<std::size_t>(m.node)];
    if (!node.active) continue;
    const std::unique_ptr<ceres::CostFunction> cost(planeCost(g, k0, m));
    const int offset = s.offset(m.node);
    addFactor(s, *cost, {k0.pose.data(), node.params.data()}, {0, offset}, c.huber_plane_sigmas);
  }

  eliminate(s.H, s.b, 0, 3);  // k0 leaves: k1 is now the first block, the nodes follow
  forgetWalls(g, s, c);
  Eigen::VectorXd x0(3 + 3 * static_cast<Eigen::Index>(s.nodes.size()));
  x0.head<3>() = k1.planar();
  for (std::size_t i = 0; i < s.nodes.size(); ++i)
    x0.segment<3>(3 + 3 * static_cast<Eigen::Index>(i)) = Eigen::Vector3d(g.nodes[static_cast<std::size_t>(s.nodes[i])].params.data());
  g.prior = priorFromInformation(s.H, s.b, x0, s.nodes);

  KeyframeInfo& info = g.history[static_cast<std::size_t>(k0.id)];
  info.T_map_base = k0.T_map_base();
  info.in_window = false;
  g.window.pop_front();
}

}  // namespace bimloc::sgraph::detail
