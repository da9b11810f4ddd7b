// Free-space (negative) evidence (pf/free_space_evidence.hpp) against answers known from the
// geometry: the cost of one ray through a wall at a known distance, on the wall, through an
// opening, short of every wall (clutter), each wall counted once and bounded; and a storey built
// in code, two identical offices that differ by one door, which the planes cannot tell apart
// from inside and the rays through the door can. Scans are cast here, in 2D against the faces
// at each height (not by the sim's lidar), so that the truth is the plan's.
#include "sgraph_fixtures.hpp"

#include "pf/free_space_evidence.hpp"

#include <bimloc/pf/particle_filter.hpp>
#include <bimloc/pf/range_profile.hpp>
#include <bimloc/planes/plane_extraction.hpp>

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cmath>
#include <limits>
#include <optional>
#include <random>

using namespace bimloc;
using namespace bimloc::pf::detail;

namespace {

constexpr double kFaceWorth = 0.5 * (11.34 - 3.0);  // the default gate's face: evidenceMargin / 2

FreeSpaceParams defaultParams() { return FreeSpaceParams::of(pf::ParticleFilterConfig{}, 0.0); }

// A profile of rays from the base's origin (lidar at the origin, 0.6 m up), ends at 1.4 m.
pf::RangeProfile profileOf(const std::vector<Eigen::Vector2d>& ends) {
  pf::RangeProfile p;
  p.origin_base = Eigen::Vector3d(0, 0, 0.6);
  for (const auto& e : ends) p.ends_base.emplace_back(static_cast<float>(e.x()), static_cast<float>(e.y()), 1.4f);
  return p;
}

// One wall whose axis runs x = 5, y -15..15, 0.2 m thick: its face towards the origin at
// x = 4.9; and another behind it, its face at x = 6.9 (where the rays through the first end).
bim::Storey oneWall(std::optional<std::pair<double, double>> door_y = std::nullopt) {
  bim::Storey s;
  s.walls.push_back(test::boxWall("W", {5, -15}, {5, 15}, 0.2));
  s.walls.push_back(test::boxWall("Behind", {7, -15}, {7, 15}, 0.2));
  if (door_y)
    for (auto& f : s.walls[0].faces) {
      const Eigen::Vector2d d = (f.end - f.start).head<2>().normalized();
      const double a = (Eigen::Vector2d(5, door_y->first) - f.start.head<2>()).dot(d);
      const double b = (Eigen::Vector2d(5, door_y->second) - f.start.head<2>()).dot(d);
      f.openings.push_back({std::min(a, b), std::max(a, b), 0.0, 2.1});
    }
  return s;
}

std::vector<FreeSpaceHit> hitsOf(const bim::Storey& s, const std::vector<Eigen::Vector2d>& ends,
                                 const FreeSpaceParams& params = defaultParams()) {
  const FreeSpaceMap map(s);
  return freeSpaceHits(map, params, Eigen::Vector3d::Zero(), 0.0, profileOf(ends));
}

}  // namespace

TEST(FreeSpace, ThroughCostIsTheBetterOfTheWallAndTheClutterFloor) {
  const double sigma = 0.1, cap = kFaceWorth;
  EXPECT_DOUBLE_EQ(throughCost(0.0, sigma, cap), 0.0);
  EXPECT_DOUBLE_EQ(throughCost(-1.0, sigma, cap), 0.0);  // short: clutter's, never costed here
  // -log max(exp(-z^2 / 2), exp(-cap)): the wall's Gaussian up to z = sqrt(2 cap), then the floor.
  for (const double z : {0.5, 1.0, 2.0, 2.8})
    EXPECT_NEAR(throughCost(z * sigma, sigma, cap), 0.5 * z * z, 1e-12) << z;
  for (const double z : {2.9, 3.0, 3.1, 5.0, 1000.0}) EXPECT_DOUBLE_EQ(throughCost(z * sigma, sigma, cap), cap) << z;
  double last = 0;
  for (double e = 0.01; e < 5.0; e += 0.01) {
    const double c = throughCost(e, sigma, cap);
    EXPECT_GE(c, last - 1e-12);
    EXPECT_LE(c, cap);
    last = c;
  }
}

