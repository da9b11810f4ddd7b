// The localizer follows the robot up a flight of stairs (issue 31), on a two-storey building
// built in code: lidar points ray-cast from the true pose against both storeys' walls, floors
// and the slab between them (with the stairwell's hole), odometry with scale and heading drift
// that climbs with the base. The truth is the path the test walks, not the localizer's algebra.
// And `--storey auto` with an altitude: two identical storeys, which the walls cannot tell
// apart, the altitude can.
#include "sgraph_fixtures.hpp"

#include <bimloc/geometry/planar_pose.hpp>
#include <bimloc/localizer.hpp>
#include <bimloc/storeys/storey_follower.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace {

using namespace bimloc;

constexpr double kStoreyHeight = 3.0;  // floor to floor; the walls reach the slab above
constexpr double kBaseHeight = 0.5;    // base_link above the floor
const Eigen::Vector3d kFlightBottom(7.0, 7.0, 0.0), kFlightTop(11.0, 7.0, kStoreyHeight);

// A wall of storey `level`: the fixture's box wall raised to the storey's floor, as tall as the storey.
bim::Wall wallAt(const std::string& id, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double floor_z) {
  bim::Wall w = test::boxWall(id, a, b, 0.2);
  w.height_m = kStoreyHeight;
  w.start.z() = w.end.z() = floor_z;
  for (auto& f : w.faces) f.start.z() = f.end.z() = floor_z;
  return w;
}

bim::Room roomAt(bim::Room r, double floor_z) {
  r.floor_z = floor_z;
  r.height_m = kStoreyHeight;
  return r;
}

// The outer walls of both storeys: 14 x 8 m, counter-clockwise (faces[0] looks in).
std::vector<bim::Wall> outerWalls(double z) {
  return {wallAt("S" + std::to_string(int(z)), {0, 0}, {14, 0}, z), wallAt("E" + std::to_string(int(z)), {14, 0}, {14, 8}, z),
          wallAt("N" + std::to_string(int(z)), {14, 8}, {0, 8}, z), wallAt("W" + std::to_string(int(z)), {0, 8}, {0, 0}, z)};
}

// Ground floor: a partition at x = 6 with a 3 m gap at its north end, the stair's side wall.
bim::Storey groundFloor() {
  bim::Storey s;
  s.id = "G", s.name = "Ground", s.elevation_m = 0;
  s.walls = outerWalls(0);
  s.walls.push_back(wallAt("X1", {6, 0}, {6, 5}, 0));
  s.walls.push_back(wallAt("ST0", {7, 6}, {11, 6}, 0));
  s.rooms = {roomAt(test::boxRoom("A", 0, 0, 6, 8, {{"S0", 0}, {"N0", 0}, {"W0", 0}, {"X1", 0}}), 0),
             roomAt(test::boxRoom("B", 6, 0, 14, 8, {{"S0", 0}, {"E0", 0}, {"N0", 0}, {"X1", 1}}), 0)};
  return s;
}

// First floor: other walls: a long wall at y = 4 (open at its east end), a partition at x = 4.
bim::Storey firstFloor() {
  bim::Storey s;
  s.id = "F", s.name = "First", s.elevation_m = kStoreyHeight;
  s.walls = outerWalls(kStoreyHeight);
  s.walls.push_back(wallAt("Y1", {0, 4}, {10, 4}, kStoreyHeight));
  s.walls.push_back(wallAt("X2", {4, 0}, {4, 4}, kStoreyHeight));
  s.walls.push_back(wallAt("ST1", {7, 6}, {11, 6}, kStoreyHeight));
  s.rooms = {roomAt(test::boxRoom("C", 0, 0, 4, 4, {{"S3", 0}, {"W3", 0}, {"Y1", 1}, {"X2", 0}}), kStoreyHeight),
             roomAt(test::boxRoom("D", 4, 0, 14, 4, {{"S3", 0}, {"E3", 0}, {"Y1", 1}, {"X2", 1}}), kStoreyHeight),
             roomAt(test::boxRoom("E", 0, 4, 14, 8, {{"N3", 0}, {"W3", 0}, {"E3", 0}, {"Y1", 0}}), kStoreyHeight)};
  return s;
}

