// The oracle's distance field (sim/oracle/wall_field.hpp) against brute force: at() is the least
// distance over every segment, to the bit, nearest() that segment, squareDistance() the least
// over a dense sampling of the square; and what exactness is for: two identical rooms a
// non-whole number of raster cells apart score alike, so the oracle never tells them apart.
#include "oracle_fixtures.hpp"
#include "sim/oracle/path_score.hpp"
#include "sim/oracle/wall_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace bimloc;
using namespace bimloc::sim::oracle;
using namespace bimloc::test;

namespace {

// Random segments in a 12 x 9 m box: long and short, axis-aligned and oblique, crossing, a few
// of zero length, and a T and an L sharing end points (where nearest walls tie).
std::vector<Segment2> randomSegments(std::mt19937& rng) {
  std::uniform_real_distribution<double> x(0.0, 12.0), y(0.0, 9.0), len(0.0, 4.0), turn(0.0, 2 * M_PI);
  std::vector<Segment2> out;
  for (int k = 0; k < 40; ++k) {
    const Eigen::Vector2d a(x(rng), y(rng));
    const double l = k % 13 == 0 ? 0.0 : len(rng), t = k % 3 == 0 ? (k % 2) * M_PI / 2 : turn(rng);
    out.push_back({a, a + l * Eigen::Vector2d(std::cos(t), std::sin(t))});
  }
  out.push_back({{2, 2}, {6, 2}}), out.push_back({{4, 2}, {4, 5}}), out.push_back({{6, 2}, {6, 6}});
  return out;
}

float bruteDistance(const std::vector<Segment2>& segments, float x, float y, float clamp, int* nearest) {
  double least = static_cast<double>(clamp) * clamp;
  *nearest = -1;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const double d = segmentDistance2(Eigen::Vector2d(x, y), segments[k]);
    if (d < least) least = d, *nearest = static_cast<int>(k);
  }
  return std::min(clamp, static_cast<float>(std::sqrt(least)));
}

}  // namespace

TEST(OracleField, IsTheLeastDistanceOverEverySegmentToTheBit) {
  std::mt19937 rng(7);
  for (int world = 0; world < 6; ++world) {
    const std::vector<Segment2> segments = randomSegments(rng);
    const double cell = world % 2 == 0 ? 0.05 : 0.13, clamp = world < 4 ? 0.5 : 1.7;
    const DistanceField field(segments, cell, clamp, 1.0);
    std::uniform_real_distribution<double> x(-2.0, 14.0), y(-2.0, 11.0), u01(0.0, 1.0), off(-0.6, 0.6);
    int checked = 0, within = 0;
    for (int k = 0; k < 40000; ++k) {
      float px, py;
      if (k % 4 == 0) {  // anywhere
        px = static_cast<float>(x(rng)), py = static_cast<float>(y(rng));
      } else {  // near a segment: on it, beside it, past its ends
        const Segment2& s = segments[static_cast<std::size_t>(k) % segments.size()];
        const Eigen::Vector2d beside = (k % 4 == 1 ? 0.0 : 1.0) * Eigen::Vector2d(off(rng), off(rng));
        const Eigen::Vector2d p = s.a + (1.4 * u01(rng) - 0.2) * (s.b - s.a) + beside;
        px = static_cast<float>(p.x()), py = static_cast<float>(p.y());
      }
      if (k % 7 == 0) {  // on a square's edge
        px = static_cast<float>(field.lower().x() + cell * std::round((px - field.lower().x()) / cell));
      }
      int nearest = -2;
      const float brute = bruteDistance(segments, px, py, static_cast<float>(clamp), &nearest);
      ASSERT_EQ(field.at(px, py), brute) << "world " << world << " point " << px << ", " << py;
      ASSERT_EQ(field.nearest(px, py), nearest) << "world " << world << " point " << px << ", " << py;
      ++checked, within += brute < clamp;
    }
    EXPECT_GT(within, checked / 2) << "most points near a wall";
  }
}