TEST(FreeSpace, ARayThroughAWallCostsByHowFarBeyond) {
  const FreeSpaceParams params = defaultParams();
  // 2 m beyond the face at x = 4.9, head-on: far beyond the gate, the cost saturates.
  const auto through = hitsOf(oneWall(), {{6.9, 0.0}});
  ASSERT_EQ(through.size(), 1u);
  EXPECT_EQ(through[0].key, 0);  // wall 0
  EXPECT_NEAR(through[0].cost, throughCost(2.0, params.sigma_m, kFaceWorth), 1e-5);
  EXPECT_GT(through[0].cost, 0.99 * kFaceWorth);
  // Just beyond by less than the gate (3 sigma): noise, no cost.
  EXPECT_TRUE(hitsOf(oneWall(), {{4.9 + 2.5 * params.sigma_m, 0.0}}).empty());
  // By 4 sigma: the cost of 4 sigma, beyond the gate one face. (Head-on, the heading's gate moves
  // the crossing at 4.9 m to 4.9 / cos(3.3 deg), 8 mm farther: sigma 0.0501 m.)
  const auto four = hitsOf(oneWall(), {{4.9 + 4.0 * params.sigma_m, 0.0}});
  ASSERT_EQ(four.size(), 1u);
  const double tilt = params.gate_sigmas * params.sigma_yaw_rad;
  const double head_on = std::hypot(params.sigma_m, 4.9 * (1.0 / std::cos(tilt) - 1.0) / params.gate_sigmas);
  EXPECT_NEAR(four[0].cost, throughCost(4.0 * params.sigma_m, head_on, kFaceWorth), 1e-5);
  // Obliquely (60 deg off the normal), the same 4 sigma along the ray is 2 sigma of its range:
  // within the gate.
  const Eigen::Vector2d u(std::cos(M_PI / 3), std::sin(M_PI / 3));
  const double t = 4.9 / u.x();
  EXPECT_TRUE(hitsOf(oneWall(), {(t + 4.0 * params.sigma_m) * u}).empty());
}

TEST(FreeSpace, ARayEndingOnTheWallOrShortOfItCostsNothing) {
  EXPECT_TRUE(hitsOf(oneWall(), {{4.9, 0.0}, {4.92, 1.0}, {4.85, -2.0}}).empty());
  // 0.5 m short (a desk, a person in front of the wall): within open_m, nothing.
  EXPECT_TRUE(hitsOf(oneWall(), {{4.4, 0.0}}).empty());
}

TEST(FreeSpace, ARayThroughAnOpeningIsNoPenetration) {
  // A door y -1..1 (to 2.1 m): a ray through it ends 2 m beyond the wall and costs nothing; a
  // ray through the wall beside it does.
  const auto s = oneWall(std::make_pair(-1.0, 1.0));
  EXPECT_TRUE(hitsOf(s, {{6.9, 0.0}, {6.9, 0.5}}).empty());
  EXPECT_EQ(hitsOf(s, {{6.9, 3.0}}).size(), 1u);
  // Above the door's head (the ray's end at 1.4 m, the door to 2.1 m: inside; a door to 1.0 m
  // would not be).
  auto low = s;
  for (auto& f : low.walls[0].faces) f.openings[0].z_max_m = 1.0;
  EXPECT_EQ(hitsOf(low, {{6.9, 0.0}}).size(), 1u);
}

