// The particle filter, step by step on planes from the simulator, and on bad input.
#include "sim_fixtures.hpp"

#include "sim/base/base_trajectory.hpp"
#include "sim/lidar/vlp16.hpp"
#include "sim/world/world.hpp"

#include <bimloc/geometry/planar_pose.hpp>
#include <bimloc/pf/particle_filter.hpp>

#include <gtest/gtest.h>

#include <cmath>

using namespace bimloc;
using test::officeWorld;
using test::pose;
using test::wallsSeenFrom;

TEST(ParticleFilter, ScoresTheTruePoseAboveItsLookAlikesInOtherRoomsOnlyWithTheRoomFactor) {
  const auto& storey = officeWorld().building().storeys[0];
  const Eigen::Isometry3d mount = sim::Vlp16Config{}.T_base_lidar;
  const bim::Room* r101 = storey.findRoom("R101");
  ASSERT_NE(r101, nullptr);
  const auto walls = wallsSeenFrom(pose(r101->centre.x(), r101->centre.y(), 0.3), mount);
  ASSERT_GE(walls.size(), 3u);
  pf::ParticleFilter filter(storey, mount, {});
  const auto truth = filter.score(r101->centre.x(), r101->centre.y(), 0.3, walls);
  EXPECT_GE(truth.second, 3);
  // The same relative pose in the identical room R102 scores the same: the rooms look alike.
  const bim::Room* r102 = storey.findRoom("R102");
  const auto twin = filter.score(r102->centre.x(), r102->centre.y(), 0.3, walls);
  EXPECT_NEAR(twin.first, truth.first, 1.0);
  // A pose in the corridor, or turned by 90 degrees, scores clearly worse.
  const bim::Room* corridor = storey.findRoom("C100");
  EXPECT_LT(filter.score(corridor->centre.x(), corridor->centre.y(), 0.3, walls).first, truth.first - 5.0);
  EXPECT_LT(filter.score(r101->centre.x(), r101->centre.y(), 0.3 + M_PI / 2, walls).first, truth.first - 5.0);
}

TEST(ParticleFilter, StepByStepFromOneRoomToConvergenceNeverFalse) {
  // Kimera-RPGO style: check the filter after each step. The base starts in R105 and walks out
  // of its door into the corridor and on to the lobby (the planned tour); odometry is exact here.
  const auto& storey = officeWorld().building().storeys[0];
  const Eigen::Isometry3d mount = sim::Vlp16Config{}.T_base_lidar;
  const bim::Room* start_room = storey.findRoom("R105");
  pf::ParticleFilterConfig config;
  config.seed = 3;
  pf::ParticleFilter filter(storey, mount, config);
  sim::MotionConfig motion;
  motion.kind = sim::MotionConfig::Kind::Tour;
  motion.rooms = {"C100"};
  const auto trajectory = sim::BaseTrajectory::plan(officeWorld(), 0, {start_room->centre.x(), start_room->centre.y(), 0.0},
                                                    motion, 40.0, 1);
  std::vector<Eigen::Vector3d> path;  // x, y, yaw in the map, at the lidar rate
  for (double t = 0; t <= trajectory.duration_s(); t += 0.1) {
    const Eigen::Isometry3d T = trajectory.T_map_base(t);
    path.push_back(planarPose(T));
  }
  const Eigen::Isometry3d T_map_odom_true = pose(path[0].x(), path[0].y(), path[0].z(), 0.0);
  bool converged = false;
  for (const auto& p : path) {
    const Eigen::Isometry3d T_map_base = pose(p.x(), p.y(), p.z());
    filter.predict(T_map_odom_true.inverse() * T_map_base);
    const auto walls = wallsSeenFrom(T_map_base, mount);
    const auto report = filter.update(walls);
    EXPECT_TRUE(report.warnings.empty());
    if (!filter.converged()) continue;
    converged = true;
    const Eigen::Isometry3d estimate = filter.T_map_base();
    // Once converged, always right (0.5 m, 10 degrees: the false-convergence bounds).
    EXPECT_LT((estimate.translation() - T_map_base.translation()).head<2>().norm(), 0.5) << p.transpose();
    const double yaw_error = yawOf(estimate.linear()) - p.z();
    EXPECT_LT(std::abs(std::atan2(std::sin(yaw_error), std::cos(yaw_error))), 10.0 * M_PI / 180.0) << p.transpose();
    // map <- odom is the transform that puts odometry into the plan (paper, initial transformation).
    EXPECT_LT((filter.T_map_odom()->translation() - T_map_odom_true.translation()).head<2>().norm(), 0.5);
  }
  EXPECT_TRUE(converged);
}

TEST(ParticleFilter, BadInputWarnsAndGoesOn) {
  const auto& storey = officeWorld().building().storeys[0];
  pf::ParticleFilter filter(storey, Eigen::Isometry3d::Identity(), {});
  planes::ObservedPlane nan_plane;
  nan_plane.normal = Eigen::Vector3d(std::nan(""), 0, 0);
  nan_plane.d = 1.0;
  filter.predict(Eigen::Isometry3d::Identity());
  auto report = filter.update({nan_plane, nan_plane});
  EXPECT_FALSE(report.warnings.empty());
  EXPECT_EQ(report.observations, 0);
  report = filter.update({});  // an empty scan
  EXPECT_EQ(report.observations, 0);
  Eigen::Isometry3d broken = Eigen::Isometry3d::Identity();
  broken.translation().x() = std::numeric_limits<double>::infinity();
  filter.predict(broken);                  // ignored
  filter.predict(pose(50.0, 0.0, 2.0));    // an odometry jump: particles move, nothing breaks
  report = filter.update({});
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("odometry jumped by 50.00 m"), std::string::npos) << report.warnings[0];
  for (const auto& p : filter.particles()) EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.yaw));
  EXPECT_FALSE(filter.converged());
}

TEST(ParticleFilter, RoomWithoutWallsDoesNotBreakTheFilter) {
  bim::Storey storey;
  bim::Room empty;
  empty.id = empty.name = "empty";
  empty.footprint = {{0, 0}, {4, 0}, {4, 4}, {0, 4}};
  empty.area_m2 = 16;
  empty.centre = {2, 2};
  storey.rooms.push_back(empty);
  pf::ParticleFilter filter(storey, Eigen::Isometry3d::Identity(), {});
  planes::ObservedPlane wall;
  wall.normal = Eigen::Vector3d(-1, 0, 0);
  wall.d = 2.0;
  planes::ObservedPlane other = wall;
  other.normal = Eigen::Vector3d(0, -1, 0);
  filter.predict(Eigen::Isometry3d::Identity());
  const auto report = filter.update({wall, other});
  EXPECT_EQ(report.associated, 0);
  EXPECT_FALSE(filter.converged());
}
