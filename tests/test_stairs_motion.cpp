// The legged base from floor to floor (issue 31), on a two-storey house built in code: one
// 8 x 4 m room per storey, a straight flight of 16 risers of 0.1875 m and 15 goings of 0.28 m
// along x between them, the upper floor open above the flight. The truths are the flight's own
// numbers: the height along the run line, the slope atan(rise / run), the storey on each side.
#include "sim/base/base_trajectory.hpp"
#include "sim/base/gait.hpp"
#include "sim/base/stair_links.hpp"
#include "sim/odometry/barometer.hpp"
#include "sim/odometry/odometry_model.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/simulation/simulator.hpp"
#include "sim/world/world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace bimloc;
using sim::World;

namespace {

constexpr double kStoreyHeight_m = 3.0;
constexpr int kRisers = 16;
constexpr double kRiser_m = kStoreyHeight_m / kRisers;  // 0.1875
constexpr double kGoing_m = 0.28;
const Eigen::Vector3d kBottom(1.0, 1.0, 0.0);
const Eigen::Vector3d kTop(1.0 + (kRisers - 1) * kGoing_m, 1.0, kStoreyHeight_m);  // x = 5.2

void addBox(bim::TriangleMesh& mesh, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  for (int i = 0; i < 8; ++i)
    mesh.vertices.emplace_back(float(i & 1 ? hi.x() : lo.x()), float(i & 2 ? hi.y() : lo.y()), float(i & 4 ? hi.z() : lo.z()));
  const std::uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    mesh.triangles.push_back({base + f[0], base + f[1], base + f[2]});
    mesh.triangles.push_back({base + f[0], base + f[2], base + f[3]});
  }
}

// A storey: floor slab (with an opening over the flight for the upper one), four walls, and
// (on the ground floor) the flight's steps.
bim::Storey storey(int index) {
  bim::Storey s;
  const double z0 = index * kStoreyHeight_m;
  s.id = "S" + std::to_string(index), s.name = index == 0 ? "Ground" : "Upper", s.elevation_m = z0;
  bim::Room room;
  room.id = "R" + std::to_string(index), room.name = room.id;
  room.footprint = {{0, 0}, {8, 0}, {8, 4}, {0, 4}};
  room.area_m2 = 32, room.centre = {4, 2}, room.floor_z = z0, room.height_m = kStoreyHeight_m;
  s.rooms.push_back(room);
  if (index == 0) {
    addBox(s.mesh, {-0.2, -0.2, z0 - 0.2}, {8.2, 4.2, z0});
  } else {  // around the opening x in [1, 5.2], y in [0.5, 1.5]
    addBox(s.mesh, {-0.2, -0.2, z0 - 0.2}, {1.0, 4.2, z0});
    addBox(s.mesh, {5.2, -0.2, z0 - 0.2}, {8.2, 4.2, z0});
    addBox(s.mesh, {1.0, 1.5, z0 - 0.2}, {5.2, 4.2, z0});
    addBox(s.mesh, {1.0, -0.2, z0 - 0.2}, {5.2, 0.5, z0});
    addBox(s.mesh, {-0.2, -0.2, z0 + kStoreyHeight_m}, {8.2, 4.2, z0 + kStoreyHeight_m + 0.2});  // roof
    // The balustrade round the opening, open at the flight's head (x = 5.2).
    addBox(s.mesh, {1.0, 1.5, z0}, {5.2, 1.55, z0 + 1.0});
    addBox(s.mesh, {0.95, 0.0, z0}, {1.0, 1.55, z0 + 1.0});
  }
  const double top = z0 + kStoreyHeight_m - (index == 0 ? 0.2 : 0.0);
  addBox(s.mesh, {-0.2, -0.2, z0}, {0.0, 4.2, top});
  addBox(s.mesh, {8.0, -0.2, z0}, {8.2, 4.2, top});
  addBox(s.mesh, {-0.2, -0.2, z0}, {8.2, 0.0, top});
  addBox(s.mesh, {-0.2, 4.0, z0}, {8.2, 4.2, top});
  if (index == 0)  // step k's tread at height (k + 1) riser, from the nosing line of step k
    for (int k = 0; k + 1 < kRisers; ++k)
      addBox(s.mesh, {kBottom.x() + k * kGoing_m, 0.5, 0.0}, {kBottom.x() + (k + 1) * kGoing_m, 1.5, (k + 1) * kRiser_m});
  return s;
}