TEST(FreeSpace, ARayEndingInTheOpenCostsLittleAndIsBounded) {
  const FreeSpaceParams params = defaultParams();
  // 3 m short of the wall: in the open.
  const auto open = hitsOf(oneWall(), {{1.9, 0.0}});
  ASSERT_EQ(open.size(), 1u);
  EXPECT_GE(open[0].key, kOpenKeyBase);
  EXPECT_NEAR(open[0].cost, params.open_wall_faces * kFaceWorth, 1e-5);
  // Clutter everywhere (a crowd, stacked material): 90 rays over 20 scans, all in the open,
  // cost at most open_faces faces in all.
  std::vector<std::vector<FreeSpaceHit>> scans;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> y(-4.5, 4.5), x(0.5, 3.5);
  for (int k = 0; k < 20; ++k) {
    std::vector<Eigen::Vector2d> ends;
    for (int r = 0; r < 90; ++r) ends.emplace_back(x(rng), y(rng));
    scans.push_back(hitsOf(oneWall(), ends));
  }
  std::vector<const std::vector<FreeSpaceHit>*> window;
  for (const auto& s : scans) window.push_back(&s);
  const double penalty = freeSpacePenalty(window, params);
  EXPECT_GT(penalty, 0.5 * kFaceWorth);
  EXPECT_LE(penalty, params.open_faces * kFaceWorth + 1e-9);
}

TEST(FreeSpace, EachWallCountsOnceAndAtMostOneFace) {
  const FreeSpaceParams params = defaultParams();
  // A wall not built yet: every ray of 30 scans goes through it, far beyond. One face's worth.
  std::vector<std::vector<FreeSpaceHit>> scans;
  for (int k = 0; k < 30; ++k) {
    std::vector<Eigen::Vector2d> ends;
    for (int r = -20; r <= 20; ++r) ends.emplace_back(8.0, 0.2 * r);
    scans.push_back(hitsOf(oneWall(), ends));
    ASSERT_EQ(scans.back().size(), 41u);
  }
  std::vector<const std::vector<FreeSpaceHit>*> window;
  for (const auto& s : scans) window.push_back(&s);
  EXPECT_DOUBLE_EQ(freeSpacePenalty(window, params), params.face_worth);  // exactly, though costs are floats
  // One ray alone counts a third (support_rays = 3): a stray return is not a wall's worth.
  const std::vector<FreeSpaceHit> one{{0, static_cast<float>(kFaceWorth)}};
  EXPECT_NEAR(freeSpacePenalty({&one}, params), kFaceWorth / 3.0, 1e-5);
  // Two walls: two faces' worth, the bar, and no more.
  const std::vector<FreeSpaceHit> two{{0, 4.0f}, {0, 4.0f}, {0, 4.0f}, {7, 4.0f}, {7, 4.0f}, {7, 4.0f}};
  EXPECT_NEAR(freeSpacePenalty({&two}, params), 8.0, 1e-5);
}

TEST(FreeSpace, ARayThroughTwoWallsCountsAgainstTheFirstOnly) {
  const FreeSpaceParams params = defaultParams();
  // Ending 1 m past the wall behind (its far face at x = 7.1): walls in one line of sight are
  // one deviation (missing together), so the first wall alone, at the ray's distance beyond it.
  const auto both = hitsOf(oneWall(), {{8.1, 0.0}});
  ASSERT_EQ(both.size(), 1u);
  EXPECT_EQ(both[0].key, 0);
  EXPECT_NEAR(both[0].cost, throughCost(8.1 - 4.9, params.sigma_m, kFaceWorth), 1e-5);
  // Through a door in the first wall, then through the wall behind: the wall behind is the
  // first solid one.
  const auto door = hitsOf(oneWall(std::make_pair(-1.0, 1.0)), {{8.1, 0.0}});
  ASSERT_EQ(door.size(), 1u);
  EXPECT_EQ(door[0].key, 1);
}

