// The information-limit oracle (sim/oracle/) against cases whose answer is known from the
// geometry alone: storeys built in code, scans cast in 2D against their wall faces by a ray
// caster written here (not the oracle's distance field), odometry exact in a frame of its own.
// - a point-symmetric room is never decidable from inside (its 180 deg twin explains everything);
// - two identical L-shaped rooms, one with a doorway onto a corridor, become decidable once the
//   robot sees through the doorway, not before;
// - a corridor of identical bays, seen by a range-limited sensor, becomes decidable when its end
//   comes into range;
// - on a site that is not its plan (a doorway walled up), the test can rule the true place out,
//   and reports it;
// - the branch-and-bound finds the same best cell as evaluating every cell of the same grid;
// - a run's keyframes replayed on its walls (decideOnWalls) give decideWhen's verdict.
#include "oracle_fixtures.hpp"
#include "sgraph_fixtures.hpp"
#include "sim/oracle/oracle.hpp"
#include "sim/oracle/place_search.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <tuple>

using namespace bimloc;
using namespace bimloc::sim::oracle;
using namespace bimloc::test;

namespace {

// An L-shaped room: [0, 6] x [0, 3] and [0, 3] x [3, 8], moved by `offset`; with a doorway
// x 1-2 in its north wall when `door`.
void lRoom(bim::Storey& s, const Eigen::Vector2d& o, bool door) {
  addWall(s, {0, 0}, {6, 0}, o);
  addWall(s, {6, 0}, {6, 3}, o);
  addWall(s, {6, 3}, {3, 3}, o);
  addWall(s, {3, 3}, {3, 8}, o);
  if (door) {
    addWall(s, {3, 8}, {2, 8}, o), addWall(s, {0.8, 8}, {0, 8}, o);  // 0.2 m grown ends: the gap is x 1.0-1.8
  } else {
    addWall(s, {3, 8}, {0, 8}, o);
  }
  addWall(s, {0, 8}, {0, 0}, o);
}

}  // namespace

TEST(Oracle, PointSymmetricRoomIsNeverDecidable) {
  bim::Storey s;
  addWall(s, {0, 0}, {6, 0}), addWall(s, {6, 0}, {6, 4}), addWall(s, {6, 4}, {0, 4}), addWall(s, {0, 4}, {0, 0});
  const Walk w = walk({{1.5, 1.2}, {4.5, 1.2}, {4.5, 2.8}, {2.0, 2.8}});
  const OracleVerdict v = runOracle(s, w, 30.0, smallMargin());
  EXPECT_GT(v.keyframes, 20);
  EXPECT_GT(v.threshold, std::log(1.0 / 0.01));
  EXPECT_FALSE(v.decidable_at_s.has_value()) << "decidable at " << v.decidable_at_s.value_or(-1);
  EXPECT_FALSE(v.truth_ruled_out);  // its twin explains the scans as well, not better
}

TEST(Oracle, TwinRoomsBecomeDecidableOnceTheDoorIsInView) {
  // Room A with the doorway onto a corridor (a wall 2.5 m beyond), room B 20 m east, the same
  // room without the doorway and with nothing beyond.
  bim::Storey s;
  lRoom(s, {0, 0}, true);
  addWall(s, {-2, 10.5}, {5, 10.5});
  lRoom(s, {20, 0}, false);
  const Walk w = walk({{5.2, 1.5}, {1.4, 1.5}, {1.4, 6.5}});
  // When the first ray through the doorway reaches the corridor's wall.
  const std::optional<double> door_seen = firstSeen(s, w, 30.0, [](const Eigen::Vector2d& hit) { return hit.y() > 10.0; });
  ASSERT_TRUE(door_seen.has_value());
  const OracleVerdict v = runOracle(s, w, 30.0, smallMargin());
  ASSERT_TRUE(v.decidable_at_s.has_value()) << "door seen at " << *door_seen;
  EXPECT_GE(*v.decidable_at_s, *door_seen - 1e-9);  // before, A and B explain every point alike
  EXPECT_LE(*v.decidable_at_s, *door_seen + 1.0);
}