bim::Building twoStoreyHouse() {
  bim::Building b;
  b.file = "two-storey house (test)";
  b.storeys = {storey(0), storey(1)};
  bim::StairFlight f;
  f.id = f.stair_id = "F1", f.name = "Flight", f.ifc_type = "IfcStairFlight";
  f.bottom = kBottom, f.top = kTop, f.width_m = 1.0;
  f.risers = kRisers, f.riser_height_m = kRiser_m, f.going_m = kGoing_m;
  f.bottom_storey = 0, f.top_storey = 1, f.source = "test";
  b.stairs.push_back(f);
  return b;
}

const World& house() {
  static const World world = World::fromBuilding(twoStoreyHouse());
  return world;
}

// A still body: no gait bob or rocking, so the pose is the planned motion itself.
sim::MotionConfig stillGait() {
  sim::MotionConfig m;
  m.kind = sim::MotionConfig::Kind::Tour;
  m.gait.bob_amplitude_m = m.gait.roll_amplitude_deg = m.gait.pitch_amplitude_deg = 0.0;
  return m;
}

// Up to the upper room, then back down to the ground floor's.
sim::BaseTrajectory upAndDown(const sim::MotionConfig& base = stillGait()) {
  sim::MotionConfig m = base;
  m.kind = sim::MotionConfig::Kind::Tour;
  m.rooms = {"R1", "R0"};
  m.storeys = {"Upper", "Ground"};
  return sim::BaseTrajectory::plan(house(), 0, {6.5, 3.0, 0.0}, m, 120.0, 7);
}

Eigen::Isometry3d at(double x, double y, double z) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

double slopeOf(const Eigen::Isometry3d& T) { return std::asin(std::clamp(T.linear()(2, 0), -1.0, 1.0)); }

}  // namespace

TEST(StairsMotion, LinksJoinTheStoreysBothWays) {
  const auto links = sim::stairLinks(house().building());
  ASSERT_EQ(links.size(), 2u);
  const auto route = sim::stairRoute(links, 0, 1);
  ASSERT_TRUE(route);
  ASSERT_EQ(route->size(), 1u);
  EXPECT_TRUE(route->front()->up);
  EXPECT_EQ(sim::reachableStoreys(links, 1), (std::vector<std::size_t>{1, 0}));
  // A flight whose top ends on a half landing only joins the storeys through the next flight.
  bim::Building b = twoStoreyHouse();
  b.stairs[0].top_storey = -1;
  EXPECT_TRUE(sim::stairLinks(b).empty());
  bim::StairFlight second = b.stairs[0];
  second.id = "F2", second.bottom = kTop, second.top = kTop + Eigen::Vector3d(0, 1, 1.5);
  second.bottom_storey = -1, second.top_storey = 1;
  b.stairs.push_back(second);
  const auto chained = sim::stairLinks(b);
  ASSERT_EQ(chained.size(), 2u);
  EXPECT_EQ(chained[0].flights.size(), 2u);
  EXPECT_EQ(chained[0].to, 1u);
}