TEST(FreeSpace, ATurnNotDeSkewedIsJudgedWithItsOwnSkew) {
  // A wall 20 m away (face at x = 19.9) with a door y -1..1; a ray through the wall 0.3 m past
  // the door's edge. With the heading known to 0.1 deg, it went through the wall.
  bim::Storey far;
  far.walls.push_back(test::boxWall("Far", {20, -15}, {20, 15}, 0.2));
  for (auto& f : far.walls[0].faces) {
    const Eigen::Vector2d d = (f.end - f.start).head<2>().normalized();
    const double a = (Eigen::Vector2d(20, -1) - f.start.head<2>()).dot(d), b = (Eigen::Vector2d(20, 1) - f.start.head<2>()).dot(d);
    f.openings.push_back({std::min(a, b), std::max(a, b), 0.0, 2.1});
  }
  FreeSpaceParams params = defaultParams();
  params.sigma_yaw_rad = 0.1 * M_PI / 180.0;
  const FreeSpaceMap map(far);
  const Eigen::Vector2d end = Eigen::Vector2d(19.9, 1.3) * (25.0 / 19.9);
  pf::RangeProfile turn = profileOf({end});
  EXPECT_EQ(freeSpaceHits(map, params, Eigen::Vector3d::Zero(), 0.0, turn).size(), 1u);
  // The same turn taken while turning at 60 deg/s (6 deg over the turn): its rays are up to
  // 3 deg, 1 m at 20 m, off the mid-turn pose; this one may have passed through the door.
  turn.skew_yaw_rad = 3.0 * M_PI / 180.0;
  EXPECT_TRUE(freeSpaceHits(map, params, Eigen::Vector3d::Zero(), 0.0, turn).empty());
  // A ray 5 m past the door's edge went through the wall either way.
  turn.ends_base.emplace_back(25.0f, 6.0f * 25.0f / 19.9f, 1.4f);
  EXPECT_EQ(freeSpaceHits(map, params, Eigen::Vector3d::Zero(), 0.0, turn).size(), 1u);
}

TEST(FreeSpace, ARayGrazingAWallFromItsDoorwayCrossesItWhereThePositionAllows) {
  // The robot in the doorway (y -1..1) of the wall whose face is at x = 4.9, 0.1 m in front of
  // it; a ray at 9 deg to the wall crosses the face 0.15 m past the door's edge. Its position,
  // known to sigma_m (5 cm), moves that crossing by sigma_m / cos(incidence) along the wall:
  // it may have left through the doorway. No verdict.
  const FreeSpaceParams params = defaultParams();
  const bim::Storey storey = oneWall(std::make_pair(-1.0, 1.0));  // the map points at its openings: kept alive
  const FreeSpaceMap map(storey);
  const Eigen::Vector3d in_doorway(4.8, 0.5, 0.0);
  const Eigen::Vector2d u = Eigen::Vector2d(0.1, 0.65).normalized();
  const auto grazing = freeSpaceHits(map, params, in_doorway, 0.0, profileOf({(0.66 + 3.0) * u}));
  EXPECT_TRUE(grazing.empty());
  // Head-on through the wall 1.5 m past the door's edge, from in front of it: through it.
  EXPECT_EQ(freeSpaceHits(map, params, Eigen::Vector3d(4.8, 2.5, 0.0), 0.0, profileOf({{2.1, 0.0}})).size(), 1u);
}