TEST(Oracle, ASiteThatIsNotItsPlanCanRuleTheTruthOut) {
  // The plan of TwinRoomsBecomeDecidableOnceTheDoorIsInView; on the site, room A's doorway is
  // walled up (built as room B). Once the robot sees that wall, room B explains the scans better
  // than the true place A by more than the threshold: the plain test rules the truth out, and
  // says so. On the site that is its plan, the same walk never does.
  bim::Storey plan;
  lRoom(plan, {0, 0}, true);
  addWall(plan, {-2, 10.5}, {5, 10.5});
  lRoom(plan, {20, 0}, false);
  bim::Storey site;
  lRoom(site, {0, 0}, false);
  addWall(site, {-2, 10.5}, {5, 10.5});
  lRoom(site, {20, 0}, false);
  const Walk w = walk({{5.2, 1.5}, {1.4, 1.5}, {1.4, 6.5}});
  const OracleVerdict as_planned = runOracle(plan, w, 30.0, smallMargin());
  EXPECT_TRUE(as_planned.decidable_at_s.has_value());
  EXPECT_FALSE(as_planned.truth_ruled_out);
  const OracleVerdict walled_up = runOracle(plan, w, 30.0, smallMargin(), &site);
  EXPECT_TRUE(walled_up.truth_ruled_out);
  EXPECT_FALSE(walled_up.decidable_at_s.has_value());
}

TEST(Oracle, CorridorOfIdenticalBaysBecomesDecidableWhenItsEndIsInRange) {
  // A corridor x 0-40, y 0-2, with 1 m deep bays x 3k+1 .. 3k+2.5 along its north side, seen by
  // a sensor of 8 m range walking east from x = 20.2: a start 3 m (a bay) west explains every
  // point until the east end wall (x = 40) comes within range, at x = 32.
  bim::Storey s;
  addWall(s, {0, 0}, {40, 0}), addWall(s, {40, 0}, {40, 2}), addWall(s, {0, 2}, {0, 0});
  double x = 0;
  for (int k = 0; k < 13; ++k) {
    const double b0 = 3 * k + 1, b1 = b0 + 1.5;
    addWall(s, {b0, 2}, {x, 2});
    addWall(s, {b0, 3}, {b0, 2}), addWall(s, {b1, 3}, {b0, 3}), addWall(s, {b1, 2}, {b1, 3});
    x = b1;
  }
  addWall(s, {40, 2}, {x, 2});
  const Walk w = walk({{20.2, 1.0}, {36.0, 1.0}});
  const double in_range = (32.0 - 20.2) / 0.5;
  OracleConfig c = smallMargin();
  const OracleVerdict v = runOracle(s, w, 8.0, c);
  ASSERT_TRUE(v.decidable_at_s.has_value());
  EXPECT_GE(*v.decidable_at_s, in_range - 0.6);
  EXPECT_LE(*v.decidable_at_s, in_range + 1.0);
}

TEST(Oracle, BranchAndBoundFindsWhatEveryCellGives) {
  // A small L room (legs 3 x 1.5 and 1.5 x 2), one scan from inside: the best cell of the
  // rivals and of the truth's place, by the branch-and-bound and by every cell of the grid.
  bim::Storey s;
  addWall(s, {0, 0}, {3, 0}), addWall(s, {3, 0}, {3, 1.5}), addWall(s, {3, 1.5}, {1.5, 1.5});
  addWall(s, {1.5, 1.5}, {1.5, 3.5}), addWall(s, {1.5, 3.5}, {0, 3.5}), addWall(s, {0, 3.5}, {0, 0});
  OracleConfig c;
  c.margin_m = 0.5, c.max_points_per_scan = 40;
  std::mt19937 rng(3);
  const Eigen::Vector3d truth(2.2, 0.8, 0.4);
  const std::vector<Eigen::Vector3f> scan = scanFrom(s, truth, 30.0, rng);
  const std::vector<Keyframe> keyframes{{0.0, truth, bandPoints(scan, Eigen::Isometry3d::Identity(), -0.2, 1.3, c)}};
  ASSERT_GE(keyframes[0].points.size(), 30u);
  const DistanceField field(wallSegmentsInBand(s, c.band_low_m, c.band_high_m), c.raster_m, c.clamp_m, c.margin_m);
  const PointModel model(c, c.clamp_m);
  const Lattice lattice(field, c);
  PathCloud path;
  for (const auto& p : keyframes[0].points) path.add(p.x(), p.y());
  path.finish();
  const SearchContext context{field, model, path, lattice, TruthZone{truth, 0.5, 10.0 * M_PI / 180.0}};
  for (const Region region : {Region::Rivals, Region::Truth}) {
    const SearchAnswer every = searchEveryPlace(context, region);
    const SearchAnswer bnb = searchPlaces(context, region, -std::numeric_limits<float>::infinity(), false);
    ASSERT_GT(every.cells, 0u);
    EXPECT_EQ(bnb.best, every.best) << (region == Region::Rivals ? "rivals" : "truth");
    if (region == Region::Rivals) {
      EXPECT_LT(bnb.cells, every.cells / 10);  // it looked at far fewer cells
    }
    // The decision form: a bar just above / below the best.
    EXPECT_FALSE(searchPlaces(context, region, every.best + 0.01f, true).reached);
    EXPECT_TRUE(searchPlaces(context, region, every.best - 0.01f, true).reached);
  }
}

