// The S-Graph's factors: each residual against an independent construction (the wall moved as
// a rigid body, the plane moved into the lidar frame with Eigen), each Jacobian against
// central differences, and the marginalization against the analytic propagation of a prior.
#include "sgraph_fixtures.hpp"

#include "sgraph/graph.hpp"
#include "sgraph/marginalization.hpp"
#include "sgraph/odometry_factor.hpp"
#include "sgraph/plan_layers.hpp"
#include "sgraph/plane_factor.hpp"
#include "sgraph/prior_factors.hpp"
#include "sgraph/room_factor.hpp"
#include "sgraph/window_solver.hpp"

#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

using namespace bimloc;
using namespace bimloc::sgraph::detail;

namespace {

constexpr double kDeg = M_PI / 180.0;
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Every Jacobian block of `cost` at `params` against central differences of its residuals.
void expectJacobiansMatchNumeric(const ceres::CostFunction& cost, std::vector<std::vector<double>> params) {
  const int m = cost.num_residuals();
  std::vector<double*> blocks;
  for (auto& p : params) blocks.push_back(p.data());
  std::vector<RowMatrix> J;
  std::vector<double*> jacobians;
  for (int size : cost.parameter_block_sizes()) J.emplace_back(m, size);
  for (auto& j : J) jacobians.push_back(j.data());
  Eigen::VectorXd r(m), plus(m), minus(m);
  ASSERT_TRUE(cost.Evaluate(blocks.data(), r.data(), jacobians.data()));
  for (std::size_t b = 0; b < params.size(); ++b) {
    for (std::size_t k = 0; k < params[b].size(); ++k) {
      const double h = 1e-6, keep = params[b][k];
      params[b][k] = keep + h;
      cost.Evaluate(blocks.data(), plus.data(), nullptr);
      params[b][k] = keep - h;
      cost.Evaluate(blocks.data(), minus.data(), nullptr);
      params[b][k] = keep;
      const Eigen::VectorXd numeric = (plus - minus) / (2 * h);
      for (int i = 0; i < m; ++i)
        EXPECT_NEAR(J[b](i, static_cast<Eigen::Index>(k)), numeric[i], 1e-5 * std::max(1.0, std::abs(numeric[i])))
            << "block " << b << " parameter " << k << " residual " << i;
    }
  }
  // And Ceres' own checker (its numeric differentiation, a second oracle): every block, the
  // relative error of each Jacobian entry.
  const ceres::NumericDiffOptions diff;
  const ceres::GradientChecker checker(&cost, static_cast<const std::vector<const ceres::Manifold*>*>(nullptr), diff);
  ceres::GradientChecker::ProbeResults results;
  EXPECT_TRUE(checker.Probe(blocks.data(), 1e-6, &results)) << results.error_log;
}

// A storey of one box room [0, 4] x [0, 5] with 0.2 m walls: S, E, N, W.
bim::Storey boxStorey() {
  bim::Storey s;
  s.walls = {test::boxWall("S", {-0.1, -0.1}, {4.1, -0.1}, 0.2), test::boxWall("E", {4.1, -0.1}, {4.1, 5.1}, 0.2),
             test::boxWall("N", {4.1, 5.1}, {-0.1, 5.1}, 0.2), test::boxWall("W", {-0.1, 5.1}, {-0.1, -0.1}, 0.2)};
  // Walls run counter-clockwise, so faces[0] (on the left) looks into the room.
  s.rooms = {test::boxRoom("R", 0, 0, 4, 5, {{"S", 0}, {"E", 0}, {"N", 0}, {"W", 0}})};
  return s;
}

Eigen::Isometry3d mount() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(3 * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
               Eigen::AngleAxisd(1 * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.2, 0.05, 0.45);
  return T;
}

Keyframe keyframeAt(double x, double y, double yaw, double roll_deg, double pitch_deg) {
  Keyframe kf;
  kf.pose = {x, y, yaw};
  kf.tilt = (Eigen::AngleAxisd(roll_deg * kDeg, Eigen::Vector3d::UnitX()) * Eigen::AngleAxisd(pitch_deg * kDeg, Eigen::Vector3d::UnitY()))
                .toRotationMatrix();
  kf.z_map = 0.55;
  kf.A = kf.tilt * mount().linear();
  kf.b = kf.tilt * mount().translation();
  return kf;
}

// Face k of wall `w` after moving the wall as a rigid body: turned by alpha about its centre,
// shifted by s along faces[0]'s turned normal, each face pushed out by tau / 2.
bim::Plane movedFace(const bim::Wall& w, int k, double s, double alpha, double tau) {
  const Eigen::Vector3d c = 0.5 * (w.start + w.end);
  const Eigen::Isometry3d turn = Eigen::Translation3d(c) * Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitZ()) * Eigen::Translation3d(-c);
  const auto& f = w.faces[static_cast<std::size_t>(k)];
  bim::Plane p;
  p.n = turn.linear() * f.plane.n;
  const Eigen::Vector3d e = turn.linear() * w.faces[0].plane.n;
  const Eigen::Vector3d point = turn * f.start + s * e + 0.5 * tau * p.n;
  p.d = -p.n.dot(point);
  return p;
}

}  // namespace