namespace {

// Two identical offices [0, 6] x [0, 4] (faces 0.1 m inside the axes), a corridor wall 2.5 m
// north of each; office A (at x = 0) has a door x 2-3 in its north wall, office B (x = 20) has
// none. From inside, the planes of A (its four walls, and the corridor's through the door) are
// B's too.
bim::Storey twinOffices() {
  bim::Storey s;
  s.name = "L0";
  const auto wall = [&](Eigen::Vector2d a, Eigen::Vector2d b, double dx) {
    const Eigen::Vector2d u = (b - a).normalized();
    a += Eigen::Vector2d(dx, 0) - 0.1 * u, b += Eigen::Vector2d(dx, 0) + 0.1 * u;
    s.walls.push_back(test::boxWall("W" + std::to_string(s.walls.size()), a, b, 0.2));
    return s.walls.size() - 1;
  };
  for (const double dx : {0.0, 20.0}) {
    std::vector<bim::RoomWall> room_walls;
    for (const auto& [a, b] : std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>{
             {{0, 0}, {6, 0}}, {{6, 0}, {6, 4}}, {{6, 4}, {0, 4}}, {{0, 4}, {0, 0}}}) {
      const std::size_t w = wall(a, b, dx);
      room_walls.push_back({s.walls[w].id, -1});
      if (dx == 0.0 && a.y() == 4 && b.y() == 4)
        for (auto& f : s.walls[w].faces) {
          const Eigen::Vector2d d = (f.end - f.start).head<2>().normalized();
          const double p = (Eigen::Vector2d(2, 4) - f.start.head<2>()).dot(d), q = (Eigen::Vector2d(3, 4) - f.start.head<2>()).dot(d);
          f.openings.push_back({std::min(p, q), std::max(p, q), 0.0, 2.1});
        }
    }
    wall({-1, 6.5}, {7, 6.5}, dx);
    s.rooms.push_back(test::boxRoom(dx == 0.0 ? "A" : "B", dx + 0.1, 0.1, dx + 5.9, 3.9, room_walls));
  }
  return s;
}

// The first solid face along the ray at height z (openings let it pass), within 20 m.
std::optional<double> castAt(const bim::Storey& s, const Eigen::Vector2d& p, const Eigen::Vector2d& d, double z) {
  std::optional<double> best;
  for (const auto& w : s.walls)
    for (const auto& f : w.faces) {
      // p + t d = start + u (end - start), solved as a 2x2 system.
      const Eigen::Vector2d e = (f.end - f.start).head<2>();
      Eigen::Matrix2d m;
      m.col(0) = d, m.col(1) = -e;
      if (std::abs(m.determinant()) < 1e-12) continue;
      const Eigen::Vector2d tu = m.inverse() * (f.start.head<2>() - p);
      const double t = tu(0), u = tu(1);
      if (u < 0 || u > 1 || t <= 1e-6 || t > 20.0 || z > w.height_m || (best && t >= *best)) continue;
      const double along = u * e.norm();
      // (a rectangle of no width lies inside any set of holes, even none: give it a centimetre)
      if (bim::insideOpening(f.openings, along - 0.01, along + 0.01, z - 0.01, z + 0.01, 0.0)) continue;
      best = t;
    }
  return best;
}

// A scan from map pose (x, y, yaw), base = lidar frame at the floor: a ray each half degree at
// 15 heights 0.2-2.6 m, range noise 1 cm.
std::vector<Eigen::Vector3f> scanOf(const bim::Storey& s, const Eigen::Vector3d& pose, std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<Eigen::Vector3f> points;
  for (int k = 0; k < 720; ++k) {
    const double local = k * M_PI / 360.0;
    const Eigen::Vector2d d(std::cos(pose.z() + local), std::sin(pose.z() + local));
    for (int h = 0; h < 15; ++h) {
      const double z = 0.2 + 0.17 * h;
      const auto t = castAt(s, pose.head<2>(), d, z);
      if (!t) continue;
      const double r = *t + noise(rng);
      points.emplace_back(static_cast<float>(r * std::cos(local)), static_cast<float>(r * std::sin(local)), static_cast<float>(z));
    }
  }
  return points;
}

Eigen::Isometry3d isometry(const Eigen::Vector3d& p) {
  return Eigen::Translation3d(p.x(), p.y(), 0.0) * Eigen::AngleAxisd(p.z(), Eigen::Vector3d::UnitZ());
}

}  // namespace