TEST(StairsMotion, PlannerFindsAPathBetweenStoreys) {
  const sim::BaseTrajectory tr = upAndDown();
  EXPECT_EQ(tr.storeys(), (std::vector<std::size_t>{0, 1}));
  EXPECT_TRUE(tr.multiStorey());
  EXPECT_EQ(tr.storey(0.0), 0u);
  EXPECT_LT(tr.script_duration_s(), 120.0);
  EXPECT_EQ(tr.storey(tr.script_duration_s()), 0u);  // back down
  // Up, on the upper floor a while, and down: two changes of storey, on the flight's far side.
  int changes = 0;
  std::size_t last = 0;
  double upper_time = 0.0;
  for (double t = 0.0; t <= tr.script_duration_s(); t += 0.05) {
    const std::size_t s = tr.storey(t);
    if (s != last) {
      ++changes;
      const Eigen::Vector3d p = tr.T_map_base(t).translation();
      EXPECT_FALSE(tr.onStairs(t));
      EXPECT_NEAR(p.z() - 0.5, s == 1 ? kTop.z() : kBottom.z(), 1e-6) << "t=" << t;
    }
    if (s == 1) upper_time += 0.05;
    last = s;
  }
  EXPECT_EQ(changes, 2);
  EXPECT_GT(upper_time, 5.0);
  // The room on the upper floor was reached: the base stood in its footprint above z 3.
  bool in_upper_room = false;
  for (double t = 0.0; t <= tr.script_duration_s(); t += 0.5) {
    const Eigen::Vector3d p = tr.T_map_base(t).translation();
    in_upper_room = in_upper_room || (tr.storey(t) == 1 && (p.head<2>() - Eigen::Vector2d(4, 2)).norm() < 1.5);
  }
  EXPECT_TRUE(in_upper_room);
}

TEST(StairsMotion, HeightFollowsTheFlightAndTheBodyPitchesWithIt) {
  const sim::BaseTrajectory tr = upAndDown();
  const double rise = kTop.z() - kBottom.z(), run = (kTop - kBottom).head<2>().norm();
  const double slope = std::atan2(rise, run);
  int on_flight = 0, off_flight = 0;
  bool went_down = false;
  for (double t = 0.0; t <= tr.script_duration_s(); t += 0.02) {
    const Eigen::Isometry3d T = tr.T_map_base(t);
    const Eigen::Vector3d p = T.translation();
    if (tr.onStairs(t)) {
      ++on_flight;
      // z linear in the progress along the run line, within a step's height of the treads.
      const double progress = (p.head<2>() - kBottom.head<2>()).dot((kTop - kBottom).head<2>().normalized()) / run;
      EXPECT_NEAR(p.z() - 0.5, kBottom.z() + progress * rise, 1e-6);
      EXPECT_NEAR(p.z() - 0.5, std::floor(progress * kRisers) * kRiser_m, kRiser_m + 1e-9);
      EXPECT_NEAR(std::abs(p.y() - kBottom.y()), 0.0, 1e-6);  // on the run line
      // Nose up going up (heading +x), nose down going down: slope along the travel.
      const double heading = std::atan2(T.linear()(1, 0), T.linear()(0, 0));
      const double expected = std::cos(heading) > 0 ? slope : -slope;
      EXPECT_NEAR(slopeOf(T), expected, 1e-6) << "t=" << t;
      went_down = went_down || expected < 0;
    } else {
      ++off_flight;
      EXPECT_NEAR(slopeOf(T), 0.0, 1e-9) << "t=" << t;
    }
  }
  EXPECT_GT(on_flight, 100);
  EXPECT_GT(off_flight, 100);
  EXPECT_TRUE(went_down);
}

TEST(StairsMotion, GaitIsSlowerOnTheFlight) {
  const sim::BaseTrajectory tr = upAndDown();
  const sim::MotionConfig m = stillGait();
  const double stair_speed = sim::stairSpeed_mps(house().building().stairs[0], m);
  EXPECT_NEAR(stair_speed, kGoing_m * m.gait.step_frequency_hz / 2.0, 1e-12);  // one tread per stride
  double fastest_on = 0.0, fastest_off = 0.0;
  const double dt = 0.02;
  for (double t = dt; t <= tr.script_duration_s(); t += dt) {
    const double v = (tr.T_map_base(t).translation() - tr.T_map_base(t - dt).translation()).head<2>().norm() / dt;
    if (tr.onStairs(t) && tr.onStairs(t - dt)) fastest_on = std::max(fastest_on, v);
    if (!tr.onStairs(t) && !tr.onStairs(t - dt)) fastest_off = std::max(fastest_off, v);
  }
  EXPECT_LE(fastest_on, stair_speed + 1e-6);
  EXPECT_GT(fastest_on, 0.9 * stair_speed);  // it does walk the flight at that pace
  EXPECT_GT(fastest_off, 2.0 * stair_speed);
  // A ramp (no risers): half the speed limit.
  bim::StairFlight ramp = house().building().stairs[0];
  ramp.risers = 0;
  EXPECT_NEAR(sim::stairSpeed_mps(ramp, m), 0.5 * m.max_speed_mps, 1e-12);
}

