// Issue 28, Speed (h28speed8): RANSAC's inlier count (planes/band_count.hpp), vectorized and
// stopped once it cannot beat the best count, against the point-by-point count and against
// points placed at known distances from their plane; and the raw returns near a plane
// (indicesInBand) against Eigen's own n.dot(p) + d, point by point; a wall's runs found
// through buckets (runsAlong) against the sorted positions (runsAlongBySorting); and RANSAC's
// inliers (pclPlaneInliers, h28speed10) against PCL's own plane model.
#include "planes/band_count.hpp"
#include "planes/plane_steps.hpp"

#include <gtest/gtest.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/sac_model_plane.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

using namespace bimloc::planes::detail;

namespace {

struct Points {
  std::vector<float> x, y, z;
  void add(const Eigen::Vector3d& p) { x.push_back(float(p.x())), y.push_back(float(p.y())), z.push_back(float(p.z())); }
  std::size_t size() const { return x.size(); }
};

}  // namespace

TEST(BandCount, CountsThePointsPlacedInsideTheBand) {
  // Points at known distances from a slanted plane: inside at most half the band, outside at
  // least twice it, so float rounding cannot move one across. Every pool size 0..300 (every
  // tail length), and the inliers interleaved at random.
  std::mt19937 rng(28);
  std::uniform_real_distribution<double> along(-8.0, 8.0), unit(-1.0, 1.0), coin(0.0, 1.0);
  const double band = 0.04;
  for (std::size_t n = 0; n <= 300; n += (n < 40 ? 1 : 13)) {
    const Eigen::Vector3d normal = Eigen::Vector3d(unit(rng), unit(rng), 0.3 * unit(rng)).normalized();
    const double d = -4.0 * coin(rng);
    const Eigen::Vector3d u = normal.unitOrthogonal(), v = normal.cross(u);
    Points pts;
    std::size_t inside = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const bool in = coin(rng) < 0.4;
      const double offset = in ? 0.5 * band * unit(rng) : (coin(rng) < 0.5 ? -1.0 : 1.0) * band * (2.0 + 10.0 * coin(rng));
      pts.add(-d * normal + along(rng) * u + along(rng) * v + offset * normal);
      inside += in;
    }
    const float a = float(normal.x()), b = float(normal.y()), c = float(normal.z()), df = float(d), t = float(band);
    EXPECT_EQ(countInBandPlain(pts.x.data(), pts.y.data(), pts.z.data(), n, a, b, c, df, t), inside) << n;
    EXPECT_EQ(countInBand(pts.x.data(), pts.y.data(), pts.z.data(), n, a, b, c, df, t, 0), inside) << n;
  }
}

TEST(BandCount, IsThePointByPointCountWhereverItCanBeatTheBest) {
  // Random points and planes, with points on the band's edge (the rounding decides them): the
  // count is the plain loop's exactly when that exceeds `best`, and never above `best` when
  // it does not (RANSAC discards it either way).
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> xyz(-12.0f, 12.0f), unit(-1.0f, 1.0f);
  for (int trial = 0; trial < 400; ++trial) {
    const std::size_t n = std::size_t(trial * 7 % 2000);
    Points pts;
    Eigen::Vector3f normal(unit(rng), unit(rng), unit(rng));
    normal.normalize();
    const float d = xyz(rng), t = 0.04f + 0.5f * std::abs(unit(rng));
    for (std::size_t i = 0; i < n; ++i) {
      Eigen::Vector3f p(xyz(rng), xyz(rng), xyz(rng));
      if (i % 3 == 0) p -= (normal.dot(p) + d - (i % 2 ? t : -t)) * normal;  // on the band's edge
      pts.x.push_back(p.x()), pts.y.push_back(p.y()), pts.z.push_back(p.z());
    }
    const std::size_t full = countInBandPlain(pts.x.data(), pts.y.data(), pts.z.data(), n, normal.x(), normal.y(), normal.z(), d, t);
    for (const std::size_t best : {std::size_t(0), full / 2, full > 0 ? full - 1 : 0, full, full + 5, n}) {
      const std::size_t got = countInBand(pts.x.data(), pts.y.data(), pts.z.data(), n, normal.x(), normal.y(), normal.z(), d, t, best);
      if (full > best)
        EXPECT_EQ(got, full) << "trial " << trial << " best " << best;
      else
        EXPECT_LE(got, best) << "trial " << trial << " best " << best;
    }
  }
}

TEST(BandCount, TheReturnsNearAPlaneAreThoseEigensResidualKeeps) {
  // pointsNearPlane's test was |n.dot(p) + d| > band in Eigen's float arithmetic, point by
  // point: the packed test must keep exactly the same points, those on the band's edge too.
  std::mt19937 rng(16);
  std::uniform_real_distribution<float> xyz(-30.0f, 30.0f), unit(-1.0f, 1.0f);
  for (int trial = 0; trial < 300; ++trial) {
    const std::size_t n = std::size_t(trial * 11 % 3000);
    Eigen::Vector3f normal(unit(rng), unit(rng), 0.2f * unit(rng));
    normal.normalize();
    const float d = xyz(rng), band = 0.04f;
    std::vector<Eigen::Vector3f> cloud;
    Points pts;
    for (std::size_t i = 0; i < n; ++i) {
      Eigen::Vector3f p(xyz(rng), xyz(rng), 3.0f * unit(rng));
      if (i % 2 == 0) p -= (normal.dot(p) + d - band * unit(rng) * 1.01f) * normal;  // in and near the band's edges
      cloud.push_back(p);
      pts.x.push_back(p.x()), pts.y.push_back(p.y()), pts.z.push_back(p.z());
    }
    std::vector<int> expected, got;
    for (std::size_t i = 0; i < n; ++i)
      if (!(std::abs(normal.dot(cloud[i]) + d) > band)) expected.push_back(static_cast<int>(i));
    indicesInBand(pts.x.data(), pts.y.data(), pts.z.data(), n, normal.x(), normal.y(), normal.z(), d, band, got);
    ASSERT_EQ(got, expected) << "trial " << trial;
  }
}