TEST(FreeSpace, TwinOfficesDifferingByADoorAreToldApartByTheRaysThroughIt) {
  const bim::Storey s = twinOffices();
  std::mt19937 rng(11);
  const Eigen::Vector3d in_a(2.5, 1.5, 0.3), in_b = in_a + Eigen::Vector3d(20, 0, 0);
  const auto points = scanOf(s, in_a, rng);
  const auto walls = planes::extractPlanes(points).walls;
  ASSERT_GE(walls.size(), 4u);
  // The planes cannot tell the offices apart: the same score at A and at B.
  pf::ParticleFilter filter(s, Eigen::Isometry3d::Identity(), {});
  const auto at_a = filter.score(in_a.x(), in_a.y(), in_a.z(), walls), at_b = filter.score(in_b.x(), in_b.y(), in_b.z(), walls);
  EXPECT_NEAR(at_a.first, at_b.first, 1e-6);
  EXPECT_EQ(at_a.second, at_b.second);
  // The rays through the door went through B's solid north wall: at least one face against B,
  // nothing against A.
  const pf::RangeProfile profile = pf::rangeProfile(points, Eigen::Isometry3d::Identity(), pf::profileConfig({}));
  EXPECT_LE(profile.ends_base.size(), 180u);
  const FreeSpaceMap map(s);
  const FreeSpaceParams params = defaultParams();
  const auto hits_a = freeSpaceHits(map, params, in_a, 0.0, profile), hits_b = freeSpaceHits(map, params, in_b, 0.0, profile);
  // (At A, a ray or two grazing the door's jambs, which the model lets through by its 0.1 m
  // margin, end on the wall beside the door: in A's open, a fraction of a face.)
  for (const auto& h : hits_a) EXPECT_GE(h.key, kOpenKeyBase) << "a ray through a solid wall of A, cost " << h.cost;
  const double against_a = freeSpacePenalty({&hits_a}, params), against_b = freeSpacePenalty({&hits_b}, params);
  EXPECT_LE(against_a, params.open_faces * kFaceWorth);
  EXPECT_GT(against_b - against_a, 0.9 * kFaceWorth) << hits_b.size() << " hits at B";
}

namespace {

// The filter walked through office A, scans every 0.1 s at 0.5 m/s, odometry exact: its last
// report.
pf::UpdateReport walkInA(bool free_space) {
  const bim::Storey s = twinOffices();
  pf::ParticleFilterConfig config;
  config.free_space_evidence = free_space;
  config.particles = 2000;
  config.seed = 5;
  pf::ParticleFilter filter(s, Eigen::Isometry3d::Identity(), config);
  std::mt19937 rng(13);
  const std::vector<Eigen::Vector2d> waypoints{{1.0, 1.0}, {5.0, 1.0}, {5.0, 3.0}, {1.2, 3.0}};
  pf::UpdateReport last;
  for (std::size_t k = 0; k + 1 < waypoints.size(); ++k) {
    const Eigen::Vector2d a = waypoints[k], b = waypoints[k + 1];
    const double yaw = std::atan2(b.y() - a.y(), b.x() - a.x());
    for (double t = 0; t < (b - a).norm(); t += 0.05) {
      const Eigen::Vector3d pose(a.x() + t * std::cos(yaw), a.y() + t * std::sin(yaw), yaw);
      filter.predict(isometry(pose));  // odom = map: the filter does not know it
      const auto points = scanOf(s, pose, rng);
      const auto walls = planes::extractPlanes(points).walls;
      const pf::RangeProfile profile = pf::rangeProfile(points, Eigen::Isometry3d::Identity(), pf::profileConfig(config));
      const pf::UpdateReport r = filter.update(walls, &profile);
      if (r.weighed) last = r;
    }
  }
  return last;
}

// The margin of the best over office B (the rival beyond x = 15), +inf when B is no rival
// within the bar.
double marginOverB(const pf::UpdateReport& r) {
  for (const auto& [pose, margin] : r.path_rivals)
    if (pose.x() > 15.0) return margin;
  return std::numeric_limits<double>::infinity();
}

}  // namespace

