// The S-Graph tracker on walks with a known trajectory: the site office's plan read from its
// IFC, the walls a lidar sees computed from the true poses (with noise, fixed seeds), legged
// odometry drifting 1-2 %. Truth is the trajectory and the walls the observations came from.
#include "sgraph_fixtures.hpp"
#include "sgraph/graph.hpp"
#include "sgraph/loss_monitor.hpp"
#include "sgraph/plan_layers.hpp"
#include "sim_fixtures.hpp"

#include "sim/base/base_trajectory.hpp"
#include "sim/lidar/vlp16.hpp"
#include "sim/odometry/odometry_config.hpp"
#include "sim/odometry/odometry_model.hpp"
#include "sim/world/world.hpp"

#include <bimloc/geometry/planar_pose.hpp>
#include <bimloc/sgraph/sgraph_tracker.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <numeric>

using namespace bimloc;

namespace {

constexpr double kDeg = M_PI / 180.0;

const bim::Storey& office() { return test::officeWorld().building().storeys[0]; }

std::size_t wallIndex(const bim::Storey& storey, const std::string& name) {
  for (std::size_t i = 0; i < storey.walls.size(); ++i)
    if (storey.walls[i].name == name) return i;
  throw std::runtime_error("no wall " + name);
}

sim::BaseTrajectory plannedWalk(const sim::Pose2& start, const std::vector<Eigen::Vector2d>& waypoints, double duration_s,
                                sim::MotionConfig::Kind kind = sim::MotionConfig::Kind::Waypoints, std::vector<std::string> rooms = {}) {
  sim::MotionConfig motion;
  motion.kind = kind;
  for (const auto& w : waypoints) motion.waypoints.push_back({w, std::nullopt});
  motion.rooms = std::move(rooms);
  motion.skip_unreachable_rooms = true;
  return sim::BaseTrajectory::plan(test::officeWorld(), 0, start, motion, duration_s, 1);
}

struct Walk {
  const bim::Storey* plan = &office();
  const bim::Storey* truth = &office();
  std::vector<test::Opening> openings = test::worldOpenings("site_office", office());
  std::function<Eigen::Isometry3d(double)> pose;  // true map <- base at t
  double duration_s = 0;
  // The planes seen from the true map <- base: by default computed from `truth`'s walls.
  std::function<std::vector<planes::ObservedPlane>(const Eigen::Isometry3d&)> lidar;
  std::uint64_t odometry_seed = 1, noise_seed = 2;
  Eigen::Vector3d initial_error = {0.15, -0.10, 2.0 * kDeg};  // the particle filter's, at convergence
  sgraph::SGraphConfig config;
  double scan_rate_hz = 10;
  // Bad input: a NaN pose at this scan, a NaN plane at the first keyframe from this scan on,
  // the odometry 3 m off from this scan on, no walls seen in [blind_from, blind_to).
  int nan_pose_at = -1, nan_plane_from = -1, jump_from = -1, blind_from = -1, blind_to = -1;
};

struct Outcome {
  std::vector<sgraph::SGraphResult> keyframes;
  std::vector<double> error_m, yaw_error_deg, odometry_error_m, time_s, stamp_s;
  std::vector<int> scan;  // index of the keyframe's scan
  std::vector<std::string> warnings, plan_warnings;
  std::vector<sgraph::WallDeviation> deviations;
  std::vector<sgraph::NewPlane> new_planes;
  std::vector<sgraph::KeyframeInfo> history;
  std::vector<sgraph::RoomNode> rooms;
  int max_window = 0;
  int wanted_mismatches = 0;  // scans where wantsObservations() did not foretell a keyframe
};

double rms(const std::vector<double>& v, std::size_t from = 0) {
  double s = 0;
  for (std::size_t i = from; i < v.size(); ++i) s += v[i] * v[i];
  return v.size() > from ? std::sqrt(s / static_cast<double>(v.size() - from)) : 0.0;
}

Outcome run(const Walk& w) {
  Outcome out;
  sim::NoisyOdometry odometry(sim::odometryPreset("legged"), w.odometry_seed);
  std::mt19937_64 rng(w.noise_seed);
  const Eigen::Isometry3d mount = sim::Vlp16Config{}.T_base_lidar;
  const double odometry_rate_hz = 50;
  const int every = static_cast<int>(std::lround(odometry_rate_hz / w.scan_rate_hz));
  const Eigen::Isometry3d T0 = w.pose(0);
  const auto first = odometry.step(0, T0);
  const Eigen::Isometry3d guess = Eigen::Translation3d(w.initial_error.x(), w.initial_error.y(), 0) * T0 *
                                  Eigen::AngleAxisd(w.initial_error.z(), Eigen::Vector3d::UnitZ());
  sgraph::SGraphTracker tracker(*w.plan, mount, w.config, guess * first.T_odom_base.inverse());
  const Eigen::Isometry3d T_map_odom_guess = guess * first.T_odom_base.inverse();
  int scan = 0;
  bool nan_plane_done = false;
  for (int step = 0;; ++step) {
    const double t = step / odometry_rate_hz;
    if (t > w.duration_s) break;
    const Eigen::Isometry3d truth = w.pose(t);
    auto sample = step == 0 ? first : odometry.step(t, truth);
    if (step % every != 0) continue;
    Eigen::Isometry3d T_odom_base = sample.T_odom_base;
    if (scan == w.nan_pose_at) T_odom_base.translation().x() = std::nan("");
    if (w.jump_from >= 0 && scan >= w.jump_from) T_odom_base.translation().x() += 3.0;
    std::vector<planes::ObservedPlane> walls;
    const bool wanted = tracker.wantsObservations(T_odom_base);
    const bool blind = scan >= w.blind_from && scan < w.blind_to;
    if (wanted && !blind)
      walls = w.lidar ? w.lidar(truth) : test::syntheticWalls(*w.truth, w.openings, truth * mount, {}, rng);
    if (w.nan_plane_from >= 0 && scan >= w.nan_plane_from && !walls.empty() && !nan_plane_done) {
      walls[0].d = std::nan("");
      nan_plane_done = true;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const sgraph::SGraphResult r = tracker.addScan(t, T_odom_base, walls);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ++scan;
    if (wanted != r.keyframe_added) ++out.wanted_mismatches;
    for (const auto& warning : r.warnings)  // the plan's own warnings are checked apart
      if (std::find(tracker.warnings().begin(), tracker.warnings().end(), warning) == tracker.warnings().end()) out.warnings.push_back(warning);
    out.max_window = std::max(out.max_window, r.window_keyframes);
    if (!r.keyframe_added) continue;
    out.keyframes.push_back(r);
    out.time_s.push_back(dt);
    out.stamp_s.push_back(t);
    out.scan.push_back(scan - 1);
    out.error_m.push_back((r.T_map_base.translation() - truth.translation()).head<2>().norm());
    out.yaw_error_deg.push_back(std::abs(std::remainder(yawOf(r.T_map_base.linear()) - yawOf(truth.linear()), 2 * M_PI)) / kDeg);
    out.odometry_error_m.push_back(((T_map_odom_guess * sample.T_odom_base).translation() - truth.translation()).head<2>().norm());
  }
  out.plan_warnings = tracker.warnings();
  out.deviations = tracker.wallDeviations();
  out.new_planes = tracker.newPlanes();
  out.history = tracker.keyframes();
  out.rooms = tracker.rooms();
  return out;
}

// A walk on the office's planned trajectory.
Walk onTrajectory(const sim::BaseTrajectory& trajectory) {
  Walk w;
  w.pose = [&trajectory](double t) { return trajectory.T_map_base(t); };
  w.duration_s = trajectory.duration_s();
  return w;
}

// Office R101, out of its door, along the corridor into the lobby: about 25 m.
const sim::BaseTrajectory& officeWalk() {
  static const sim::BaseTrajectory walk =
      plannedWalk({2.0, 2.5, M_PI / 2}, {{3.2, 4.3}, {3.2, 6.1}, {15.5, 6.1}, {19.0, 8.0}, {19.0, 11.0}, {20.5, 11.0}}, 50.0);
  return walk;
}

}  // namespace

TEST(SGraphTracker, TracksAWalkThroughTheOfficeWithinCentimetresBetterThanOdometry) {
  Walk w = onTrajectory(officeWalk());
  const Outcome o = run(w);
  ASSERT_GE(o.keyframes.size(), 20u);
  EXPECT_GT(officeWalk().distance_m(w.duration_s), 20.0);
  // From the third keyframe on (the initial error of 0.18 m / 2 deg is corrected at once).
  for (std::size_t i = 2; i < o.keyframes.size(); ++i) {
    EXPECT_LT(o.error_m[i], 0.10) << "keyframe " << i << " at " << o.stamp_s[i] << " s";
    EXPECT_LT(o.yaw_error_deg[i], 1.0) << "keyframe " << i;
    EXPECT_EQ(o.keyframes[i].state, sgraph::TrackingState::Tracking);
  }
  const double tracked = rms(o.error_m, 2), odometry = rms(o.odometry_error_m, 2);
  EXPECT_LT(tracked, 0.05);
  EXPECT_LT(tracked, 0.5 * odometry);
  EXPECT_TRUE(o.warnings.empty()) << o.warnings.front();
  EXPECT_LE(o.max_window, w.config.window_keyframes);
  EXPECT_EQ(o.wanted_mismatches, 0);
  // The plan is the building here: its walls stay within their tolerance, nothing new appears.
  for (const auto& d : o.deviations) {
    EXPECT_LT(std::abs(d.offset_m), 0.03) << d.wall_id;
    EXPECT_LT(std::abs(d.angle_deg), 0.5) << d.wall_id;
  }
  EXPECT_TRUE(o.new_planes.empty());
  // Every keyframe is in the history, the last ones in the window.
  ASSERT_EQ(o.history.size(), o.keyframes.size());
  EXPECT_EQ(std::count_if(o.history.begin(), o.history.end(), [](const auto& k) { return k.in_window; }), w.config.window_keyframes);
  for (std::size_t i = 0; i < o.history.size(); ++i) EXPECT_EQ(o.history[i].id, o.keyframes[i].keyframe);
  // The topological layer: the offices, the WC and the store (the corridor with its lobby is
  // no rectangle), their centres where their walls put them.
  EXPECT_EQ(o.rooms.size(), 10u);
  for (const auto& room : o.rooms) {
    EXPECT_NE(room.name, "C100");
    EXPECT_LT((room.centre - room.plan_centre).norm(), 0.03) << room.name;
  }
  std::printf("office walk: %zu keyframes, RMS error %.3f m (odometry alone %.3f m), max %.3f m\n", o.keyframes.size(), tracked,
              odometry, *std::max_element(o.error_m.begin() + 2, o.error_m.end()));
}

TEST(SGraphTracker, SameInputSameOutput) {
  Walk w = onTrajectory(officeWalk());
  const Outcome a = run(w);
  // Other allocations in between, so that the second run's blocks sit elsewhere in memory (an
  // order by address made the covariance differ in its last digits).
  std::vector<std::unique_ptr<double[]>> shift;
  for (int i = 0; i < 1000; ++i) shift.emplace_back(new double[static_cast<std::size_t>(3 + i % 7)]);
  const Outcome b = run(w);
  ASSERT_EQ(a.keyframes.size(), b.keyframes.size());
  int covariances = 0;
  for (std::size_t i = 0; i < a.keyframes.size(); ++i) {
    EXPECT_EQ(std::memcmp(a.keyframes[i].T_map_base.data(), b.keyframes[i].T_map_base.data(), sizeof(double) * 16), 0);
    EXPECT_EQ(a.keyframes[i].final_cost, b.keyframes[i].final_cost);
    ASSERT_EQ(a.keyframes[i].covariance.has_value(), b.keyframes[i].covariance.has_value());
    if (!a.keyframes[i].covariance) continue;
    ++covariances;
    EXPECT_EQ(std::memcmp(a.keyframes[i].covariance->data(), b.keyframes[i].covariance->data(), sizeof(double) * 9), 0) << "keyframe " << i;
  }
  EXPECT_GT(covariances, 0);
}

TEST(SGraphTracker, AWallBuiltOffItsPlanMovesItsNodeNotTheRobot) {
  // The lobby's east wall stands 10 cm west of its plan position; the plan does not know.
  const std::size_t east = wallIndex(office(), "EXT-E");
  const bim::Storey truth = test::shiftedWall(office(), east, 0.10);  // along faces[0]'s normal (-x)
  static const sim::BaseTrajectory lobby =
      plannedWalk({14.0, 6.1, 0.0}, {{19.5, 6.1}, {19.5, 10.8}, {17.5, 10.8}, {17.5, 4.5}, {20.5, 4.5}}, 40.0);
  Walk w = onTrajectory(lobby);
  w.truth = &truth;
  const Outcome shifted = run(w);
  w.truth = &office();
  const Outcome planned = run(w);
  const auto deviation = std::find_if(shifted.deviations.begin(), shifted.deviations.end(), [&](const auto& d) { return d.wall == int(east); });
  ASSERT_NE(deviation, shifted.deviations.end());
  EXPECT_NEAR(deviation->offset_m, 0.10, 0.03);
  EXPECT_NEAR(deviation->angle_deg, 0.0, 0.5);
  for (const auto& d : shifted.deviations)
    if (d.wall != int(east)) {
      EXPECT_LT(std::abs(d.offset_m), 0.04) << d.wall_id;
    }
  // The robot stays where it is: errors as with the wall where the plan has it.
  const double rms_shifted = rms(shifted.error_m, 2), rms_planned = rms(planned.error_m, 2);
  EXPECT_LT(rms_shifted, 0.03);
  EXPECT_LT(rms_shifted, rms_planned + 0.02);
  std::printf("EXT-E 10 cm off plan: estimated %.3f m, %.2f deg; robot RMS %.3f m (plan exact: %.3f m)\n", deviation->offset_m,
              deviation->angle_deg, rms_shifted, rms_planned);
}

TEST(SGraphTracker, OfTwoNearParallelWallsTheRightOneIsAssociated) {
  // A room [0, 6] x [0, 6] and, 0.3 m in front of its west wall, a lining wall that the plan
  // has but the site may not (yet): the robot must match what it sees to the right one.
  bim::Storey plan;
  plan.walls = {test::boxWall("S", {-0.1, -0.1}, {6.1, -0.1}, 0.2), test::boxWall("E", {6.1, -0.1}, {6.1, 6.1}, 0.2),
                test::boxWall("N", {6.1, 6.1}, {-0.1, 6.1}, 0.2), test::boxWall("W", {-0.1, 6.1}, {-0.1, -0.1}, 0.2),
                test::boxWall("L", {0.24, 5.5}, {0.24, 0.5}, 0.12)};  // its east face at x = 0.30
  plan.rooms = {test::boxRoom("R", 0, 0, 6, 6, {{"S", 0}, {"E", 0}, {"N", 0}, {"W", 0}})};
  bim::Storey unlined = plan;
  unlined.walls.pop_back();
  for (const bim::Storey* truth : {&plan, &unlined}) {
    for (double error_x : {-0.1, 0.1}) {
      Walk w;
      w.plan = &plan;
      w.truth = truth;
      w.openings.clear();
      w.pose = [](double t) { return test::pose(2.0 + 0.25 * t, 3.0 + 0.05 * t, std::atan2(0.05, 0.25)); };  // walking forward
      w.duration_s = 12;
      w.initial_error = {error_x, 0.0, 0.0};
      sgraph::SGraphTracker tracker(plan, sim::Vlp16Config{}.T_base_lidar, {}, Eigen::Isometry3d::Identity());
      const Outcome o = run(w);
      const int expected = truth == &plan ? 4 : 3;  // L where it is built, else W
      int matched = 0;
      for (const auto& r : o.keyframes)
        for (const auto& a : r.associations) {
          if (a.kind != sgraph::PlaneAssociation::Kind::PlanWall || (a.wall != 3 && a.wall != 4)) continue;
          EXPECT_EQ(a.wall, expected) << "lining " << (truth == &plan) << ", initial error " << error_x;
          ++matched;
        }
      EXPECT_GE(matched, 3);
      EXPECT_LT(rms(o.error_m, 1), 0.03);
    }
  }
}

TEST(SGraphTracker, UnmappedWallsBecomeNewPlanesAndAWallFarOffItsPlanIsMergedByItsRoom) {
  // In office R101: a free-standing panel the plan does not have, and the divider to R102
  // built 0.4 m into R101 (beyond the association gate). The panel becomes a new plane; the
  // divider too at first, until the room it closes matches R101 and it merges with its wall.
  const std::size_t divider = wallIndex(office(), "DIV-S1");
  bim::Storey truth = test::shiftedWall(office(), divider, 0.40);  // faces[0] looks -x, into R101
  truth.walls.push_back(test::boxWall("PANEL", {1.0, 3.65}, {3.0, 3.65}, 0.1));  // south face at y = 3.6
  static const sim::BaseTrajectory room =
      plannedWalk({1.0, 1.0, 0.0}, {{2.8, 1.0}, {2.8, 2.8}, {1.0, 2.8}, {1.0, 1.0}, {2.8, 1.0}, {2.8, 2.6}, {1.5, 2.0}}, 40.0);
  Walk w = onTrajectory(room);
  // Two x walls in view, one 0.4 m off: which one is off only the initial pose can say, so
  // it is good here (the particle filter's own spread in a room it has seen from all sides).
  w.initial_error = {0.05, -0.05, 1.0 * kDeg};
  w.truth = &truth;
  const Outcome o = run(w);
  int merged = 0;
  for (const auto& r : o.keyframes) merged += r.planes_merged;
  EXPECT_GE(merged, 1);
  const auto deviation = std::find_if(o.deviations.begin(), o.deviations.end(), [&](const auto& d) { return d.wall == int(divider); });
  ASSERT_NE(deviation, o.deviations.end());
  EXPECT_NEAR(deviation->offset_m, 0.40, 0.03);
  ASSERT_EQ(o.new_planes.size(), 1u);  // the panel's south face
  const auto& panel = o.new_planes[0];
  EXPECT_NEAR(panel.normal.y(), -1.0, 0.01);
  // n·p + d = 0 at y = 3.6; to 5 cm: the only plan wall across it in view is the outer wall,
  // so the robot's y (and what it maps) is known to that wall's as-built tolerance.
  EXPECT_NEAR(-panel.d / panel.normal.y(), 3.6, 0.05);
  EXPECT_LT(rms(o.error_m, 2), 0.04);
  for (const auto& r : o.keyframes) EXPECT_EQ(r.state, sgraph::TrackingState::Tracking);
  std::printf("divider 0.4 m off: estimated %.3f m after %d merge(s); panel at y = %.3f\n", deviation->offset_m, merged,
              -panel.d / panel.normal.y());
}

TEST(SGraphTracker, TwoNewPlanesAcrossARoomDoNotMoveItsWalls) {
  // Office R101 with its south and north walls both built 0.4 m north of the plan (beyond the
  // association gate): from inside, just what a robot 0.4 m south of its estimate would see.
  // Nothing the map knows says the room is there; its walls stay unmerged new planes, and the
  // robot's y is held by its history, not dragged by them.
  bim::Storey truth = test::shiftedWall(office(), wallIndex(office(), "EXT-S"), 0.40);
  truth = test::shiftedWall(truth, wallIndex(office(), "PART-S"), 0.40);
  static const sim::BaseTrajectory room =
      plannedWalk({1.0, 1.3, 0.0}, {{2.8, 1.3}, {2.8, 2.8}, {1.0, 2.8}, {1.0, 1.3}, {2.8, 1.3}}, 30.0);
  Walk w = onTrajectory(room);
  w.initial_error = {0.05, -0.05, 1.0 * kDeg};
  w.truth = &truth;
  const Outcome o = run(w);
  int merged = 0;
  for (const auto& r : o.keyframes) merged += r.planes_merged;
  EXPECT_EQ(merged, 0);
  EXPECT_LT(rms(o.error_m, 2), 0.1);
  std::printf("two walls across R101 0.4 m off: %d merge(s), robot RMS %.3f m, max %.3f m\n", merged, rms(o.error_m, 2),
              *std::max_element(o.error_m.begin() + 2, o.error_m.end()));
}

bool contains(const std::vector<std::string>& warnings, const std::string& text) {
  return std::any_of(warnings.begin(), warnings.end(), [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

TEST(SGraphTracker, BadInputIsWarnedAboutAndTrackingGoesOn) {
  bim::Storey plan = office();
  bim::Wall zero = plan.walls[0];
  zero.id = zero.name = "ZERO";
  zero.end = zero.start;
  plan.walls.push_back(zero);
  Walk w = onTrajectory(officeWalk());
  w.plan = &plan;
  w.config.window_keyframes = 0;  // impossible: 2 are used
  w.nan_pose_at = 30;
  w.nan_plane_from = 60;
  const Outcome o = run(w);
  EXPECT_TRUE(contains(o.plan_warnings, "'ZERO' (ZERO) is not a landmark: it has zero length"));
  EXPECT_TRUE(contains(o.plan_warnings, "window_keyframes = 0"));
  EXPECT_TRUE(contains(o.warnings, "not a finite rigid transform, scan skipped"));
  EXPECT_TRUE(contains(o.warnings, "not a finite plane, not used"));
  EXPECT_LE(o.max_window, 2);
  EXPECT_LT(rms(o.error_m, 2), 0.05);
  for (const auto& r : o.keyframes) EXPECT_EQ(r.state, sgraph::TrackingState::Tracking);
}

TEST(SGraphTracker, BeforeAndAtItsFirstScanTheTrackerHasItsInitialPose) {
  const Eigen::Isometry3d T_map_odom = test::pose(3.0, 4.0, 0.5, 0.0);
  sgraph::SGraphTracker tracker(office(), sim::Vlp16Config{}.T_base_lidar, {}, T_map_odom);
  EXPECT_TRUE(tracker.keyframes().empty());
  EXPECT_TRUE(tracker.wallDeviations().empty());
  EXPECT_TRUE(tracker.newPlanes().empty());
  EXPECT_TRUE(T_map_odom.isApprox(tracker.T_map_odom()));
  // A first scan with no walls at all: a keyframe at the initial pose, nothing to optimize.
  const Eigen::Isometry3d T_odom_base = test::pose(1.0, 0.0, 0.0);
  const auto r = tracker.addScan(0.0, T_odom_base, {});
  EXPECT_TRUE(r.keyframe_added);
  EXPECT_TRUE(r.T_map_base.isApprox(T_map_odom * T_odom_base, 1e-9));
  EXPECT_EQ(r.state, sgraph::TrackingState::Tracking);
  EXPECT_EQ(tracker.keyframes().size(), 1u);
}

TEST(SGraphTracker, WithoutWallsForLongItReportsLostThenRecovers) {
  Walk w = onTrajectory(officeWalk());
  w.blind_from = 100, w.blind_to = 250;  // 15 s along the corridor, about 10 keyframes
  const Outcome o = run(w);
  EXPECT_TRUE(contains(o.warnings, "lost: 5 bad keyframes in a row (last: 0 plan walls matched)"));
  EXPECT_TRUE(contains(o.warnings, "tracking again"));
  EXPECT_EQ(o.keyframes.back().state, sgraph::TrackingState::Tracking);
  // Odometry bridged the gap: the walls were found again where they were.
  EXPECT_LT(o.error_m.back(), 0.05);
}

TEST(SGraphTracker, AnOdometryJumpIsWarnedAndNeverTrackedConfidentlyWrong) {
  Walk w = onTrajectory(officeWalk());
  w.jump_from = 150;  // the odometry moves 3 m in one scan, and stays off
  const Outcome o = run(w);
  EXPECT_TRUE(contains(o.warnings, "odometry jumped by 3.00 m"));
  // Wherever the estimate is off (more than 0.3 m), the tracker says lost, at the latest after
  // lost_after_keyframes keyframes; or the map pulled it back.
  int confidently_wrong = 0;
  for (std::size_t i = 0; i < o.keyframes.size(); ++i)
    if (o.error_m[i] > 0.3 && o.keyframes[i].state == sgraph::TrackingState::Tracking) ++confidently_wrong;
  EXPECT_LE(confidently_wrong, w.config.lost_after_keyframes);
  std::printf("after a 3 m odometry jump: final error %.2f m, state %s, %d keyframes off and not yet lost\n", o.error_m.back(),
              sgraph::toString(o.keyframes.back().state), confidently_wrong);
}

TEST(SGraphTracker, TracksOnPlanesExtractedFromSimulatedLidarScans) {
  // The real chain: Embree ray casting of the VLP-16 in the office's meshes, then the plane
  // extraction's sequential RANSAC, at every keyframe.
  Walk w = onTrajectory(officeWalk());
  w.lidar = [](const Eigen::Isometry3d& T_map_base) { return test::wallsSeenFrom(T_map_base, sim::Vlp16Config{}.T_base_lidar); };
  const Outcome o = run(w);
  ASSERT_GE(o.keyframes.size(), 20u);
  const double tracked = rms(o.error_m, 2);
  EXPECT_LT(tracked, 0.05);
  for (std::size_t i = 2; i < o.keyframes.size(); ++i) {
    EXPECT_LT(o.error_m[i], 0.12) << "keyframe " << i;
    EXPECT_EQ(o.keyframes[i].state, sgraph::TrackingState::Tracking);
  }
  EXPECT_LT(tracked, 0.5 * rms(o.odometry_error_m, 2));
  std::printf("office walk on extracted planes: RMS %.3f m, max %.3f m, %zu new planes\n", tracked,
              *std::max_element(o.error_m.begin() + 2, o.error_m.end()), o.new_planes.size());
}

TEST(SGraphTracker, TimePerKeyframeStaysFlatOverATenMinuteWalk) {
  std::vector<std::string> tour;
  for (int lap = 0; lap < 4; ++lap)
    for (const char* room : {"R105", "R101", "R106", "R102", "R107", "R103", "R108", "R104", "W100", "S100", "C100"}) tour.push_back(room);
  static const sim::BaseTrajectory walk = plannedWalk({2.0, 6.1, 0.0}, {}, 600.0, sim::MotionConfig::Kind::Tour, tour);
  Walk w = onTrajectory(walk);
  const Outcome o = run(w);
  ASSERT_GT(o.keyframes.size(), 200u);
  EXPECT_LE(o.max_window, w.config.window_keyframes);
  auto meanTime = [&](double from_s, double to_s) {
    double sum = 0;
    int n = 0;
    for (std::size_t i = 0; i < o.time_s.size(); ++i)
      if (o.stamp_s[i] >= from_s && o.stamp_s[i] < to_s) sum += o.time_s[i], ++n;
    return n > 0 ? sum / n : 0.0;
  };
  const double first = meanTime(0, 60), last = meanTime(540, 600);
  std::printf("ms per keyframe, minute by minute:");  // the prior fills up to its bound, then stays
  for (int m = 0; m < 10; ++m) std::printf(" %.2f", 1e3 * meanTime(60 * m, 60 * (m + 1)));
  std::printf("\n");
  EXPECT_LT(last, 3 * first + 0.002);  // flat, with room for a busy machine
  EXPECT_LT(rms(o.error_m, 2), 0.05);
  int lost = 0;
  for (const auto& r : o.keyframes) lost += r.state == sgraph::TrackingState::Lost;
  EXPECT_EQ(lost, 0);
  double iterations = 0, solve_s = 0;
  for (const auto& r : o.keyframes) iterations += r.iterations, solve_s += r.solve_time_s;
  std::printf("10-minute walk (%.0f m): %zu keyframes, %.2f ms per keyframe in the first minute, %.2f ms in the last "
              "(Ceres %.2f ms, %.1f iterations on average); RMS %.3f m, max %.3f m, odometry alone %.2f m\n",
              walk.distance_m(600), o.keyframes.size(), 1e3 * first, 1e3 * last, 1e3 * solve_s / o.keyframes.size(),
              iterations / o.keyframes.size(), rms(o.error_m, 2), *std::max_element(o.error_m.begin() + 2, o.error_m.end()),
              rms(o.odometry_error_m, 2));
}

TEST(SGraphTracker, WithTwoParallelWallsInViewTheRobotsHistorySaysWhichIsOff) {
  // The divider between R101 and R102 stands 10 cm into R101. In R101 the robot sees two x
  // walls, the outer one and the divider: which is off, only the way it came in can say.
  // It comes from the corridor, localized there.
  const std::size_t divider = wallIndex(office(), "DIV-S1");
  const bim::Storey truth = test::shiftedWall(office(), divider, 0.10);
  static const sim::BaseTrajectory walk =
      plannedWalk({8.0, 6.1, M_PI}, {{3.2, 6.1}, {3.2, 4.3}, {2.6, 2.8}, {1.0, 2.8}, {1.0, 1.0}, {2.8, 1.0}, {2.8, 2.6}}, 40.0);
  Walk w = onTrajectory(walk);
  w.truth = &truth;
  w.initial_error = {0.05, 0.0, 1.0 * kDeg};
  const Outcome o = run(w);
  const auto deviation = std::find_if(o.deviations.begin(), o.deviations.end(), [&](const auto& d) { return d.wall == int(divider); });
  ASSERT_NE(deviation, o.deviations.end());
  std::printf("divider 10 cm off, two x walls in view: estimated %.3f m; robot RMS %.3f m, max %.3f m\n", deviation->offset_m,
              rms(o.error_m, 2), *std::max_element(o.error_m.begin() + 2, o.error_m.end()));
  EXPECT_NEAR(deviation->offset_m, 0.10, 0.03);
  EXPECT_LT(rms(o.error_m, 2), 0.03);
}

TEST(SGraphTracker, ALongWallSeenAtOneEndDoesNotTurnAndCarryTheRobot) {
  // A corridor along x (faces y = 0.1 and 2.9), a branch north at x 28-34; its west wall X,
  // 57 m long, is the only wall across the corridor. On the site X stands 1.5 deg off its plan,
  // turned about its south end: at the corridor it is where the plan has it, and its far end
  // is 1.5 m off. A wall's angle is known to the as-built tolerance over half its length
  // (0.1 deg here), not to 1 deg: turned about its centre by its observed 1.5 deg, X's south
  // end would move 0.75 m along the corridor and carry the robot with it (random school
  // 98006 on a construction site: 0.55 m, 1.4 deg).
  const auto storeyWith = [](double x_turn_rad) {
    bim::Storey s;
    s.name = "L0";
    s.walls.push_back(test::boxWall("S", {0, 0}, {60, 0}, 0.2));
    s.walls.push_back(test::boxWall("N-W", {0, 3}, {28, 3}, 0.2));
    s.walls.push_back(test::boxWall("N-E", {34, 3}, {60, 3}, 0.2));
    s.walls.push_back(test::boxWall("X", {28.1, 3}, {28.1 + 57 * std::sin(x_turn_rad), 3 + 57 * std::cos(x_turn_rad)}, 0.2));
    s.walls.push_back(test::boxWall("Y", {34, 3}, {34, 60}, 0.2));
    return s;
  };
  const bim::Storey plan = storeyWith(0.0), truth = storeyWith(-1.5 * kDeg);
  Walk w;
  w.plan = &plan;
  w.truth = &truth;
  w.openings = {};
  w.pose = [](double t) {
    return Eigen::Isometry3d(Eigen::Translation3d(42.0 - 0.8 * t, 1.5, 0.0) * Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()));
  };
  w.duration_s = 12.0;
  w.initial_error = {0.05, 0.0, 0.5 * kDeg};
  const Outcome o = run(w);
  ASSERT_GE(o.error_m.size(), 5u);
  const double worst = *std::max_element(o.error_m.begin(), o.error_m.end());
  std::printf("X turned 1.5 deg about its corridor end: robot max error %.3f m over %zu keyframes\n", worst, o.error_m.size());
  // With a 1 deg angle prior: 0.47 m and growing along the walk (checked by hand).
  EXPECT_LT(worst, 0.25);
}

TEST(SGraphLoss, PlanesInAPlanWallsPlaneDoNotCountAgainstTheTrackPlanesOffEveryPlaneDo) {
  // Two box walls along y = 0 and y = 4 (faces at y = ±0.05, 3.95 / 4.05), 10 m long. A keyframe
  // matches the south wall's north face; it also sees two y planes unmatched to the plan:
  //  - in line with that face but beyond the wall's ends (x = 14, x = -4): elements the plan's walls do
  //    not cover, agreeing with the plan along y: not a contradiction;
  //  - behind the north wall (y = 5.55), where the plan says no plane can be seen: what a robot
  //    off along a corridor sees: counts, with the north wall in clear view and not seen.
  //    (Before the south wall, y = 1.55, such planes are clutter the plan does not hold: they
  //    do not count; SGraphLoss.ClutterInASmallRoomIsNoLossAWrongPoseStillIs.)
  bim::Storey storey;
  storey.walls = {test::boxWall("S", {0, 0}, {10, 0}, 0.1), test::boxWall("N", {0, 4}, {10, 4}, 0.1)};
  sgraph::detail::Graph g;
  std::vector<std::string> warnings;
  sgraph::detail::buildPlanLayers(storey, g, warnings);
  sgraph::detail::Keyframe kf;
  kf.pose = {5.0, 2.0, 0.0};
  const auto observation = [](int index, double x, double y) {
    sgraph::detail::ScanObservation o;
    o.index = index;
    o.normal_map = Eigen::Vector2d(0, 1);  // looking north: towards the robot at y = 2
    o.centroid_map = Eigen::Vector2d(x, y);
    o.axis = bim::WallAxis::Y;
    o.extent_m = 2.0;
    return o;
  };
  // The match: observation 0 on the south wall's face that looks north.
  int south_node = -1, face = -1;
  for (std::size_t n = 0; n < g.nodes.size(); ++n)
    for (int f = 0; f < 2; ++f)
      if (g.nodes[n].kind == sgraph::detail::WallNode::Kind::Plan && g.nodes[n].normal(f).y() > 0.9 && g.nodes[n].d(f) > -0.5)
        south_node = static_cast<int>(n), face = f;
  ASSERT_GE(south_node, 0);
  sgraph::detail::PlaneMeasurement m;
  m.node = south_node, m.face = face, m.observation = 0;
  kf.planes.push_back(m);
  kf.plan_walls = 1;
  sgraph::SGraphConfig config;
  config.min_plan_associations = 1;
  // (With them counted, 1 of 3 would be matched: the keyframe would be bad.)
  const std::string in_line =
      sgraph::detail::keyframeDoubt(g, kf, {observation(0, 5, 0.05), observation(1, 14, 0.07), observation(2, -4, 0.02)}, true, config);
  EXPECT_EQ(in_line.find("walls matched the plan"), std::string::npos) << in_line;
  const std::string off = sgraph::detail::keyframeDoubt(g, kf, {observation(0, 5, 0.05), observation(1, 5, 5.55), observation(2, 7, 5.55)}, true, config);
  EXPECT_NE(off.find("1 of 4 y walls matched the plan (2 planes behind a plan wall, 1 plan walls in view unseen)"), std::string::npos)
      << off;
  const std::string clutter =
      sgraph::detail::keyframeDoubt(g, kf, {observation(0, 5, 0.05), observation(1, 5, 1.55), observation(2, 7, 1.55)}, true, config);
  EXPECT_EQ(clutter.find("walls matched the plan"), std::string::npos) << clutter;
}

TEST(SGraphLoss, ClutterInASmallRoomIsNoLossAWrongPoseStillIs) {
  // A 3 x 3 m room (walls 0.1 m thick, inner faces at 0.05 and 2.95). The robot stands at its
  // centre and sees its four walls and five planes of clutter in the open (furniture, stacked
  // material: the site has them, the plan does not). The truth is the geometry: what the lidar
  // sees from the true pose, put in the map by the pose the keyframe holds.
  bim::Storey storey;
  storey.walls = {test::boxWall("S", {0, 0}, {3, 0}, 0.1), test::boxWall("E", {3, 0}, {3, 3}, 0.1),
                  test::boxWall("N", {3, 3}, {0, 3}, 0.1), test::boxWall("W", {0, 3}, {0, 0}, 0.1)};
  sgraph::detail::Graph g;
  std::vector<std::string> warnings;
  sgraph::detail::buildPlanLayers(storey, g, warnings);
  struct Seen {
    Eigen::Vector2d normal, centroid;  // in the robot's frame (x east, y north: no turn); the normal looks at it
    double extent_m;
  };
  const Eigen::Vector2d robot(1.5, 1.5);
  std::vector<Seen> seen = {{{1, 0}, Eigen::Vector2d(0.05, 1.5) - robot, 2.8}, {{-1, 0}, Eigen::Vector2d(2.95, 1.5) - robot, 2.8},
                            {{0, 1}, Eigen::Vector2d(1.5, 0.05) - robot, 2.8}, {{0, -1}, Eigen::Vector2d(1.5, 2.95) - robot, 2.8},
                            {{1, 0}, Eigen::Vector2d(0.8, 1.0) - robot, 0.6},  {{-1, 0}, Eigen::Vector2d(2.5, 2.0) - robot, 0.6},
                            {{0, 1}, Eigen::Vector2d(1.0, 0.7) - robot, 0.6},  {{0, -1}, Eigen::Vector2d(2.0, 2.3) - robot, 0.6},
                            {{0, 1}, Eigen::Vector2d(0.6, 1.1) - robot, 0.6}};
  // The plan face whose plane holds a map point, looking along `normal`; -1 none.
  const auto planFace = [&](const Eigen::Vector2d& normal, const Eigen::Vector2d& p, int& face) {
    for (std::size_t n = 0; n < g.nodes.size(); ++n)
      for (int f = 0; f < 2; ++f)
        if (g.nodes[n].normal(f).dot(normal) > 0.99 && std::abs(g.nodes[n].normal(f).dot(p) + g.nodes[n].d(f)) < 0.02 &&
            g.nodes[n].along(f, p) > 0 && g.nodes[n].along(f, p) < g.nodes[n].length(f))
          return face = f, static_cast<int>(n);
    return -1;
  };
  // A keyframe at `estimate` (the robot truly at the centre): the planes in the map by the
  // estimate, each matched to the plan face it lies on (as the association does, within 2 cm).
  const auto keyframeAt = [&](const Eigen::Vector2d& estimate, std::vector<sgraph::detail::ScanObservation>& observed) {
    sgraph::detail::Keyframe kf;
    kf.pose = {estimate.x(), estimate.y(), 0.0};
    kf.predicted = kf.planar();  // the odometry agrees: only what the planes say is asked
    observed.clear();
    for (std::size_t i = 0; i < seen.size(); ++i) {
      sgraph::detail::ScanObservation o;
      o.index = static_cast<int>(i);
      o.normal_map = seen[i].normal;
      o.centroid_map = estimate + seen[i].centroid;
      o.axis = std::abs(o.normal_map.x()) > 0.5 ? bim::WallAxis::X : bim::WallAxis::Y;
      o.extent_m = seen[i].extent_m;
      observed.push_back(o);
      int face = 0;
      const int node = planFace(o.normal_map, o.centroid_map, face);
      if (node < 0) continue;
      sgraph::detail::PlaneMeasurement m;
      m.node = node, m.face = face, m.observation = o.index;
      kf.planes.push_back(m);
      ++kf.plan_walls;
    }
    return kf;
  };
  sgraph::SGraphConfig config;
  std::vector<sgraph::detail::ScanObservation> observed;
  // At the truth: four walls matched; the clutter (2 x, 3 y planes) outnumbers the walls of
  // its class, and is in the open: no doubt, never lost.
  sgraph::detail::LossMonitor right(config);
  for (int k = 0; k < 2 * config.lost_after_keyframes; ++k) {
    const auto kf = keyframeAt(robot, observed);
    ASSERT_EQ(kf.plan_walls, 4);
    const std::string doubt = sgraph::detail::keyframeDoubt(g, kf, observed, true, config);
    EXPECT_EQ(doubt, "") << doubt;
    EXPECT_EQ(right.update(doubt, warnings), sgraph::TrackingState::Tracking);
  }
  // 1 m off in x: the y walls still match (along their length), the x walls do not: the east
  // wall and a cupboard seen behind the east plan face, and that face in clear view unseen
  // (the west wall, seen in the open, hides the west plan face: no evidence either way).
  sgraph::detail::LossMonitor wrong(config);
  sgraph::TrackingState state = sgraph::TrackingState::Tracking;
  std::string last;
  for (int k = 0; k < config.lost_after_keyframes; ++k) {
    const auto kf = keyframeAt(robot + Eigen::Vector2d(1.0, 0.0), observed);
    ASSERT_EQ(kf.plan_walls, 2);
    last = sgraph::detail::keyframeDoubt(g, kf, observed, true, config);
    state = wrong.update(last, warnings);
  }
  EXPECT_NE(last.find("0 of 3 x walls matched the plan (2 planes behind a plan wall, 1 plan walls in view unseen)"), std::string::npos)
      << last;
  EXPECT_EQ(state, sgraph::TrackingState::Lost);
}