TEST(StairsMotion, WithTheGaitTheSlopeStaysWithinTheGaitsPitch) {
  const sim::BaseTrajectory tr = upAndDown(sim::MotionConfig{});  // default gait
  const double slope = std::atan2(kTop.z() - kBottom.z(), (kTop - kBottom).head<2>().norm());
  const double gait_pitch = sim::GaitConfig{}.pitch_amplitude_deg * M_PI / 180.0;
  int up = 0;
  for (double t = 0.0; t <= tr.script_duration_s(); t += 0.05) {
    if (!tr.onStairs(t) || tr.storey(t) != 0 || tr.T_map_base(t).linear()(0, 0) <= 0) continue;  // going up only
    ++up;
    EXPECT_NEAR(slopeOf(tr.T_map_base(t)), slope, gait_pitch + 0.02);
  }
  EXPECT_GT(up, 50);
}

TEST(StairsMotion, NoStairsNoOtherStorey) {
  bim::Building b = twoStoreyHouse();
  b.stairs.clear();
  const World world = World::fromBuilding(std::move(b));
  sim::MotionConfig m = stillGait();
  m.rooms = {"R1"}, m.storeys = {"Upper"};
  try {
    sim::BaseTrajectory::plan(world, 0, {6.5, 3.0, 0.0}, m, 60.0, 7);
    FAIL() << "planned a tour to a storey no stairs lead to";
  } catch (const sim::MotionError& e) {
    EXPECT_NE(std::string(e.what()).find("no stairs lead from storey 'Ground' to storey 'Upper'"), std::string::npos) << e.what();
  }
  // --multi-storey there: the base stays on its storey.
  m.rooms.clear(), m.storeys.clear(), m.all_storeys = true, m.explore_after_tour = true;
  EXPECT_EQ(sim::BaseTrajectory::plan(world, 0, {6.5, 3.0, 0.0}, m, 30.0, 7).storeys(), (std::vector<std::size_t>{0}));
}

TEST(StairsMotion, MultiStoreyTourVisitsEveryStoreyReachable) {
  sim::MotionConfig m = stillGait();
  m.all_storeys = true, m.explore_after_tour = true, m.skip_unreachable_rooms = true;
  const sim::BaseTrajectory tr = sim::BaseTrajectory::plan(house(), 1, {6.5, 3.0, 0.0}, m, 90.0, 3);
  EXPECT_EQ(tr.storeys(), (std::vector<std::size_t>{1, 0}));
  EXPECT_EQ(tr.storey(0.0), 1u);
  EXPECT_EQ(tr.storey(89.0), 0u);
}

// A run that stays on the ground floor sees the whole building, as a robot there does: the upper
// storey's floor slab (its underside at 2.8 m, storey 1's element) is the ground floor's ceiling,
// and through the stair opening the upper storey's walls. A world of the ground storey's elements
// alone had neither: the rays went up into nothing. The lidar is mounted on its side (spinning
// about the base's x axis), so that it sees straight up.
TEST(StairsMotion, ARunOnOneStoreySeesTheStoreyAboveIt) {
  sim::Scenario s;
  s.file = s.world = "two-storey house (test)";
  s.storey = "Ground", s.name = "still";
  s.start.kind = sim::StartConfig::Kind::Pose;
  s.start.pose = {4.0, 2.5, 0.0};  // beside the opening (y 0.5-1.5), on the ground floor
  s.motion.kind = sim::MotionConfig::Kind::Stand;
  s.duration_s = 0.2;
  s.sensor.T_base_lidar = Eigen::Translation3d(0.0, 0.0, 0.25) * Eigen::AngleAxisd(0.5 * M_PI, Eigen::Vector3d::UnitY());
  const sim::Simulator sim(s, house());
  ASSERT_FALSE(sim.trajectory().multiStorey());
  EXPECT_EQ(sim.lidarStorey(), World::kAllStoreys);
  const auto scan = sim.turn(0);
  int under_slab = 0, upper = 0;
  for (const auto& p : scan.points) {
    // In the map: the base stands still (its gait's bob is a few millimetres).
    const Eigen::Vector3d q = sim.trajectory().T_map_base(scan.stamp_s) * s.sensor.T_base_lidar * Eigen::Vector3d(p.x, p.y, p.z);
    if (std::abs(q.z() - (kStoreyHeight_m - 0.2)) < 0.05 && q.y() > 1.6) ++under_slab;  // the slab's underside
    if (q.z() > kStoreyHeight_m + 0.05) ++upper;  // the upper storey, seen through the opening
  }
  EXPECT_GT(under_slab, 100);
  EXPECT_GT(upper, 0);
}