TEST(SGraphFactors, WallNodeFacesAreThePlanFacesAndMoveAsARigidWall) {
  const bim::Storey storey = boxStorey();
  Graph g;
  std::vector<std::string> warnings;
  buildPlanLayers(storey, g, warnings);
  EXPECT_TRUE(warnings.empty());
  ASSERT_EQ(g.nodes.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    for (int k = 0; k < 2; ++k) {
      const auto& plan = storey.walls[i].faces[static_cast<std::size_t>(k)].plane;
      EXPECT_NEAR((g.nodes[i].normal(k) - plan.n.head<2>()).norm(), 0.0, 1e-12);
      EXPECT_NEAR(g.nodes[i].d(k), plan.d, 1e-12);
      g.nodes[i].params = {0.07, 2 * kDeg, 0.03};
      const bim::Plane moved = movedFace(storey.walls[i], k, 0.07, 2 * kDeg, 0.03);
      EXPECT_NEAR((g.nodes[i].normal(k) - moved.n.head<2>()).norm(), 0.0, 1e-12);
      EXPECT_NEAR(g.nodes[i].d(k), moved.d, 1e-12);
      g.nodes[i].params = {0, 0, 0};
    }
  }
  // The room: centre where both pairs' mid-lines cross, the factor zero on the plan.
  ASSERT_EQ(g.rooms.size(), 1u);
  EXPECT_FALSE(g.rooms[0].corridor);
  EXPECT_NEAR((g.rooms[0].plan_centre - Eigen::Vector2d(2.0, 2.5)).norm(), 0.0, 1e-12);
}