TEST(Oracle, PathBoundIsNeverBelowTheScoreOfAnyStartInItsBox) {
  // The branch-and-bound is exact only if its bound never underestimates: over random boxes of
  // start poses, from a cell to a root block, the bound against the score of many starts drawn
  // in each box (and its corners), and the distance code against the exact minimum of at().
  bim::Storey s;
  lRoom(s, {0, 0}, true);
  addWall(s, {-1, -1}, {6, -1}), addWall(s, {6, -1}, {6, 5});
  OracleConfig c;
  std::mt19937 rng(11);
  const std::vector<Eigen::Vector3f> scan = scanFrom(s, {1.0, 0.8, 0.3}, 30.0, rng);
  const DistanceField field(wallSegmentsInBand(s, c.band_low_m, c.band_high_m), c.raster_m, c.clamp_m, c.margin_m);
  const PointModel model(c, c.clamp_m);
  PathCloud path;
  for (const auto& p : bandPoints(scan, Eigen::Isometry3d::Identity(), -0.2, 1.3, c)) path.add(p.x(), p.y());
  path.finish();
  ASSERT_GE(path.size(), 30u);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int boxes = 0;
  for (const double half_m : {0.05, 0.2, 0.8, 1.6})
    for (const double half_deg : {1.0, 4.0, 16.0})
      for (int trial = 0; trial < 20; ++trial, ++boxes) {
        const Eigen::Vector3d centre(-0.5 + 6.0 * u01(rng), -0.5 + 5.0 * u01(rng), 2.0 * M_PI * u01(rng));
        const double half_rad = half_deg * M_PI / 180.0;
        const float bound = pathBound(field, model, path, centre.x(), centre.y(), centre.z(), half_m, half_m, half_rad);
        for (int k = 0; k < 40; ++k) {
          const double sx = k < 8 ? (k & 1 ? 1.0 : -1.0) : 2.0 * u01(rng) - 1.0;  // the corners first
          const double sy = k < 8 ? (k & 2 ? 1.0 : -1.0) : 2.0 * u01(rng) - 1.0;
          const double st = k < 8 ? (k & 4 ? 1.0 : -1.0) : 2.0 * u01(rng) - 1.0;
          const float score = pathScore(field, model, path, centre.x() + sx * half_m, centre.y() + sy * half_m, centre.z() + st * half_rad);
          ASSERT_GE(bound, score) << "box " << boxes << " start " << k;
        }
        // The code is a lower bound of the field over the box (sampled on a 21 x 21 grid).
        const float x0 = static_cast<float>(centre.x() - half_m), y0 = static_cast<float>(centre.y() - half_m);
        const float x1 = static_cast<float>(centre.x() + half_m), y1 = static_cast<float>(centre.y() + half_m);
        float least = field.at(x0, y0);
        for (int a = 0; a <= 20; ++a)
          for (int b = 0; b <= 20; ++b) least = std::min(least, field.at(x0 + (x1 - x0) * a / 20.0f, y0 + (y1 - y0) * b / 20.0f));
        ASSERT_LE(field.codeDistance(field.minCodeOver(x0, y0, x1, y1)), least) << "box " << boxes;
      }
}