TEST(StairsMotion, LidarSeesEveryStoreyThroughTheOpening) {
  // Straight up through the opening from above the flight (step 7's tread, at x = 3, is 1.5 m
  // high: a ray from z = 1.5 starts on it and hits it at range 0, which is what this test, so
  // written, failed on): the ground storey's scene has nothing above; the whole building's has
  // the upper storey's roof at z 6.
  const Eigen::Vector3f origin(3.0f, 1.0f, 2.0f), up(0.0f, 0.0f, 1.0f), down(0.0f, 0.0f, -1.0f);
  EXPECT_FALSE(house().castRay(0, origin, up, 0.0f, 100.0f).hit());
  const sim::RayHit all = house().castRay(World::kAllStoreys, origin, up, 0.0f, 100.0f);
  ASSERT_TRUE(all.hit());
  EXPECT_NEAR(all.range_m, 2.0 * kStoreyHeight_m - origin.z(), 1e-4);
  // Down through the opening from the upper storey: its own scene has no floor there; the whole
  // building's has step 7's tread at 8 risers.
  const Eigen::Vector3f above(3.0f, 1.0f, 4.0f);
  EXPECT_FALSE(house().castRay(1, above, down, 0.0f, 100.0f).hit());
  const sim::RayHit tread = house().castRay(World::kAllStoreys, above, down, 0.0f, 100.0f);
  ASSERT_TRUE(tread.hit());
  EXPECT_NEAR(tread.range_m, above.z() - 8 * kRiser_m, 1e-4);
  // Beside the opening, the upper storey's floor slab (its top at z 3) in both scenes.
  const Eigen::Vector3f beside(3.0f, 3.0f, 4.0f);
  EXPECT_NEAR(house().castRay(1, beside, down, 0.0f, 100.0f).range_m, beside.z() - kStoreyHeight_m, 1e-4);
  EXPECT_NEAR(house().castRay(World::kAllStoreys, beside, down, 0.0f, 100.0f).range_m, beside.z() - kStoreyHeight_m, 1e-4);
  // The packet path agrees.
  Eigen::Vector3f origins[16], dirs[16];
  sim::RayHit hits[16];
  for (int i = 0; i < 16; ++i) origins[i] = i % 2 ? above : origin, dirs[i] = i % 2 ? down : up;
  house().castRays16(World::kAllStoreys, origins, dirs, 0.0f, 100.0f, hits, 16);
  EXPECT_NEAR(hits[6].range_m, all.range_m, 1e-5);
  EXPECT_NEAR(hits[7].range_m, tread.range_m, 1e-5);
}