TEST(SGraphFactors, PlaneFactorIsTheFaceMovedIntoTheLidarFrame) {
  const bim::Storey storey = boxStorey();
  Graph g;
  std::vector<std::string> warnings;
  buildPlanLayers(storey, g, warnings);
  const Keyframe kf = keyframeAt(1.2, 3.1, 200 * kDeg, 2.0, -1.5);
  const Eigen::Isometry3d T_map_lidar = kf.T_map_base() * mount();
  const std::array<double, 3> params{0.04, 0.5 * kDeg, 0.01};
  for (std::size_t i = 0; i < 4; ++i) {
    const bim::Plane moved = movedFace(storey.walls[i], 0, params[0], params[1], params[2]);
    // Independently: n_s = R^T n, d_s = d + n·t (reference.md, S-Graphs math).
    const Eigen::Vector3d expected =
        planes::minimalPlane(T_map_lidar.linear().transpose() * moved.n, moved.d + moved.n.dot(T_map_lidar.translation()));
    double predicted[3];
    PlaneFactor::predict(g.nodes[i].face[0], kf.A, kf.b, kf.pose.data(), params.data(), predicted);
    EXPECT_NEAR(wrapAngle(predicted[0] - expected[0]), 0.0, 1e-12) << "wall " << i;
    EXPECT_NEAR(predicted[1], expected[1], 1e-12);
    EXPECT_NEAR(predicted[2], expected[2], 1e-12);
    // The residual: the whitened difference to the observation, azimuth wrapped.
    Eigen::Matrix3d L;
    L << 50, 1, 2, 0, 40, 3, 0, 0, 20;
    const Eigen::Vector3d observed(wrapAngle(expected[0] + 0.01), expected[1] - 0.02, expected[2] + 0.03);
    const std::unique_ptr<ceres::CostFunction> cost(PlaneFactor::create(g.nodes[i].face[0], kf.A, kf.b, observed, L));
    double r[3];
    const double* blocks[2] = {kf.pose.data(), params.data()};
    ASSERT_TRUE(cost->Evaluate(blocks, r, nullptr));
    const Eigen::Vector3d want = L * Eigen::Vector3d(-0.01, 0.02, -0.03);
    EXPECT_NEAR((Eigen::Vector3d(r[0], r[1], r[2]) - want).norm(), 0.0, 1e-9);
    expectJacobiansMatchNumeric(*cost, {{kf.pose[0], kf.pose[1], kf.pose[2]}, {params[0], params[1], params[2]}});
  }
}

TEST(SGraphFactors, OdometryFactorWrapsTheHeadingAndHasTheRightJacobians) {
  // b is a in a's frame moved by (1, 0.2) and turned by 0.1 rad, across the +-pi seam.
  const Eigen::Vector3d a(2.0, -1.0, 3.1), delta(1.0, 0.2, 0.1);
  const Eigen::Vector3d b = compose(a, delta);
  EXPECT_LT(b.z(), 0.0);
  const std::unique_ptr<ceres::CostFunction> cost(OdometryFactor::create(delta, {0.02, 0.02, 0.01}));
  double r[3];
  const double* blocks[2] = {a.data(), b.data()};
  ASSERT_TRUE(cost->Evaluate(blocks, r, nullptr));
  EXPECT_NEAR(Eigen::Vector3d(r[0], r[1], r[2]).norm(), 0.0, 1e-12);
  // Off by 5 cm along a's x axis: 2.5 sigmas on the first residual.
  const Eigen::Vector3d off = compose(a, delta + Eigen::Vector3d(0.05, 0, 0));
  const double* moved[2] = {a.data(), off.data()};
  cost->Evaluate(moved, r, nullptr);
  EXPECT_NEAR(r[0], 2.5, 1e-9);
  expectJacobiansMatchNumeric(*cost, {{a.x(), a.y(), a.z()}, {off.x(), off.y(), off.z()}});
}

