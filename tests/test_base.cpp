// The simulated legged base on the default world: paths through doors, clearance from the
// building, speed and turn limits, the gait, and reproducibility.
#include "sim/base/base_trajectory.hpp"
#include "sim/world/world.hpp"

#include <bimloc/bim/geometry2d.hpp>
#include <bimloc/geometry/planar_pose.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <regex>

namespace bimloc::sim {
namespace {

const World& siteOffice() {
  static const std::unique_ptr<World> world =
      std::make_unique<World>(World::fromPlan(std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc"));
  return *world;
}

const bim::Room& roomNamed(const std::string& name) {
  for (const auto& r : siteOffice().building().storeys.at(0).rooms)
    if (r.name == name) return r;
  throw std::runtime_error("no room " + name);
}

double yawOf(const Eigen::Isometry3d& T) { return bimloc::yawOf(T.linear()); }

// Distance from p to the triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
double pointTriangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                             const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

// The building's surfaces nearest to the body centre. The storey mesh, not the wall faces of
// the model: those run across the doorways the base walks through.
double clearance(const bim::TriangleMesh& mesh, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : mesh.triangles)
    best = std::min(best, pointTriangleDistance(p, mesh.vertices[t[0]].cast<double>(), mesh.vertices[t[1]].cast<double>(),
                                                mesh.vertices[t[2]].cast<double>()));
  return best;
}

MotionConfig tour(std::vector<std::string> rooms) {
  MotionConfig m;
  m.kind = MotionConfig::Kind::Tour;
  m.rooms = std::move(rooms);
  return m;
}

TEST(BaseTrajectory, TourFromR101ReachesR105ThroughTheDoors) {
  const MotionConfig motion = tour({"R105"});
  const bim::Room& r101 = roomNamed("R101");
  const auto trajectory = BaseTrajectory::plan(siteOffice(), 0, {r101.centre.x(), r101.centre.y(), 0.0}, motion, 90.0, 1);
  ASSERT_LT(trajectory.script_duration_s(), 90.0);
  const Eigen::Vector3d end = trajectory.T_map_base(trajectory.duration_s()).translation();
  EXPECT_TRUE(bim::pointInPolygon(roomNamed("R105").footprint, end.head<2>())) << end.transpose();
  // A few straight segments, not a staircase of grid steps.
  EXPECT_LE(trajectory.corners().size(), 8u);
  EXPECT_GT(trajectory.distance_m(trajectory.duration_s()), (roomNamed("R105").centre - r101.centre).norm());

  const bim::TriangleMesh& mesh = siteOffice().building().storeys.at(0).mesh;
  ASSERT_FALSE(mesh.empty());
  const double dt = 0.02;
  double min_clearance = std::numeric_limits<double>::infinity();
  for (double t = 0.0; t <= trajectory.script_duration_s() + dt; t += dt) {
    const Eigen::Vector3d p = trajectory.T_map_base(t).translation();
    // The body sphere is centred at body height; the gait's bob is not part of the check.
    const Eigen::Vector3d centre(p.x(), p.y(), motion.gait.body_height_m);
    min_clearance = std::min(min_clearance, clearance(mesh, centre));
  }
  EXPECT_GE(min_clearance, motion.body_radius_m - 1e-3);
}

TEST(BaseTrajectory, RespectsSpeedTurnAndAccelerationLimits) {
  MotionConfig motion = tour({"C100", "R106", "R103"});
  motion.max_speed_mps = 0.6;
  motion.max_turn_rate_dps = 45.0;
  motion.max_accel_mps2 = 0.4;
  const auto trajectory = BaseTrajectory::plan(siteOffice(), 0, {2.0, 2.5, 0.3}, motion, 120.0, 3);
  ASSERT_LT(trajectory.script_duration_s(), 120.0);
  const double dt = 0.01, tol = 1.0 + 1e-6;
  double top_speed = 0.0, top_turn = 0.0;
  for (double t = dt; t + dt <= trajectory.script_duration_s() + 1.0; t += dt) {
    const Eigen::Isometry3d a = trajectory.T_map_base(t - dt), b = trajectory.T_map_base(t), c = trajectory.T_map_base(t + dt);
    const Eigen::Vector2d v = (c.translation() - b.translation()).head<2>() / dt;
    const Eigen::Vector2d v_before = (b.translation() - a.translation()).head<2>() / dt;
    const double turn = std::abs(std::remainder(yawOf(c) - yawOf(b), 2.0 * M_PI)) / dt;
    top_speed = std::max(top_speed, v.norm());
    top_turn = std::max(top_turn, turn);
    ASSERT_LE(v.norm(), motion.max_speed_mps * tol) << "t = " << t;
    ASSERT_LE(turn, motion.max_turn_rate_dps * M_PI / 180.0 * tol) << "t = " << t;
    ASSERT_LE((v - v_before).norm() / dt, motion.max_accel_mps2 * tol + 1e-6) << "t = " << t;
    // Continuous: no jump between close instants.
    ASSERT_LT((trajectory.T_map_base(t + 1e-4).translation() - b.translation()).norm(), 1e-3) << "t = " << t;
  }
  // It does use the limits.
  EXPECT_GT(top_speed, 0.95 * motion.max_speed_mps);
  EXPECT_GT(top_turn, 0.95 * motion.max_turn_rate_dps * M_PI / 180.0);
  // Yaw follows the direction of travel.
  for (double t = 0.5; t < trajectory.script_duration_s(); t += 0.5) {
    const Eigen::Isometry3d b = trajectory.T_map_base(t), c = trajectory.T_map_base(t + 0.01);
    const Eigen::Vector2d step = (c.translation() - b.translation()).head<2>();
    if (step.norm() < 1e-4) continue;
    EXPECT_NEAR(std::remainder(std::atan2(step.y(), step.x()) - yawOf(b), 2.0 * M_PI), 0.0, 1e-6) << "t = " << t;
  }
}

TEST(BaseTrajectory, WaypointPathThroughAWallIsRefused) {
  MotionConfig motion;
  motion.kind = MotionConfig::Kind::Waypoints;
  motion.waypoints = {{Eigen::Vector2d(2.0, 4.0), std::nullopt}, {Eigen::Vector2d(6.0, 4.0), std::nullopt}};
  try {
    BaseTrajectory::plan(siteOffice(), 0, {2.0, 2.5, 0.0}, motion, 30.0, 0);
    FAIL() << "a path through the wall between R101 and R102 was accepted";
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    std::smatch m;
    ASSERT_TRUE(std::regex_search(message, m,
                                  std::regex(R"(motion segment 2 from \(2\.00, 4\.00\) to \(6\.00, 4\.00\) hits the )"
                                             R"(building at \(([-0-9.]+), ([-0-9.]+), ([-0-9.]+)\))")))
        << message;
    // The divider DIV-S1 has its west face at x = 4.00.
    EXPECT_NEAR(std::stod(m[1]), 4.0, 0.05) << message;
    EXPECT_NEAR(std::stod(m[2]), 4.0, 0.31) << message;
  }
}

TEST(BaseTrajectory, GaitBobsAtTheStepFrequencyWhileWalkingAndStopsWhenStanding) {
  MotionConfig motion;
  motion.kind = MotionConfig::Kind::Waypoints;
  motion.waypoints = {{Eigen::Vector2d(15.0, 6.12), std::nullopt}};  // along the corridor
  motion.gait.step_frequency_hz = 2.5;
  motion.gait.bob_amplitude_m = 0.02;
  const auto trajectory = BaseTrajectory::plan(siteOffice(), 0, {1.0, 6.12, 0.0}, motion, 30.0, 5);
  // Cruising (0.8 m/s after 1.6 s of acceleration) from t = 2 s to 14 s.
  const double t0 = 2.0, t1 = 14.0, dt = 0.002;
  double lo = 1e9, hi = -1e9;
  int rising = 0;
  double previous = trajectory.T_map_base(t0).translation().z() - motion.gait.body_height_m;
  for (double t = t0 + dt; t < t1; t += dt) {
    const double dz = trajectory.T_map_base(t).translation().z() - motion.gait.body_height_m;
    lo = std::min(lo, dz), hi = std::max(hi, dz);
    rising += previous < 0.0 && dz >= 0.0;
    previous = dz;
  }
  EXPECT_NEAR(hi, motion.gait.bob_amplitude_m, 1e-4);
  EXPECT_NEAR(lo, -motion.gait.bob_amplitude_m, 1e-4);
  EXPECT_NEAR(rising, motion.gait.step_frequency_hz * (t1 - t0), 1.0);
  // Roll and pitch rock the body within their amplitudes.
  double max_roll = 0.0;
  for (double t = t0; t < t1; t += 0.01) {
    const Eigen::Matrix3d R = trajectory.T_map_base(t).linear();
    max_roll = std::max(max_roll, std::abs(std::atan2(R(2, 1), R(2, 2))));
  }
  EXPECT_NEAR(max_roll, motion.gait.roll_amplitude_deg * M_PI / 180.0, 1e-3);
  // Standing after the script: at body height, level, still.
  ASSERT_LT(trajectory.script_duration_s(), 25.0);
  for (double t = trajectory.script_duration_s() + 0.01; t < 30.0; t += 0.37) {
    const Eigen::Isometry3d T = trajectory.T_map_base(t);
    EXPECT_NEAR(T.translation().z(), motion.gait.body_height_m, 1e-6);
    EXPECT_NEAR(T.translation().x(), 15.0, 1e-9);
    EXPECT_TRUE(T.linear().isApprox(Eigen::Matrix3d::Identity(), 1e-9)) << T.linear();
  }
}

TEST(BaseTrajectory, SameSeedSameRandomWalk) {
  MotionConfig motion;
  motion.kind = MotionConfig::Kind::RandomWalk;
  motion.walk_room = "R103";
  const bim::Room& room = roomNamed("R103");
  const Pose2 start{room.centre.x(), room.centre.y(), 1.0};
  const auto a = BaseTrajectory::plan(siteOffice(), 0, start, motion, 40.0, 11);
  const auto b = BaseTrajectory::plan(siteOffice(), 0, start, motion, 40.0, 11);
  const auto c = BaseTrajectory::plan(siteOffice(), 0, start, motion, 40.0, 12);
  EXPECT_GE(a.script_duration_s(), 40.0);  // walks until the end
  bool differs = false;
  for (double t = 0.0; t <= 40.0; t += 0.05) {
    ASSERT_TRUE(a.T_map_base(t).isApprox(b.T_map_base(t), 1e-12)) << "t = " << t;
    differs = differs || !a.T_map_base(t).isApprox(c.T_map_base(t), 1e-6);
    EXPECT_TRUE(bim::pointInPolygon(room.footprint, a.T_map_base(t).translation().head<2>())) << "t = " << t;
  }
  EXPECT_TRUE(differs);
  EXPECT_GT(a.corners().size(), 3u);
}

TEST(BaseTrajectory, StandHoldsTheStartPose) {
  const MotionConfig motion;  // Stand
  const auto trajectory = BaseTrajectory::plan(siteOffice(), 0, {6.0, 2.5, 0.5}, motion, 10.0, 0);
  EXPECT_EQ(trajectory.duration_s(), 10.0);
  EXPECT_EQ(trajectory.distance_m(10.0), 0.0);
  for (const double t : {-1.0, 0.0, 3.3, 10.0, 20.0}) {
    const Eigen::Isometry3d T = trajectory.T_map_base(t);
    EXPECT_TRUE(T.translation().isApprox(Eigen::Vector3d(6.0, 2.5, motion.gait.body_height_m), 1e-6));
    EXPECT_NEAR(yawOf(T), 0.5, 1e-12);
  }
}

TEST(BaseTrajectory, WaypointYawIsReachedOnArrival) {
  MotionConfig motion;
  motion.kind = MotionConfig::Kind::Waypoints;
  motion.waypoints = {{Eigen::Vector2d(3.0, 2.5), -M_PI / 2}, {Eigen::Vector2d(3.0, 1.0), M_PI}};
  const auto trajectory = BaseTrajectory::plan(siteOffice(), 0, {1.0, 2.5, 0.0}, motion, 30.0, 0);
  const Eigen::Isometry3d end = trajectory.T_map_base(30.0);
  EXPECT_TRUE(end.translation().head<2>().isApprox(Eigen::Vector2d(3.0, 1.0), 1e-12));
  EXPECT_NEAR(std::abs(yawOf(end)), M_PI, 1e-9);
  EXPECT_NEAR(trajectory.distance_m(30.0), 3.5, 1e-9);
  ASSERT_EQ(trajectory.corners().size(), 3u);
  EXPECT_NEAR(trajectory.corners()[2].yaw, -M_PI / 2, 1e-9);  // arrives heading south
}

TEST(BaseTrajectory, StartInsideAWallIsRefused) {
  EXPECT_THROW(BaseTrajectory::plan(siteOffice(), 0, {4.06, 2.5, 0.0}, MotionConfig{}, 10.0, 0), std::runtime_error);
  EXPECT_THROW(BaseTrajectory::plan(siteOffice(), 0, {2.0, 2.5, 0.0}, tour({"R999"}), 10.0, 0), std::runtime_error);
}

}  // namespace
}  // namespace bimloc::sim
