#include "window_solver.hpp"

#include "odometry_factor.hpp"
#include "plane_factor.hpp"
#include "prior_factors.hpp"
#include "room_factor.hpp"

#include <ceres/ceres.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <chrono>
#include <cmath>
#include <map>
#include <set>

namespace bimloc::sgraph::detail {
namespace {

constexpr double kDeg = M_PI / 180.0;

// How well the window knows where the robot is now: the newest pose's block of the inverse
// Gauss-Newton Hessian J'J (robust kernels applied, tangent space of each block), from the
// Jacobian Ceres evaluates in the order given here. Ceres' own Covariance orders the blocks by
// their addresses in memory, which differ from run to run, and the result then differed in
// its last digits; this order does not. Unset when J'J is rank deficient.
std::optional<Eigen::Matrix3d> newestCovariance(ceres::Problem& problem, const std::vector<double*>& blocks) {
  ceres::Problem::EvaluateOptions options;
  options.parameter_blocks = blocks;
  options.num_threads = 1;
  ceres::CRSMatrix crs;
  if (!problem.Evaluate(options, nullptr, nullptr, nullptr, &crs)) return std::nullopt;
  // Sparse, as the solve is: the window's walls bring in the rooms along them with all their
  // walls (a corridor wall of a 600-room floor, 150 offices), and a dense J'J of 2 000 columns
  // was 97 % of the tracking's CPU there (3.4-15x real time, against 110x on the default world).
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(crs.values.size());
  for (int r = 0; r < crs.num_rows; ++r)
    for (int k = crs.rows[static_cast<std::size_t>(r)]; k < crs.rows[static_cast<std::size_t>(r) + 1]; ++k)
      entries.emplace_back(r, crs.cols[static_cast<std::size_t>(k)], crs.values[static_cast<std::size_t>(k)]);
  Eigen::SparseMatrix<double> J(crs.num_rows, crs.num_cols);
  J.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SparseMatrix<double> H = Eigen::SparseMatrix<double>(J.transpose()) * J;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(H);
  if (ldlt.info() != Eigen::Success) return std::nullopt;
  const Eigen::VectorXd pivots = ldlt.vectorD();
  if (pivots.size() < 3 || pivots.minCoeff() <= 1e-12 * std::max(pivots.maxCoeff(), 1e-300)) return std::nullopt;
  // The newest pose comes first in `blocks`: its covariance is the top-left 3x3 of H^-1.
  const Eigen::MatrixXd columns = ldlt.solve(Eigen::MatrixXd::Identity(H.rows(), 3));
  Eigen::Matrix3d covariance = columns.topRows<3>();
  return Eigen::Matrix3d(0.5 * (covariance + covariance.transpose()));
}

// Whether the newest keyframe's correction carried the plan walls it sees along with it: across
// every seen wall the robot moved by more than 3 sigma of the wall priors, that wall moved in
// this solve the same way, by at least half as much and more than 3 sigma. The walls then no
// longer say where the robot is: the robust (Cauchy) priors let the few walls that hold an axis
// go, and the window slid with them into another basin (AC90R1-Jasmin-Sun, Erdgeschoss/101 seed
// 2 of a multi-storey tour: walls 1 and 3, the only x walls in view, and the robot 0.35 m in
// one keyframe while turning in place, then 0.1 m more: a false convergence). A correction
// the plan makes moves the robot against its walls, not with them.
bool carriedItsWalls(const Graph& g, const Keyframe& newest, const std::set<int>& nodes, const std::vector<std::array<double, 3>>& before,
                     const SGraphConfig& c) {
  const Eigen::Vector2d move = (newest.planar() - newest.predicted).head<2>();
  const double bar_m = 3.0 * c.wall_prior_sigma_m;
  if (!(move.norm() > bar_m)) return false;
  std::map<int, double> shifted;  // node -> the change of its shift s (along faces[0]'s normal e) in this solve
  std::size_t i = 0;
  for (int n : nodes) shifted[n] = g.nodes[static_cast<std::size_t>(n)].params[0] - before[i++][0];
  int across = 0, carried = 0;
  std::set<int> seen;
  for (const PlaneMeasurement& m : newest.planes) {
    const WallNode& node = g.nodes[static_cast<std::size_t>(m.node)];
    if (node.kind != WallNode::Kind::Plan || !node.active || !seen.insert(m.node).second) continue;
    const double robot = move.dot(node.face[0].e);  // the robot's move across the wall
    if (!(std::abs(robot) > bar_m)) continue;
    ++across;
    const auto it = shifted.find(m.node);
    const double wall = it == shifted.end() ? 0.0 : it->second;
    if (wall * robot > 0 && std::abs(wall) >= 0.5 * std::abs(robot) && std::abs(wall) > bar_m) ++carried;
  }
  return across > 0 && carried == across;
}

// A plan wall's rotation about its centre (alpha) moves its ends by alpha L / 2. An as-built
// tolerance is on where a wall stands, at its ends as at its middle, so a long wall's angle is
// known to sigma_m over half its length, and never worse than wall_prior_sigma_deg. Without the
// bound, a 57 m wall seen near one end turned 1.4 deg to fit one grazing plane and carried the
// robot 0.55 m along the corridor with it (random school 98006, construction site, R007).
double wallAngleSigma(const WallNode& node, const SGraphConfig& c) {
  const double half_length_m = 0.5 * std::max(node.length(0), node.length(1));
  const double by_angle = c.wall_prior_sigma_deg * kDeg;
  return half_length_m > 0.0 ? std::min(by_angle, c.wall_prior_sigma_m / half_length_m) : by_angle;
}

}  // namespace

Eigen::Vector3d odometrySigma(const Keyframe& a, const Keyframe& b, const SGraphConfig& c) {
  if (b.odometry_jump) return {c.odometry_jump_m, c.odometry_jump_m, c.odometry_jump_deg * kDeg};
  const Eigen::Vector3d u = between(a.odom, b.odom);
  const double distance = u.head<2>().norm(), turn = std::abs(u.z());
  const double xy = c.odometry_sigma_xy_floor_m + c.odometry_sigma_xy_per_m * distance;
  const double yaw = c.odometry_sigma_yaw_floor_deg * kDeg + c.odometry_sigma_yaw_per_rad * turn + c.odometry_sigma_yaw_per_m_deg * kDeg * distance;
  return {xy, xy, yaw};
}

ceres::CostFunction* odometryCost(const Keyframe& a, const Keyframe& b, const SGraphConfig& c) {
  return OdometryFactor::create(between(a.odom, b.odom), odometrySigma(a, b, c));
}

ceres::CostFunction* planeCost(const Graph& g, const Keyframe& kf, const PlaneMeasurement& m) {
  const WallNode& node = g.nodes[static_cast<std::size_t>(m.node)];
  return PlaneFactor::create(node.face[m.face], kf.A, kf.b, m.minimal, m.sqrt_information);
}

std::vector<double> planeResiduals2(const Graph& g, const Keyframe& kf) {
  std::vector<double> out;
  for (const PlaneMeasurement& m : kf.planes) {
    const WallNode& node = g.nodes[static_cast<std::size_t>(m.node)];
    const PlaneFactor factor(node.face[m.face], kf.A, kf.b, m.minimal, m.sqrt_information);
    double r[3];
    factor(kf.pose.data(), node.params.data(), r);
    out.push_back(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  }
  return out;
}

SolveReport optimizeWindow(Graph& g, const SGraphConfig& c) {
  SolveReport report;
  if (g.window.empty()) return report;
  ceres::Problem problem;
  // One kernel object per kind: the problem owns them and deletes each once.
  ceres::LossFunction* huber_plane = new ceres::HuberLoss(c.huber_plane_sigmas);
  ceres::LossFunction* huber_odometry = new ceres::HuberLoss(c.huber_odometry_sigmas);
  ceres::LossFunction* cauchy_wall = new ceres::CauchyLoss(c.cauchy_wall_prior_sigmas);
  ceres::LossFunction* huber_room = new ceres::HuberLoss(c.huber_room_sigmas);

  // Tracking layer: the window's keyframes, odometry between them.
  for (Keyframe& kf : g.window) problem.AddParameterBlock(kf.pose.data(), 3);
  for (std::size_t i = 0; i + 1 < g.window.size(); ++i)
    problem.AddResidualBlock(odometryCost(g.window[i], g.window[i + 1], c), huber_odometry, g.window[i].pose.data(),
                             g.window[i + 1].pose.data());

  // Keyframe-plane factors, and the wall nodes they reach.
  std::set<int> nodes;
  for (Keyframe& kf : g.window) {
    for (const PlaneMeasurement& m : kf.planes) {
      WallNode& node = g.nodes[static_cast<std::size_t>(m.node)];
      if (!node.active) continue;
      problem.AddResidualBlock(planeCost(g, kf, m), huber_plane, kf.pose.data(), node.params.data());
      nodes.insert(m.node);
    }
  }
  // Topological layer: the rooms of those walls, with all their walls.
  std::set<int> rooms;
  for (int n : nodes)
    for (int r : g.nodes[static_cast<std::size_t>(n)].rooms) rooms.insert(r);
  for (int r : rooms) {
    RoomData& room = g.rooms[static_cast<std::size_t>(r)];
    for (const FaceRef& f : room.pairs) nodes.insert(f.node);
    problem.AddResidualBlock(GaussianPrior<2>::create(room.plan_centre, Eigen::Matrix2d::Identity() / c.room_prior_sigma_m), nullptr,
                             room.centre.data());
    std::vector<FaceGeometry> faces;
    std::vector<double*> blocks{room.centre.data()};
    for (const FaceRef& f : room.pairs) {
      faces.push_back(g.nodes[static_cast<std::size_t>(f.node)].face[f.face]);
      blocks.push_back(g.nodes[static_cast<std::size_t>(f.node)].params.data());
    }
    if (room.corridor)
      problem.AddResidualBlock(CorridorFactor::create({faces[0], faces[1]}, c.room_factor_sigma_m), huber_room, blocks);
    else
      problem.AddResidualBlock(RoomFactor::create({faces[0], faces[1], faces[2], faces[3]}, c.room_factor_sigma_m), huber_room, blocks);
  }
  // What the marginalized keyframes said, on the oldest keyframe and the walls they saw.
  if (g.prior.J.rows() > 0) {
    std::vector<double*> blocks{g.window.front().pose.data()};
    for (int n : g.prior.nodes) {
      blocks.push_back(g.nodes[static_cast<std::size_t>(n)].params.data());
      nodes.insert(n);
    }
    problem.AddResidualBlock(new MarginalPriorFactor(g.prior), nullptr, blocks);
  }
  // Metric-semantic layer: plan walls at their as-built tolerance (never marginalized: they
  // are the map's own knowledge, not the keyframes'); a new plane has one face and no thickness.
  for (int n : nodes) {
    WallNode& node = g.nodes[static_cast<std::size_t>(n)];
    if (node.kind == WallNode::Kind::Plan) {
      problem.AddResidualBlock(WallPrior::create(c.wall_prior_sigma_m, wallAngleSigma(node, c)), cauchy_wall, node.params.data());
      problem.AddResidualBlock(ThicknessPrior::create(c.wall_thickness_sigma_m), nullptr, node.params.data());
    } else {
      problem.SetManifold(node.params.data(), new ceres::SubsetManifold(3, {2}));
    }
  }

  // Keep the state to restore it if the solver fails.
  std::vector<std::array<double, 3>> poses, params;
  for (const Keyframe& kf : g.window) poses.push_back(kf.pose);
  for (int n : nodes) params.push_back(g.nodes[static_cast<std::size_t>(n)].params);

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE) ||
                                       ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::EIGEN_SPARSE)
                                   ? ceres::SPARSE_NORMAL_CHOLESKY
                                   : ceres::DENSE_QR;
  options.max_num_iterations = std::max(1, c.max_iterations);
  options.num_threads = 1;  // same input, same output
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  const auto t0 = std::chrono::steady_clock::now();
  ceres::Solve(options, &problem, &summary);
  report.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  report.iterations = static_cast<int>(summary.iterations.size()) - 1;
  report.initial_cost = summary.initial_cost;
  report.final_cost = summary.final_cost;
  bool finite = std::isfinite(summary.final_cost);
  for (const Keyframe& kf : g.window) finite = finite && std::isfinite(kf.pose[0] + kf.pose[1] + kf.pose[2]);
  for (int n : nodes) {
    const auto& p = g.nodes[static_cast<std::size_t>(n)].params;
    finite = finite && std::isfinite(p[0] + p[1] + p[2]);
  }
  // A solution that carries the newest keyframe farther from its odometry prediction than the
  // loss check allows moved the window's keyframes and their walls together: the walls' plan
  // priors are robust (Cauchy), so when few walls hold an axis, the robot and those walls can
  // slide together into another basin (SampleHouse4: its two x walls and the robot, 0.65 m in
  // one keyframe, while turning in place). The odometry says the robot did not move so: the
  // estimate is kept and the keyframe counts as bad (loss_monitor.cpp).
  const Keyframe& newest = g.window.back();
  const double correction = (newest.planar() - newest.predicted).head<2>().norm();
  const bool jumped = finite && !newest.odometry_jump && correction > c.loss_correction_m;
  const bool slid = finite && !jumped && !newest.odometry_jump && carriedItsWalls(g, newest, nodes, params, c);
  if (!summary.IsSolutionUsable() || !finite || jumped || slid) {
    report.usable = false;
    report.message = jumped ? "it moved the keyframe " + std::to_string(correction).substr(0, 4) + " m from its odometry prediction"
                     : slid ? "it moved the keyframe " + std::to_string(correction).substr(0, 4) + " m with the plan walls it sees"
                            : summary.message;
    std::size_t i = 0;
    for (Keyframe& kf : g.window) kf.pose = poses[i++];
    i = 0;
    for (int n : nodes) g.nodes[static_cast<std::size_t>(n)].params = params[i++];
    return report;
  }
  std::vector<double*> blocks{g.window.back().pose.data()};
  for (std::size_t i = 0; i + 1 < g.window.size(); ++i) blocks.push_back(g.window[i].pose.data());
  for (int n : nodes) blocks.push_back(g.nodes[static_cast<std::size_t>(n)].params.data());
  for (int r : rooms) blocks.push_back(g.rooms[static_cast<std::size_t>(r)].centre.data());
  report.newest_covariance = newestCovariance(problem, blocks);
  for (Keyframe& kf : g.window) kf.pose[2] = wrapAngle(kf.pose[2]);
  return report;
}

}  // namespace bimloc::sgraph::detail