TEST(FreeSpace, TheFilterWithFreeSpaceCountsTheDoorAgainstTheOfficeWithoutIt) {
  // One wall tells the offices apart (B's north wall, where A has its door): one face's worth,
  // by the rule, half the bar; the planes give nothing.
  const pf::UpdateReport planes_only = walkInA(false), with_free_space = walkInA(true);
  ASSERT_TRUE(planes_only.path_best && with_free_space.path_best);
  const double faces_planes = (planes_only.path_best->x() > 15.0 ? 0.0 : marginOverB(planes_only)) / kFaceWorth;
  EXPECT_LT(faces_planes, 0.1) << "planes alone told the offices apart";
  EXPECT_LT(with_free_space.path_best->x(), 10.0) << "the free space put the best in B";
  const double faces_free = marginOverB(with_free_space) / kFaceWorth;
  EXPECT_GT(faces_free, 0.9);
  EXPECT_LT(faces_free, 1.0 + 1e-5);  // one wall: at most one face
}

TEST(FreeSpace, AnOpenRayThatTheOtherPlaceEndsOnItsWallCountsPerThatWallAndOnceWithItsPlane) {
  // free_space_explained (off by default): place X sees 4 rays end 3 m short of the wall (in its
  // open); at place Y (1 m nearer the wall, the same rays) three of them end on the wall's face
  // and one 2 m short of it.
  FreeSpaceParams params = defaultParams();
  params.explained = true;
  const std::vector<Eigen::Vector2d> ends{{1.9, 0.0}, {1.9, 0.3}, {1.9, -0.3}, {0.9, 1.0}};
  const bim::Storey storey = oneWall();  // the map points at its faces' openings: kept alive
  const FreeSpaceMap map(storey);
  const auto at_x = freeSpaceHits(map, params, Eigen::Vector3d::Zero(), 0.0, profileOf(ends));
  const auto at_y = freeSpaceHits(map, params, Eigen::Vector3d(3.0, 0.0, 0.0), 0.0, profileOf(ends));
  ASSERT_EQ(at_x.size(), 4u);  // all open
  int on_wall = 0;
  for (const auto& h : at_y) on_wall += (h.key == kOnWallBase + 0 && h.cost == 0.0f) ? 1 : 0;
  EXPECT_EQ(on_wall, 3);
  const std::vector<const std::vector<FreeSpaceHit>*> x{&at_x}, y{&at_y};
  // Against X: wall 0 in full (3 rays = support), the fourth ray stays open (a quarter face, a third of it).
  const FreeSpaceCost cost = freeSpaceCostGiven(x, y, params, {});
  ASSERT_EQ(cost.explained.size(), 1u);
  EXPECT_EQ(cost.explained[0].first, 0);
  EXPECT_NEAR(cost.explained[0].second, kFaceWorth, 1e-6);
  EXPECT_NEAR(cost.rest, params.open_wall_faces * kFaceWorth / 3.0, 1e-5);
  // The planes already counted 3 of wall 0's worth for Y: the rays add only what is left, and
  // stay in the bounded open term.
  const FreeSpaceCost counted = freeSpaceCostGiven(x, y, params, {3.0});
  EXPECT_NEAR(counted.explained[0].second, kFaceWorth - 3.0, 1e-6);
  EXPECT_NEAR(counted.rest, freeSpacePenalty(x, params), 1e-6);
  // The bound over every other place holds.
  EXPECT_LE(cost.rest + cost.explained[0].second, freeSpacePenaltyBound(x, params) + 1e-9);
  // Y's own rays end on its wall: nothing against Y given X.
  const FreeSpaceCost against_y = freeSpaceCostGiven(y, x, params, {});
  EXPECT_TRUE(against_y.explained.empty());
}