TEST(SGraphFactors, RoomFactorCentresTheRoomBetweenItsOppositeWalls) {
  const bim::Storey storey = boxStorey();
  Graph g;
  std::vector<std::string> warnings;
  buildPlanLayers(storey, g, warnings);
  const RoomData& room = g.rooms[0];
  std::array<FaceGeometry, 4> faces;
  for (int i = 0; i < 4; ++i) faces[i] = g.nodes[static_cast<std::size_t>(room.pairs[i].node)].face[room.pairs[i].face];
  const std::unique_ptr<ceres::CostFunction> cost(RoomFactor::create(faces, 0.02));
  std::vector<std::vector<double>> p = {{2.0, 2.5}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  auto evaluate = [&] {
    std::vector<const double*> blocks;
    for (auto& b : p) blocks.push_back(b.data());
    Eigen::Vector2d r;
    cost->Evaluate(blocks.data(), r.data(), nullptr);
    return r;
  };
  EXPECT_NEAR(evaluate().norm(), 0.0, 1e-12);
  // One wall of the first pair moved 0.1 m into the room: the centre should move 0.05 m.
  p[1][0] = 0.1;
  EXPECT_NEAR(std::abs(evaluate()[0]), 0.05 / 0.02, 1e-9);
  EXPECT_NEAR(evaluate()[1], 0.0, 1e-12);
  const Eigen::Vector2d n = g.nodes[static_cast<std::size_t>(room.pairs[0].node)].normal(room.pairs[0].face);
  p[0] = {2.0 + 0.05 * n.x(), 2.5 + 0.05 * n.y()};
  EXPECT_NEAR(evaluate().norm(), 0.0, 1e-12);
  p = {{2.3, 2.1}, {0.02, 0.01, 0.01}, {-0.03, -0.02, 0.0}, {0.01, 0.005, 0.02}, {0.05, 0.01, -0.01}};
  expectJacobiansMatchNumeric(*cost, p);
  const std::unique_ptr<ceres::CostFunction> corridor(CorridorFactor::create({faces[0], faces[1]}, 0.02));
  expectJacobiansMatchNumeric(*corridor, {p[0], p[1], p[2]});
}

TEST(SGraphFactors, PriorsHaveTheirValuesAndJacobians) {
  Eigen::Matrix3d L;
  L << 10, 1, 0, 0, 10, 2, 0, 0, 100;
  MarginalPrior prior = posePrior({1, 2, M_PI - 0.01}, {0.1, 0.1, 0.01});
  prior.J = L;
  const std::unique_ptr<ceres::CostFunction> pose(new MarginalPriorFactor(prior));
  const double wrapped[3] = {1.1, 2.0, -M_PI + 0.01};  // 0.02 rad away across the seam
  const double* blocks[1] = {wrapped};
  double r[3];
  pose->Evaluate(blocks, r, nullptr);
  EXPECT_NEAR((Eigen::Vector3d(r[0], r[1], r[2]) - L * Eigen::Vector3d(0.1, 0, 0.02)).norm(), 0.0, 1e-9);
  expectJacobiansMatchNumeric(*pose, {{1.1, 2.0, -M_PI + 0.01}});
  const std::unique_ptr<ceres::CostFunction> wall(WallPrior::create(0.05, 1 * kDeg));
  const double node[3] = {0.1, 2 * kDeg, 0.3};
  const double* nb[1] = {node};
  wall->Evaluate(nb, r, nullptr);
  EXPECT_NEAR(r[0], 2.0, 1e-12);
  EXPECT_NEAR(r[1], 2.0, 1e-12);
  expectJacobiansMatchNumeric(*wall, {{0.1, 2 * kDeg, 0.3}});
  expectJacobiansMatchNumeric(*std::unique_ptr<ceres::CostFunction>(ThicknessPrior::create(0.02)), {{0.1, 0.0, 0.03}});
  expectJacobiansMatchNumeric(*std::unique_ptr<ceres::CostFunction>(GaussianPrior<3>::create({0.1, 0.2, 0.3}, L)), {{0.2, 0.1, 0.0}});
}

TEST(SGraphFactors, MarginalizingAKeyframePropagatesItsPriorThroughOdometry) {
  // Two keyframes, no walls: the prior on the second must be the first's prior moved by the
  // odometry, covariance J P J' + Q (J the Jacobian of a (+) delta with respect to a).
  sgraph::SGraphConfig config;
  Graph g;
  Keyframe k0 = keyframeAt(1.0, 2.0, 0.3, 0, 0), k1 = keyframeAt(0, 0, 0, 0, 0);
  k0.id = 0, k1.id = 1;
  k0.odom = Eigen::Vector3d(5, 5, 1.0);
  k1.odom = compose(k0.odom, {2.0, 0.5, 0.2});
  const Eigen::Vector3d x1 = compose(k0.planar(), between(k0.odom, k1.odom));
  k1.pose = {x1.x(), x1.y(), x1.z()};
  k0.predicted = k0.planar(), k1.predicted = x1;
  const Eigen::Vector3d sigma0(0.1, 0.2, 0.05);
  g.prior = posePrior(k0.planar(), sigma0);
  g.history.resize(2);
  g.window = {k0, k1};
  // The window's covariance of its newest pose, before: the same propagation (checked below).
  const SolveReport solved = optimizeWindow(g, config);
  ASSERT_TRUE(solved.newest_covariance.has_value());
  const Eigen::Matrix3d window_covariance = *solved.newest_covariance;
  marginalizeOldest(g, config);
  ASSERT_EQ(g.window.size(), 1u);
  ASSERT_EQ(g.prior.J.rows(), 3);
  ASSERT_TRUE(g.prior.nodes.empty());
  // Its minimum (where the residual vanishes) is the odometry's prediction.
  const Eigen::Vector3d minimum = g.prior.x0 - g.prior.J.colPivHouseholderQr().solve(g.prior.r0);
  EXPECT_NEAR((minimum - x1).norm(), 0.0, 1e-9);
  const Eigen::Vector3d q = odometrySigma(k0, k1, config);
  const Eigen::Vector3d d = between(k0.odom, k1.odom);
  const double c = std::cos(k0.pose[2]), s = std::sin(k0.pose[2]);
  Eigen::Matrix3d J = Eigen::Matrix3d::Identity();  // d(a (+) d)/da
  J(0, 2) = -s * d.x() - c * d.y();
  J(1, 2) = c * d.x() - s * d.y();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // the odometry noise is in a's frame
  R.topLeftCorner<2, 2>() << c, -s, s, c;
  const Eigen::Matrix3d P = J * sigma0.cwiseAbs2().asDiagonal() * J.transpose() + R * q.cwiseAbs2().asDiagonal() * R.transpose();
  const Eigen::Matrix3d information = g.prior.J.transpose() * g.prior.J;
  EXPECT_LT((information.inverse() - P).norm(), 1e-6 * P.norm());
  EXPECT_LT((window_covariance - P).norm(), 1e-6 * P.norm());
}

// The oracle for the window's marginalization: on a walk whose factors are all near their
// linear regime (small noise, no robust kernel active), sliding a 3-keyframe window along it
// must give, for what is still in the window, the same estimate as one batch optimization of
// every keyframe with all their factors (exact Gaussian elimination loses nothing). The walk's
// odometry is biased 2 % and its start prior 4 cm off, so that the answer is a compromise the
// marginalized keyframes take part in, not a consensus every method finds.
TEST(SGraphFactors, SlidingTheWindowGivesWhatTheBatchGivesForWhatIsLeft) {
  sgraph::SGraphConfig config;
  const bim::Storey storey = boxStorey();
  const std::array<double, 3> truth_shift{0.04, -0.02, 0.0};  // wall S and wall E built off their plan
  std::mt19937_64 rng(7);
  std::normal_distribution<double> unit;
  const Eigen::Vector3d plane_sigma(0.5 * kDeg, 0.5 * kDeg, 0.01);

  Graph base;
  std::vector<std::string> warnings;
  buildPlanLayers(storey, base, warnings);
  Graph truth_graph = base;
  truth_graph.nodes[0].params = {truth_shift[0], 0, 0};
  truth_graph.nodes[1].params = {truth_shift[1], 0, 0};
  std::vector<Keyframe> walk;
  for (int i = 0; i < 9; ++i) {
    Keyframe kf = keyframeAt(1.0 + 0.25 * i, 1.5 + 0.2 * (i % 3), 0.4 * i, 0.5, -0.3);
    kf.id = i;
    const Eigen::Vector3d truth = kf.planar();
    kf.odom = Eigen::Vector3d(1.02 * truth.x(), 1.02 * truth.y(), truth.z());  // 2 % scale error
    for (int w = 0; w < 4; ++w) {
      PlaneMeasurement m;
      m.node = w;
      m.face = 0;  // the face looking into the room
      double predicted[3];
      PlaneFactor::predict(truth_graph.nodes[static_cast<std::size_t>(w)].face[0], kf.A, kf.b, kf.pose.data(),
                           truth_graph.nodes[static_cast<std::size_t>(w)].params.data(), predicted);
      for (int k = 0; k < 3; ++k) m.minimal[k] = predicted[k] + 0.2 * plane_sigma[k] * unit(rng);
      m.sqrt_information = plane_sigma.cwiseInverse().asDiagonal();
      kf.planes.push_back(m);
    }
    walk.push_back(kf);
  }
  const Eigen::Vector3d start = walk[0].planar() + Eigen::Vector3d(0.04, -0.03, 0.5 * kDeg);

  // Both start from the odometry's dead reckoning from the (wrong) start.
  const auto deadReckoned = [&](int i) { return compose(start, between(walk[0].odom, walk[static_cast<std::size_t>(i)].odom)); };
  const auto place = [&](Keyframe kf, int i) {
    const Eigen::Vector3d p = deadReckoned(i);
    kf.pose = {p.x(), p.y(), p.z()};
    kf.predicted = p;
    return kf;
  };
  Graph batch = base;
  batch.history.resize(walk.size());
  batch.prior = posePrior(start, {0.1, 0.1, 2 * kDeg});
  for (std::size_t i = 0; i < walk.size(); ++i) batch.window.push_back(place(walk[i], static_cast<int>(i)));
  ASSERT_TRUE(optimizeWindow(batch, config).usable);

  Graph sliding = base;
  sliding.history.resize(walk.size());
  sliding.prior = posePrior(start, {0.1, 0.1, 2 * kDeg});
  for (std::size_t i = 0; i < walk.size(); ++i) {
    Keyframe kf = place(walk[i], static_cast<int>(i));
    if (!sliding.window.empty()) {  // predicted from the last optimized keyframe, as the tracker does
      const Eigen::Vector3d p = compose(sliding.window.back().planar(), between(sliding.window.back().odom, kf.odom));
      kf.pose = {p.x(), p.y(), p.z()};
      kf.predicted = p;
    }
    sliding.window.push_back(kf);
    ASSERT_TRUE(optimizeWindow(sliding, config).usable);
    while (sliding.window.size() > 3) marginalizeOldest(sliding, config);
  }
  ASSERT_EQ(sliding.window.size(), 3u);
  ASSERT_FALSE(sliding.prior.nodes.empty());
  for (std::size_t i = 0; i < 3; ++i) {
    const Keyframe& s = sliding.window[i];
    const Keyframe& b = batch.window[walk.size() - 3 + i];
    ASSERT_EQ(s.id, b.id);
    EXPECT_NEAR((s.planar() - b.planar()).head<2>().norm(), 0.0, 1e-3) << "keyframe " << s.id;
    EXPECT_NEAR(s.pose[2], b.pose[2], 0.02 * kDeg) << "keyframe " << s.id;
  }
  for (std::size_t w = 0; w < 4; ++w) {
    EXPECT_NEAR(sliding.nodes[w].params[0], batch.nodes[w].params[0], 1e-3) << storey.walls[w].id;
    EXPECT_NEAR(sliding.nodes[w].params[1], batch.nodes[w].params[1], 0.02 * kDeg) << storey.walls[w].id;
  }
  // And the batch itself measured the room as built (the independent truth): the distances
  // between opposite faces, which the scans observe whatever the robot's own offset (where
  // the pair sits is shared between the robot and the walls' plan priors).
  const auto width = [](const Graph& g, std::size_t a, std::size_t b) { return g.nodes[a].d(0) + g.nodes[b].d(0); };
  EXPECT_NEAR(width(batch, 0, 2), width(truth_graph, 0, 2), 0.005);  // S - N
  EXPECT_NEAR(width(batch, 1, 3), width(truth_graph, 1, 3), 0.005);  // E - W
}