TEST(OracleField, SquareDistanceIsTheLeastOverTheSquare) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> x(-1.0, 3.0), side(0.01, 0.8), u01(0.0, 1.0);
  for (int trial = 0; trial < 400; ++trial) {
    const std::vector<Segment2> segments = randomSegments(rng);
    const Segment2 s{Eigen::Vector2d(x(rng), x(rng)), Eigen::Vector2d(x(rng), x(rng))};
    const Eigen::Vector2d lo(x(rng), x(rng)), hi = lo + Eigen::Vector2d::Constant(side(rng));
    const double d = squareDistance(lo, hi, s);
    double sampled = 1e9;
    for (int a = 0; a <= 40; ++a)
      for (int b = 0; b <= 40; ++b) {
        const Eigen::Vector2d p = lo + (hi - lo).cwiseProduct(Eigen::Vector2d(a / 40.0, b / 40.0));
        const double dp = std::sqrt(segmentDistance2(p, s));
        ASSERT_GE(dp, d - 1e-12) << "trial " << trial;  // never above the distance of a point of the square
        sampled = std::min(sampled, dp);
      }
    // And reached: the sampling's spacing bounds how far above the least it may be.
    EXPECT_LE(sampled - d, (hi - lo).norm() / 40.0 + 1e-12) << "trial " << trial;
  }
}

TEST(OracleField, IdenticalRoomsANonWholeNumberOfCellsApartScoreAlike) {
  // Two copies of an L room without doors, the second 20.0123 m east and 0.0371 m north: the
  // same scan placed at the same pose in each must score the same, whatever the raster.
  bim::Storey s;
  const auto room = [&](const Eigen::Vector2d& o) {
    addWall(s, {0, 0}, {6, 0}, o), addWall(s, {6, 0}, {6, 3}, o), addWall(s, {6, 3}, {3, 3}, o);
    addWall(s, {3, 3}, {3, 8}, o), addWall(s, {3, 8}, {0, 8}, o), addWall(s, {0, 8}, {0, 0}, o);
  };
  const Eigen::Vector2d shift(20.0123, 0.0371);
  room({0, 0}), room(shift);
  const OracleConfig c = smallMargin();
  const DistanceField field(wallSegmentsInBand(s, c.band_low_m, c.band_high_m), c.raster_m, c.clamp_m, c.margin_m);
  const PointModel model(c, c.clamp_m);
  std::mt19937 rng(5);
  for (const Eigen::Vector3d& pose : {Eigen::Vector3d(1.5, 1.5, 0.3), Eigen::Vector3d(1.2, 6.0, -1.2), Eigen::Vector3d(4.8, 1.2, 2.5)}) {
    PathCloud path;
    for (const auto& p : bandPoints(scanFrom(s, pose, 30.0, rng), Eigen::Isometry3d::Identity(), -0.2, 1.3, c)) path.add(p.x(), p.y());
    path.finish();
    ASSERT_GT(path.size(), 30u);
    const float a = pathScore(field, model, path, pose.x(), pose.y(), pose.z());
    const float b = pathScore(field, model, path, pose.x() + shift.x(), pose.y() + shift.y(), pose.z());
    // The points differ only by float rounding (~1e-6 m): far below a hundredth of a nat in all.
    EXPECT_NEAR(a, b, 0.01) << "pose " << pose.transpose() << ": " << path.size() << " points";
  }
  // The decision: walking inside the first room, the second explains every point: never decidable.
  const OracleVerdict v = runOracle(s, walk({{1.5, 1.5}, {4.8, 1.5}, {1.5, 1.5}, {1.5, 6.5}}), 30.0, c);
  EXPECT_GT(v.keyframes, 20);
  EXPECT_FALSE(v.decidable_at_s.has_value()) << "decidable at " << v.decidable_at_s.value_or(-1);
}