bim::StairFlight flight() {
  bim::StairFlight f;
  f.id = f.stair_id = "STAIR", f.name = "Stair", f.ifc_type = "IfcStairFlight";
  f.bottom = kFlightBottom, f.top = kFlightTop;
  f.width_m = 1.0, f.risers = 18, f.riser_height_m = kStoreyHeight / 18, f.going_m = 4.0 / 17;
  f.bottom_storey = 0, f.top_storey = 1, f.source = "test";
  return f;
}

bim::Building twoStoreys() {
  bim::Building b;
  b.storeys = {groundFloor(), firstFloor()};
  b.stairs = {flight()};
  return b;
}

// The same storey twice, one above the other (ExampleHOM's ground and first floor).
bim::Building identicalStoreys() {
  bim::Building b;
  bim::Storey g = groundFloor();
  g.walls.pop_back();  // no stair
  bim::Storey up = g;
  up.id = "U", up.name = "Upper", up.elevation_m = kStoreyHeight;
  up.walls = outerWalls(kStoreyHeight);
  up.walls.push_back(wallAt("X1", {6, 0}, {6, 5}, kStoreyHeight));
  for (auto& r : up.rooms) r = roomAt(r, kStoreyHeight);
  for (auto& r : up.rooms)
    for (auto& w : r.walls)
      if (w.wall_id.back() == '0') w.wall_id.back() = '3';
  b.storeys = {g, up};
  return b;
}

// Ray casting against the storeys' wall faces, the floors and slabs (z = k * storey height,
// over the building's footprint, less the stairwell's hole above the flight).
struct Caster {
  const bim::Building& building;
  bool hole = true;

  double cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d) const {
    double best = 30.0;
    for (const auto& s : building.storeys)
      for (const auto& w : s.walls)
        for (const auto& f : w.faces) {
          const double den = f.plane.n.dot(d);
          if (den >= -1e-9) continue;  // seen from the front only
          const double t = -(f.plane.n.dot(o) + f.plane.d) / den;
          if (t <= 0.05 || t >= best) continue;
          const Eigen::Vector3d p = o + t * d;
          const Eigen::Vector2d a = f.start.head<2>(), u = (f.end - f.start).head<2>();
          const double along = (p.head<2>() - a).dot(u) / u.squaredNorm();
          if (along < 0 || along > 1 || p.z() < f.start.z() || p.z() > f.start.z() + w.height_m) continue;
          best = t;
        }
    if (std::abs(d.z()) > 1e-9)
      for (int k = 0; k <= static_cast<int>(building.storeys.size()); ++k) {
        const double t = (k * kStoreyHeight - o.z()) / d.z();
        if (t <= 0.05 || t >= best) continue;
        const Eigen::Vector3d p = o + t * d;
        if (p.x() < 0 || p.x() > 14 || p.y() < 0 || p.y() > 8) continue;
        if (hole && k == 1 && p.x() > 6.9 && p.x() < 11.1 && p.y() > 6.3 && p.y() < 7.7) continue;
        best = t;
      }
    return best;
  }

  // A 16-beam lidar (-15..15 deg, every 2 deg), 1 deg azimuth steps, 1 cm range noise.
  std::vector<Eigen::Vector3f> scan(const Eigen::Isometry3d& T_map_lidar, std::mt19937_64& rng) const {
    std::normal_distribution<double> noise(0.0, 0.01);
    std::vector<Eigen::Vector3f> points;
    const Eigen::Vector3d o = T_map_lidar.translation();
    for (int e = -15; e <= 15; e += 2)
      for (int a = 0; a < 360; ++a) {
        const double el = e * M_PI / 180, az = a * M_PI / 180;
        const Eigen::Vector3d dir_lidar(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
        const Eigen::Vector3d d = T_map_lidar.linear() * dir_lidar;
        const double r = cast(o, d);
        if (r >= 30.0) continue;
        points.push_back(((r + noise(rng)) * dir_lidar).cast<float>());
      }
    return points;
  }
};

