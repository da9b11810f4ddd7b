// 2D polygon helpers against analytic answers.
#include <bimloc/bim/geometry2d.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace bimloc::bim;

TEST(Geometry2d, AreaAndCentroidOfAnLShape) {
  // 4 x 4 square minus its 2 x 2 top-right quarter: area 12, centroid by composition.
  const Polygon2 l = {{0, 0}, {4, 0}, {4, 2}, {2, 2}, {2, 4}, {0, 4}};
  EXPECT_DOUBLE_EQ(signedArea(l), 12.0);
  const Eigen::Vector2d expected = (16.0 * Eigen::Vector2d(2, 2) - 4.0 * Eigen::Vector2d(3, 3)) / 12.0;
  EXPECT_NEAR((areaCentroid(l) - expected).norm(), 0.0, 1e-12);
  EXPECT_TRUE(pointInPolygon(l, {1, 3}));
  EXPECT_FALSE(pointInPolygon(l, {3, 3}));
}

TEST(Geometry2d, MinAreaRectangleOfRotatedBoxes) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), size(0.05, 10.0), shift(-50, 50);
  for (int trial = 0; trial < 200; ++trial) {
    const double a = angle(rng), length = size(rng), width = std::min(size(rng), length);
    const Eigen::Vector2d u(std::cos(a), std::sin(a)), v(-u.y(), u.x()), c(shift(rng), shift(rng));
    std::vector<Eigen::Vector2d> pts;
    for (int i : {-1, 1})
      for (int j : {-1, 1}) pts.push_back(c + 0.5 * i * length * u + 0.5 * j * width * v);
    pts.push_back(c);  // interior points must not matter
    const Rectangle2 r = minAreaRectangle(convexHull(pts));
    EXPECT_NEAR(r.length, length, 1e-9);
    EXPECT_NEAR(r.width, width, 1e-9);
    EXPECT_NEAR((r.centre - c).norm(), 0.0, 1e-9);
    if (length - width > 1e-6) {
      EXPECT_NEAR(std::abs(r.axis.dot(u)), 1.0, 1e-9);
    }
  }
}

TEST(Geometry2d, SimplifyDropsCollinearAndDuplicateVerticesAndOrientsCounterClockwise) {
  const Polygon2 cw = {{0, 0}, {0, 2}, {0, 4}, {3, 4}, {3, 4}, {3, 0}, {1.5, 0}};
  const Polygon2 s = simplifyPolygon(cw);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_DOUBLE_EQ(signedArea(s), 12.0);
}

TEST(Geometry2d, DistanceToASegmentIsToItsNearestPointAndSegmentsCrossOnlyInside) {
  const Eigen::Vector2d a(1, 1), b(4, 5);  // length 5
  EXPECT_NEAR(distanceToSegment({1, 1}, a, b), 0.0, 1e-12);
  EXPECT_NEAR(distanceToSegment({-2, -3}, a, b), 5.0, 1e-12);       // beyond a, along the line
  EXPECT_NEAR(distanceToSegment({8, 8}, a, b), 5.0, 1e-12);         // beyond b: (8,8)-(4,5)
  EXPECT_NEAR(distanceToSegment({2.5 + 4, 3 - 3}, a, b), 5.0, 1e-12);  // off its middle, along the normal
  EXPECT_NEAR(distanceToSegment({4, 5}, a, a), std::hypot(3.0, 4.0), 1e-12);  // a point segment
  EXPECT_TRUE(segmentsCross({0, 0}, {2, 2}, {0, 2}, {2, 0}));
  EXPECT_FALSE(segmentsCross({0, 0}, {1, 1}, {0, 2}, {2, 0}));  // they meet at (1, 1): an end touches
  EXPECT_FALSE(segmentsCross({0, 0}, {0.9, 0.9}, {0, 2}, {2, 0}));
  EXPECT_FALSE(segmentsCross({0, 0}, {2, 0}, {1, 0}, {3, 0}));  // collinear
}