// A split level: the oracle's map of a storey holds every wall standing in its band, whichever
// storey the plan files it under (withEveryWall), and none of the storeys above or below.
TEST(Oracle, AStoreysMapHoldsTheWallsOfOtherStoreysThatStandInItsBand) {
  const auto lifted = test::liftedWall;
  bim::Building b;
  b.storeys.resize(3);
  b.storeys[0].elevation_m = 0.0, b.storeys[1].elevation_m = 0.9, b.storeys[2].elevation_m = 3.0;
  b.storeys[0].walls = {lifted(test::boxWall("L0", {0, 0}, {4, 0}, 0.2), 0.0, 2.6)};
  b.storeys[1].walls = {lifted(test::boxWall("H", {0, 5}, {4, 5}, 0.2), 0.9, 2.0)};   // 0.9-2.9 m
  b.storeys[2].walls = {lifted(test::boxWall("L1", {0, 9}, {4, 9}, 0.2), 3.0, 2.6)};  // 3.0-5.6 m
  const OracleConfig c;
  const auto facesIn = [&](std::size_t s) {
    const bim::Storey map = withEveryWall(b, s);
    EXPECT_EQ(map.walls.front().id, b.storeys[s].walls.front().id);  // its own first
    const double floor = b.storeys[s].elevation_m;
    return wallSegmentsInBand(map, floor + c.band_low_m, floor + c.band_high_m).size();
  };
  EXPECT_EQ(facesIn(0), 4u);  // level 0's two faces and the half level's (0.9-2.9 m cross 0.3-1.8 m)
  EXPECT_EQ(facesIn(1), 4u);  // the half level's and level 0's (0-2.6 m cross 1.2-2.7 m)
  EXPECT_EQ(facesIn(2), 2u);  // level 1's alone: nothing below reaches 3.3 m
}

TEST(Oracle, KeyframesReplayedOnTheWallsGiveTheSameVerdict) {
  // The twin L rooms of TwinRoomsBecomeDecidableOnceTheDoorIsInView, plus a partition in room A
  // that B lacks: the robust checks run at keyframes the plain checks searched, whose truth's
  // search decideOnWalls keeps and does not redo.
  bim::Storey s;
  lRoom(s, {0, 0}, true);
  addWall(s, {-2, 10.5}, {5, 10.5});
  addWall(s, {4.0, 1.0}, {4.0, 2.0});
  lRoom(s, {20, 0}, false);
  const Walk w = walk({{5.2, 1.5}, {1.4, 1.5}, {1.4, 6.5}});
  const OracleConfig config = smallMargin();
  const std::vector<Keyframe> keyframes = oracleKeyframes(s, w, 30.0, config);
  const OracleVerdict v = decideWhen(s, 0.0, keyframes, w.poses.front(), config);
  std::vector<int> wall_of;
  const std::vector<Segment2> walls = wallSegmentsInBand(s, config.band_low_m, config.band_high_m, &wall_of);
  const OracleVerdict r = decideOnWalls(walls, wall_of, keyframes, w.poses.front(), config);
  ASSERT_TRUE(v.decidable_at_s.has_value());
  const auto plain = [](const OracleVerdict& x) { return std::make_tuple(x.decidable_at_s, x.truth_ruled_out, x.checks, x.nodes, x.cells); };
  const auto robust = [](const OracleVerdict& x) { return std::make_tuple(x.decidable_robust_at_s, x.robust_checks, x.robust_nodes); };
  EXPECT_EQ(plain(r), plain(v));
  EXPECT_EQ(robust(r), robust(v));
  // Without the robust answer, the plain one is the same: it does not depend on the robust checks.
  OracleConfig plain_only = config;
  plain_only.robust = false;
  const OracleVerdict p = decideOnWalls(walls, wall_of, keyframes, w.poses.front(), plain_only);
  EXPECT_EQ(plain(p), plain(v));
  EXPECT_EQ(robust(p), robust(OracleVerdict{}));
}