// The walk: waypoints (x, y, floor z) at 0.5 m/s on a floor, 0.25 m/s on the flight.
struct Walk {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> times;
  double end() const { return times.back(); }
  Eigen::Isometry3d at(double t) const {
    std::size_t i = 1;
    while (i + 1 < times.size() && times[i] < t) ++i;
    const double s = std::clamp((t - times[i - 1]) / (times[i] - times[i - 1]), 0.0, 1.0);
    const Eigen::Vector3d p = points[i - 1] + s * (points[i] - points[i - 1]);
    const Eigen::Vector2d dir = (points[i] - points[i - 1]).head<2>();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(std::atan2(dir.y(), dir.x()), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = p + Eigen::Vector3d(0, 0, kBaseHeight);
    return T;
  }
};

Walk walk(const std::vector<Eigen::Vector3d>& points) {
  Walk w;
  w.points = points;
  w.times = {0.0};
  for (std::size_t i = 1; i < points.size(); ++i) {
    const bool stairs = std::abs(points[i].z() - points[i - 1].z()) > 0.1;
    w.times.push_back(w.times.back() + (points[i] - points[i - 1]).head<2>().norm() / (stairs ? 0.25 : 0.5));
  }
  return w;
}

// Up the stairs: room A, through the gap in X1, up the flight, round the first floor.
Walk upTheStairs() {
  return walk({{2, 2, 0}, {3, 4.5, 0}, {5, 7, 0}, {2, 7, 0}, {4, 6.8, 0}, {kFlightBottom.x(), 7, 0}, {kFlightTop.x(), 7, kStoreyHeight},
               {12.5, 7, kStoreyHeight}, {12.5, 2, kStoreyHeight}, {6, 2, kStoreyHeight}, {8, 3, kStoreyHeight}});
}

struct Step {
  LocalizationResult result;
  Eigen::Isometry3d truth;
};

// The walk through a localizer at 10 Hz: odometry with 1 % scale, 0.3 deg/m heading drift and
// 2 % height scale; `altitude_sigma_m` > 0: the true altitude with that noise, every turn.
// `altitude_offset_m`: added to every reading (a barometer's offset); `seen`: the world the
// lidar sees, when it is not the plan (default: the plan).
std::vector<Step> run(const bim::Building& building, const Walk& w, LocalizerConfig config, double altitude_sigma_m,
                      bool hole = true, double stairs_slip = 0.0, bool blind_on_flight = false, double altitude_offset_m = 0.0,
                      const bim::Building* seen = nullptr) {
  const Eigen::Isometry3d T_base_lidar(Eigen::Translation3d(0, 0, 0.3));
  Localizer localizer(building, T_base_lidar, config);
  const Caster caster{seen ? *seen : building, hole};
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss(0.0, 1.0);
  Eigen::Isometry3d odom = Eigen::Isometry3d(Eigen::Translation3d(0, 0, kBaseHeight));
  Eigen::Isometry3d previous = w.at(0);
  std::vector<Step> steps;
  for (double t = 0; t <= w.end(); t += 0.1) {
    const Eigen::Isometry3d truth = w.at(t);
    const Eigen::Isometry3d delta = previous.inverse() * truth;
    previous = truth;
    const double metres = delta.translation().head<2>().norm();
    Eigen::Isometry3d drifted = delta;
    // On the flight, feet slip: the odometry overshoots by `stairs_slip` of the run.
    const bool on_flight = std::abs(delta.translation().z()) > 1e-6;
    drifted.translation().head<2>() *= 1.01 + (on_flight ? stairs_slip : 0.0);
    drifted.translation().z() *= 1.02;
    drifted.rotate(Eigen::AngleAxisd(0.3 * M_PI / 180 * metres, Eigen::Vector3d::UnitZ()));
    odom = odom * drifted;
    if (altitude_sigma_m > 0)
      localizer.observeAltitude(t, truth.translation().z() + altitude_offset_m + altitude_sigma_m * gauss(rng), altitude_sigma_m);
    const double floor_z = truth.translation().z() - kBaseHeight;
    const bool blind = blind_on_flight && floor_z > 0.01 && floor_z < kStoreyHeight - 0.01;
    const auto points = [&] { return blind ? std::vector<Eigen::Vector3f>{} : caster.scan(truth * T_base_lidar, rng); };
    steps.push_back({localizer.step(t, odom, Localizer::PointSource(points)), truth});
  }
  return steps;
}

double error(const Step& s) { return (s.result.T_map_base.translation() - s.truth.translation()).head<2>().norm(); }

LocalizerConfig fastConfig() {
  LocalizerConfig c;
  c.seed = 3;
  c.pf.particles = 3000;
  return c;
}

// Told the storey and the start (within 0.5 m, 10 deg): the test is what happens at the stairs.
LocalizerConfig startKnown() {
  LocalizerConfig c = fastConfig();
  c.storey = "0";
  c.pf.prior_pose = Eigen::Vector3d(2, 2, std::atan2(2.5, 1.0));
  c.pf.prior_sigma_m = 0.5;
  c.pf.prior_sigma_yaw_deg = 10;
  return c;
}

}  // namespace