TEST(BandCount, RunsFoundInBucketsAreTheSortedPositionsRuns) {
  // Points along a wall in clusters, with gaps around the cut (gap_m exactly, a hair under and
  // over it in double, several buckets wide), some clusters wider than a bucket, indices in
  // ascending order (as RANSAC's inliers and the bands are) and a subset of the cloud.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double gap = 0.5;
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector3d dir = Eigen::Vector3d(std::cos(trial * 0.7), std::sin(trial * 0.7), 0.0).normalized();
    const Eigen::Vector3d across(-dir.y(), dir.x(), 0.0);
    std::vector<Eigen::Vector3f> cloud;
    double u = -20.0 * unit(rng);
    const int clusters = 1 + trial % 9;
    for (int c = 0; c < clusters; ++c) {
      const int count = 1 + static_cast<int>(60 * unit(rng));
      const double width = trial % 3 == 0 ? 3.0 * unit(rng) : 0.4 * unit(rng);
      for (int k = 0; k < count; ++k)
        cloud.push_back((dir * (u + width * unit(rng)) + across * 0.02 * unit(rng) + Eigen::Vector3d(0, 0, 2.5 * unit(rng))).cast<float>());
      const double kinds[] = {gap, std::nextafter(gap, 0.0), std::nextafter(gap, 1.0), 0.3, 0.7, 2.6 * gap};
      u += width + kinds[(trial + c) % 6];
    }
    std::shuffle(cloud.begin(), cloud.end(), rng);
    std::vector<int> indices;
    for (int i = 0; i < static_cast<int>(cloud.size()); ++i)
      if (trial % 2 == 0 || unit(rng) < 0.7) indices.push_back(i);
    ASSERT_EQ(runsAlong(cloud, indices, dir, gap), runsAlongBySorting(cloud, indices, dir, gap)) << "trial " << trial;
  }
}

TEST(BandCount, RansacsInliersAreThoseOfPclsOwnPlaneModel) {
  // RANSAC's last step was PCL's SampleConsensusModelPlane::selectWithinDistance; the packed
  // selection (pclPlaneInliers) must keep exactly its points, in its order, with its distances:
  // random clouds, a subset of them as the pool, points on the band's edge (the rounding
  // decides them), planes of every direction and offset, and PCL called on the same data.
  std::mt19937 rng(1013);
  std::uniform_real_distribution<float> xyz(-25.0f, 25.0f), unit(-1.0f, 1.0f);
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t n = std::size_t(3 + trial * 13 % 2500);
    pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
    Eigen::Vector3f normal(unit(rng), unit(rng), unit(rng));
    normal.normalize();
    const float d = xyz(rng);
    const double threshold = trial % 2 ? 0.04 : 0.1 + 0.2 * std::abs(unit(rng));
    for (std::size_t i = 0; i < n; ++i) {
      Eigen::Vector3f p(xyz(rng), xyz(rng), xyz(rng));
      if (i % 2 == 0) p -= (normal.dot(p) + d - float(threshold) * unit(rng) * 1.01f) * normal;  // in and on the edges
      cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    }
    pcl::Indices pool;
    for (int i = 0; i < static_cast<int>(n); ++i)
      if (trial % 3 == 0 || unit(rng) < 0.6f) pool.push_back(i);
    if (pool.size() < 3) continue;
    Eigen::VectorXf model(4);
    model << normal.x(), normal.y(), normal.z(), d;
    pcl::SampleConsensusModelPlane<pcl::PointXYZ> pcl_model(cloud, pool, false);
    pcl::Indices expected;
    pcl_model.selectWithinDistance(model, threshold, expected);
    std::vector<float> x, y, z;
    for (const int i : pool) x.push_back((*cloud)[i].x), y.push_back((*cloud)[i].y), z.push_back((*cloud)[i].z);
    std::vector<int> got;
    std::vector<double> distances;
    pclPlaneInliers(x.data(), y.data(), z.data(), pool.data(), pool.size(), model[0], model[1], model[2], model[3], threshold, got,
                    distances);
    ASSERT_EQ(got, expected) << "trial " << trial;
    ASSERT_EQ(distances.size(), got.size());
    for (std::size_t k = 0; k < got.size(); ++k) {
      const auto& p = (*cloud)[got[k]];
      EXPECT_LT(distances[k], threshold);
      EXPECT_NEAR(distances[k], std::abs(normal.dot(p.getVector3fMap()) + d), 1e-4);
    }
  }
}