// Odometry on a flight: the height it reports is off by a scale error of the height climbed
// (sigma stair_height_scale_sigma over seeds), and the feet slip (the increment noise scaled).
TEST(StairsMotion, OdometryHeightErrorGrowsWithTheClimbAsModelled) {
  const sim::OdometryConfig c = sim::odometryPreset("legged");
  const double rise = kTop.z() - kBottom.z(), run = (kTop - kBottom).head<2>().norm();
  const int steps = 400, seeds = 600;
  std::vector<double> errors;
  for (int seed = 1; seed <= seeds; ++seed) {
    sim::NoisyOdometry odom(c, static_cast<std::uint64_t>(seed));
    sim::OdometrySample last;
    for (int i = 0; i <= steps; ++i) {
      Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
      T.translation() = kBottom + Eigen::Vector3d(run * i / steps, 0, rise * i / steps + 0.5);
      last = odom.step(i * 0.02, T, true);
    }
    // Half-way up, half the error: linear in the height climbed.
    errors.push_back(last.T_odom_base.translation().z() - (rise + 0.5));  // the truth: base_link 0.5 m above the treads
    EXPECT_NEAR(errors.back(), odom.heightError_m(), 1e-9);
  }
  double mean = 0, var = 0;
  for (double e : errors) mean += e / seeds;
  for (double e : errors) var += (e - mean) * (e - mean) / (seeds - 1);
  EXPECT_NEAR(std::sqrt(var), c.stair_height_scale_sigma * rise, 0.1 * c.stair_height_scale_sigma * rise);
  EXPECT_NEAR(mean, 0.0, 4.0 * c.stair_height_scale_sigma * rise / std::sqrt(double(seeds)));
  // Off the flight, no height error at all.
  sim::NoisyOdometry flat(c, 5);
  for (int i = 0; i <= steps; ++i) flat.step(i * 0.02, at(i * 0.01, 0, 0.5));
  EXPECT_EQ(flat.heightError_m(), 0.0);
}

TEST(StairsMotion, OdometrySlipsOnTheFlight) {
  sim::OdometryConfig c = sim::odometryPreset("legged");
  c.scale_bias_sigma = c.scale_bias_walk_per_sqrt_m = 0.0;  // the increment noise alone
  c.yaw_bias_sigma_rad_per_m = c.yaw_bias_walk_rad_per_m_per_sqrt_m = 0.0;
  const auto spread = [&](bool stairs) {
    std::vector<double> along;
    for (int seed = 1; seed <= 800; ++seed) {
      sim::NoisyOdometry odom(c, static_cast<std::uint64_t>(seed));
      sim::OdometrySample last;
      for (int i = 0; i <= 200; ++i)
        last = odom.step(i * 0.02, at(i * 0.02, 0, 0.5), stairs && i > 0);
      along.push_back(last.T_odom_base.translation().x() - 4.0);
    }
    double m = 0, v = 0;
    for (double x : along) m += x / along.size();
    for (double x : along) v += (x - m) * (x - m) / (along.size() - 1);
    return std::sqrt(v);
  };
  const double flat = spread(false), stairs = spread(true);
  EXPECT_NEAR(stairs / flat, c.stair_slip_factor, 0.12 * c.stair_slip_factor);
  // And off the flight the readings are those of the model without stairs, draw for draw.
  sim::NoisyOdometry a(sim::odometryPreset("legged"), 9), b(sim::odometryPreset("legged"), 9);
  for (int i = 0; i <= 50; ++i) {
    const Eigen::Isometry3d T = at(i * 0.02, 0.001 * i * i, 0.5);
    EXPECT_TRUE(a.step(i * 0.02, T).T_odom_base.matrix() == b.step(i * 0.02, T, false).T_odom_base.matrix());
  }
}

TEST(StairsMotion, BarometerReadsTheAltitudeWithItsNoiseAndDrift) {
  const sim::BarometerConfig c;
  std::vector<double> at_start, drift;
  for (int seed = 1; seed <= 1000; ++seed) {
    sim::Barometer baro(c, static_cast<std::uint64_t>(seed));
    at_start.push_back(baro.read(0.0, 3.5) - 3.5);
    double late = 0;  // the mean of many readings at 300 s: offset plus drift
    for (int k = 0; k < 200; ++k) late += (baro.read(300.0, 3.5) - 3.5) / 200.0;
    drift.push_back(late);
  }
  const auto sd = [](const std::vector<double>& v) {
    double m = 0, s = 0;
    for (double x : v) m += x / v.size();
    for (double x : v) s += (x - m) * (x - m) / (v.size() - 1);
    return std::sqrt(s);
  };
  EXPECT_NEAR(sd(at_start), sim::Barometer(c, 1).sigma_m(), 0.1 * sim::Barometer(c, 1).sigma_m());
  const double expected = std::hypot(c.offset_sigma_m, c.drift_sigma_mps * 300.0);
  EXPECT_NEAR(sd(drift), expected, 0.1 * expected);
}
