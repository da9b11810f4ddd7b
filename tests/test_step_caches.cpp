// What the localizer keeps between steps instead of recomputing it, against recomputing it
// (docs/results/2026-11-26-h28speed3.md):
// - the filter's estimate (the particles' weighted mean, moved on by the odometry since they
//   were weighed) and the particles' version, at every step of a walk, weighed or not: the
//   mean computed here from particles(), not the filter's;
// - the guide's room test (guide/wall_slice.hpp RoomBoxes) against Storey::roomAt at every
//   point of a 5 cm grid over a storey of 99 rooms, and at every corner and edge middle.
#include "face_index_fixtures.hpp"
#include "sim_fixtures.hpp"

#include "guide/wall_slice.hpp"
#include "sim/base/base_trajectory.hpp"
#include "sim/lidar/vlp16_config.hpp"
#include "sim/world/world.hpp"

#include <bimloc/geometry/planar_pose.hpp>
#include <bimloc/pf/particle_filter.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace bimloc;
using test::officeWorld;
using test::pose;
using test::wallsSeenFrom;

namespace {

// The particles' weighted mean, written out here: weights exp(log w - max), normalised; the
// heading as the mean of unit vectors.
Eigen::Vector3d meanOfParticles(const std::vector<pf::Particle>& particles) {
  double top = -INFINITY;
  for (const auto& p : particles) top = std::max(top, p.log_weight);
  double sum = 0, x = 0, y = 0, s = 0, c = 0;
  for (const auto& p : particles) {
    const double w = std::exp(p.log_weight - top);
    sum += w, x += w * p.x, y += w * p.y, s += w * std::sin(p.yaw), c += w * std::cos(p.yaw);
  }
  return {x / sum, y / sum, std::atan2(s, c)};
}

}  // namespace

TEST(StepCaches, TheEstimateIsTheParticlesMeanMovedOnAtEveryStepAndTheVersionChangesWhenWeighed) {
  const auto& storey = officeWorld().building().storeys[0];
  const Eigen::Isometry3d mount = sim::Vlp16Config{}.T_base_lidar;
  const bim::Room* start_room = storey.findRoom("R105");
  ASSERT_NE(start_room, nullptr);
  pf::ParticleFilterConfig config;
  config.seed = 5;
  config.particles = 1500;
  pf::ParticleFilter filter(storey, mount, config);
  pf::ParticleFilter other(storey, mount, config);
  EXPECT_NE(filter.particlesVersion(), other.particlesVersion());  // never the same for two filters
  sim::MotionConfig motion;
  motion.kind = sim::MotionConfig::Kind::Tour;
  motion.rooms = {"C100"};
  const auto trajectory = sim::BaseTrajectory::plan(officeWorld(), 0, {start_room->centre.x(), start_room->centre.y(), 0.0},
                                                    motion, 12.0, 1);
  const Eigen::Isometry3d first = trajectory.T_map_base(0.0);
  Eigen::Isometry3d odom_at_weighing = Eigen::Isometry3d::Identity();
  int weighed = 0, not_weighed = 0;
  for (double t = 0; t <= std::min(12.0, trajectory.duration_s()) && !filter.converged(); t += 0.1) {
    const Eigen::Isometry3d T_map_base = trajectory.T_map_base(t);
    const Eigen::Isometry3d odom = first.inverse() * T_map_base;
    filter.predict(odom);
    const std::uint64_t before = filter.particlesVersion();
    // Asked before the update too: what it keeps must not outlive the weighing below.
    (void)filter.T_map_base();
    const auto report = filter.update(wallsSeenFrom(T_map_base, mount));
    EXPECT_EQ(filter.particlesVersion() != before, report.weighed) << t;
    if (report.weighed) odom_at_weighing = odom, ++weighed;
    else ++not_weighed;
    if (filter.converged()) break;
    // Before convergence: the mean of the particles as weighed, moved on by the odometry since.
    for (int ask = 0; ask < 2; ++ask) {
      const Eigen::Vector3d estimate = planarPose(filter.T_map_base());
      const Eigen::Vector3d expected = compose(meanOfParticles(filter.particles()), planarPose(odom_at_weighing.inverse() * odom));
      EXPECT_NEAR(estimate.x(), expected.x(), 1e-9) << t;
      EXPECT_NEAR(estimate.y(), expected.y(), 1e-9) << t;
      EXPECT_NEAR(wrapAngle(estimate.z() - expected.z()), 0.0, 1e-9) << t;
    }
  }
  EXPECT_GT(weighed, 3);
  EXPECT_GT(not_weighed, 3);
}

TEST(StepCaches, TheGuidesRoomTestAnswersAsTheStoreyDoesEverywhere) {
  const bim::Storey storey = test::tiled(officeWorld().building().storeys[0], 3);
  ASSERT_GE(storey.rooms.size(), 90u);
  const guide::detail::RoomBoxes boxes(storey);
  std::vector<Eigen::Vector2d> points;
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const auto& r : storey.rooms)
    for (std::size_t i = 0; i < r.footprint.size(); ++i) {
      const Eigen::Vector2d& a = r.footprint[i];
      const Eigen::Vector2d& b = r.footprint[(i + 1) % r.footprint.size()];
      lo = lo.cwiseMin(a), hi = hi.cwiseMax(a);
      points.push_back(a), points.push_back(0.5 * (a + b));  // on the outline: where rounding decides
    }
  for (double x = lo.x() - 0.5; x <= hi.x() + 0.5; x += 0.05)
    for (double y = lo.y() - 0.5; y <= hi.y() + 0.5; y += 0.05) points.push_back({x, y});
  int inside = 0;
  for (const auto& p : points) {
    const bool expected = storey.roomAt(p) != nullptr;
    ASSERT_EQ(boxes.inAnyRoom(p), expected) << p.transpose();
    inside += expected;
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(static_cast<int>(points.size()) - inside, 1000);
}