TEST(StoreyFollower, AltitudeRulesOutStoreysAndHalfLandingsLeadOn) {
  bim::Building b = twoStoreys();
  const storeys::StoreyFollowConfig c;  // 3 sigma + 0.5 m
  EXPECT_EQ(storeys::storeysAtAltitude(b, {0, 1}, {0, 3.4, 0.2}, kBaseHeight, c), (std::vector<std::size_t>{1}));
  EXPECT_EQ(storeys::storeysAtAltitude(b, {0, 1}, {0, 0.6, 0.2}, kBaseHeight, c), (std::vector<std::size_t>{0}));
  EXPECT_EQ(storeys::storeysAtAltitude(b, {0, 1}, {0, 2.0, 0.5}, kBaseHeight, c), (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(storeys::storeyAtHeight(b, {0, 1}, 3.3, kBaseHeight, 0.6), std::optional<std::size_t>(1));
  EXPECT_FALSE(storeys::storeyAtHeight(b, {0, 1}, 2.0, kBaseHeight, 0.6)) << "half way up: no storey";
  EXPECT_EQ(storeys::flightAt(b, {9, 7, 2.0}, kBaseHeight, 0.3), 0);
  EXPECT_EQ(storeys::flightAt(b, {9, 5, 2.0}, kBaseHeight, 0.3), -1) << "beside the flight";
  EXPECT_EQ(storeys::flightAt(b, {9, 7, 6.5}, kBaseHeight, 0.3), -1) << "above it, a storey up";
  EXPECT_EQ(storeys::flightAt(b, {10, 7, kBaseHeight}, kBaseHeight, 0.3), -1) << "under it, on the ground floor";
  // Two flights with a half landing between them: leaving the first at its top leads on to the second's top.
  bim::StairFlight lower = flight(), upper = flight();
  lower.top = {11, 7, 1.5}, lower.top_storey = -1;
  upper.bottom = {11, 6, 1.5}, upper.top = {7, 6, 3.0}, upper.bottom_storey = -1, upper.id = "UP";
  b.stairs = {lower, upper};
  const storeys::FlightEnd end = storeys::flightEnd(b, 0, true);
  EXPECT_EQ(end.storey, 1);
  EXPECT_TRUE(end.at.isApprox(Eigen::Vector3d(7, 6, 3.0)));
  EXPECT_NEAR(end.heading_rad, M_PI, 1e-9);
  EXPECT_EQ(storeys::flightEnd(b, 1, false).storey, 0);
}

TEST(StoreyChange, TheLocalizerFollowsTheRobotUpTheStairsOntoTheFirstFloor) {
  const bim::Building building = twoStoreys();
  const Walk w = upTheStairs();
  const LocalizerConfig config = startKnown();
  const auto steps = run(building, w, config, 0.0);
  const double left_flight = w.times[6];  // the base steps off the flight's top
  std::optional<double> converged, switched;
  int arrivals = 0;
  for (const auto& s : steps) {
    const auto& r = s.result;
    if (!converged && r.state == LocalizationState::Converged) converged = r.stamp_s;
    if (r.arrival) {
      ++arrivals;
      EXPECT_EQ(r.arrival->from_storey, 0u);
      EXPECT_EQ(r.arrival->to_storey, 1u);
      EXPECT_EQ(r.arrival->flight, 0);
      switched = r.stamp_s;
    }
    if (converged && r.stamp_s < w.times[5]) {
      EXPECT_EQ(r.storey, std::optional<std::size_t>(0));
      EXPECT_LT(error(s), 0.1) << "t=" << r.stamp_s;
    }
    if (switched && r.stamp_s > *switched + 2.0) {
      EXPECT_EQ(r.storey, std::optional<std::size_t>(1)) << "t=" << r.stamp_s;
      EXPECT_EQ(r.state, LocalizationState::Tracking) << "t=" << r.stamp_s;
      EXPECT_LT(error(s), 0.1) << "t=" << r.stamp_s;
      EXPECT_NEAR(r.T_map_base.translation().z(), s.truth.translation().z(), 0.15) << "t=" << r.stamp_s;
    }
  }
  double worst_after = 0;
  for (const auto& s : steps)
    if (switched && s.result.stamp_s > *switched + 2.0) worst_after = std::max(worst_after, error(s));
  std::printf("converged at %.1f s, left the flight at %.1f s, on the first floor at %.1f s, worst error after %.3f m, last %.3f m\n",
              converged.value_or(NAN), left_flight, switched.value_or(NAN), worst_after, error(steps.back()));
  ASSERT_TRUE(converged);
  EXPECT_LT(*converged, w.times[5]) << "converged on the ground floor before the stairs";
  ASSERT_EQ(arrivals, 1);
  EXPECT_GT(*switched, left_flight - 0.5);
  EXPECT_LT(*switched, left_flight + 5.0) << "on the first floor within 5 s of leaving the flight";
}

TEST(StoreyChange, AnAltitudeDecidesBetweenIdenticalStoreysTheWallsCannot) {
  const bim::Building building = identicalStoreys();
  // On the upper storey: the same walk as below, one storey up.
  std::vector<Eigen::Vector3d> points{{2, 2, 0}, {3, 4.5, 0}, {5, 7, 0}, {9, 7, 0}, {12, 3, 0}, {8, 1.5, 0}, {3, 2, 0}};
  for (auto& p : points) p.z() = kStoreyHeight;
  const Walk w = walk(points);
  const auto with = run(building, w, fastConfig(), 0.3, false);
  std::optional<std::size_t> decided;
  for (const auto& s : with)
    if (s.result.storey) decided = s.result.storey;
  ASSERT_TRUE(decided) << "the altitude leaves one storey to search";
  EXPECT_EQ(*decided, 1u);
  EXPECT_LT(error(with.back()), 0.1);
  const auto without = run(building, w, fastConfig(), 0.0, false);
  std::optional<pf::StoreyBankReport> last;
  for (const auto& s : without) {
    ASSERT_FALSE(s.result.storey) << "t=" << s.result.stamp_s << ": the walls alone cannot decide";
    if (s.result.filter) last = s.result.filter;
  }
  // Not for want of evidence: each storey's filter found the place, on its own storey.
  ASSERT_TRUE(last);
  ASSERT_EQ(last->candidates.size(), 2u);
  for (const auto& c : last->candidates) EXPECT_TRUE(c.converged) << building.storeys[c.storey].name;
}

TEST(StoreyChange, TwoLookAlikeStoreys90CmApartTheAltitudeDecidesAReadingBetweenThemDoesNot) {
  // Split levels (Jesse.1's T.O. level 0 floor and Level -1): the ground floor and a copy of
  // its walls 0.9 m above it. The robot walks on the ground floor; the lidar sees that storey
  // alone (its floor, its walls, the slab 3 m up). The walls cannot tell the two apart.
  bim::Building building = identicalStoreys();
  constexpr double kSplit = 0.9;
  bim::Storey& up = building.storeys[1];
  up.elevation_m = kSplit;
  for (auto& wall : up.walls) {
    wall.start.z() = wall.end.z() = kSplit;
    for (auto& f : wall.faces) f.start.z() = f.end.z() = kSplit;
  }
  for (auto& r : up.rooms) r.floor_z = kSplit;
  bim::Building seen;
  seen.storeys = {building.storeys[0]};
  const Walk w = walk({{2, 2, 0}, {3, 4.5, 0}, {5, 7, 0}, {9, 7, 0}, {12, 3, 0}, {8, 1.5, 0}, {3, 2, 0}});
  const auto decidedStorey = [](const std::vector<Step>& steps) {
    std::optional<std::size_t> decided;
    for (const auto& s : steps)
      if (s.result.storey && !decided) decided = s.result.storey;
    return decided;
  };
  // A barometer's reading of 0.15 m sigma on the truth: 0.9 m is 6 sigma; the ground floor.
  const auto on_truth = run(building, w, fastConfig(), 0.15, false, 0.0, false, 0.0, &seen);
  ASSERT_EQ(decidedStorey(on_truth), std::optional<std::size_t>(0));
  EXPECT_LT(error(on_truth.back()), 0.1);
  // Readings half-way between the two floors (an offset of 0.45 m, noise of 0.25 m sigma told
  // and drawn afresh each time): neither storey is ruled out, and however the noise falls on
  // one step, the readings' mean weighs both alike: never the upper storey (what the walls
  // may still say, from the heights their faces span, is theirs).
  const auto between = run(building, w, fastConfig(), 0.25, false, 0.0, false, 0.5 * kSplit, &seen);
  for (const auto& s : between)
    ASSERT_NE(s.result.storey, std::optional<std::size_t>(1)) << "t=" << s.result.stamp_s << ": decided falsely on a reading between the floors";
  std::optional<pf::StoreyBankReport> last;
  for (const auto& s : between)
    if (s.result.filter) last = s.result.filter;
  ASSERT_TRUE(last);
  std::printf("readings between the floors: %zu storey(s) still searched at the end, decided: %s\n", last->candidates.size(),
              decidedStorey(between) ? "the ground floor" : "no");
}

TEST(StoreyChange, AfterSlippingOnTheStairsTheNewStoreysWallsBringThePoseBack) {
  // The odometry overshoots the flight by 20 % (0.8 m): the pose carried onto the first floor is
  // that far off. The first floor's graph (or, if it cannot confirm the walls, the search
  // around the landing) brings it back.
  const bim::Building building = twoStoreys();
  const Walk w = upTheStairs();
  const LocalizerConfig config = startKnown();
  const auto steps = run(building, w, config, 0.0, true, 0.2);
  std::optional<double> switched;
  for (const auto& s : steps)
    if (s.result.arrival) switched = s.result.stamp_s;
  ASSERT_TRUE(switched);
  EXPECT_LT(*switched, w.times[6] + 5.0);
  const Step& end = steps.back();
  std::printf("on the first floor at %.1f s, %d losses, final state %s, error %.3f m\n", *switched, end.result.losses,
              toString(end.result.state), error(end));
  EXPECT_EQ(end.result.storey, std::optional<std::size_t>(1));
  EXPECT_NE(end.result.state, LocalizationState::Lost);
  EXPECT_LT(error(end), 0.1);
}

TEST(StoreyChange, BlindOnTheStairsAndSlippingTheLandingIsTheSearchsPrior) {
  // No scan on the flight (a lidar looking into the steps) and the odometry overshooting it by
  // 30 % (1.2 m): the pose carried across is off by more than the tracker's gates. The first
  // floor's graph cannot confirm the walls, says lost, and the filter searches around the
  // landing on the first floor, where it finds the robot.
  // With one agreeing weighing too: the search that restarts after the loss may converge on its
  // first weighing, whose scan must sit at this step's odometry (it sat at the odometry's origin:
  // map <- odom came out 12.5 m off, and the run ended lost, when the new filter was not given
  // the step's odometry).
  for (const int updates : {1, 2}) {
    SCOPED_TRACE(std::to_string(updates) + " agreeing weighing(s)");
    const bim::Building building = twoStoreys();
    const Walk w = upTheStairs();
    LocalizerConfig config = startKnown();
    config.pf.converged_updates = updates;
    const auto steps = run(building, w, config, 0.0, true, 0.3, true);
    std::optional<double> switched;
    bool searched_upstairs = false;
    for (const auto& s : steps) {
      if (s.result.arrival) switched = s.result.stamp_s;
      if (switched && s.result.filter) {
        searched_upstairs = true;
        EXPECT_EQ(s.result.filter->leader, 1u) << "the search is on the new storey";
      }
    }
    ASSERT_TRUE(switched);
    const Step& end = steps.back();
    std::printf("on the first floor at %.1f s, %d losses, searched there: %s, final state %s, error %.3f m\n", *switched,
                end.result.losses, searched_upstairs ? "yes" : "no", toString(end.result.state), error(end));
    EXPECT_EQ(end.result.storey, std::optional<std::size_t>(1));
    EXPECT_NE(end.result.state, LocalizationState::Lost);
    EXPECT_LT(error(end), 0.1);
  }
}
