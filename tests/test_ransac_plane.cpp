// Issue 28, Speed: RANSAC's plane (planes/ransac_plane.cpp) is PCL's RandomSampleConsensus over
// its SampleConsensusModelPlane written out over a packed pool. The oracle is PCL's own classes
// (PCL 1.13), run on the same points, pool and seed: the same plane and the same inliers, to
// the bit, over generated scans of walls, floors and clutter, every iteration budget and band
// the extraction uses, and pools that are degenerate.
#include "planes/plane_steps.hpp"

#include <gtest/gtest.h>

#include <pcl/console/print.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_plane.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

using bimloc::planes::detail::Cloud;
using bimloc::planes::detail::Indices;
using bimloc::planes::detail::RansacPlane;
using bimloc::planes::detail::ransacPlane;

namespace {

// PCL's plane model, reseeded (PCL seeds it with 12345): nothing else of PCL's changed.
class SeededModel : public pcl::SampleConsensusModelPlane<pcl::PointXYZ> {
 public:
  SeededModel(const PointCloudConstPtr& cloud, const pcl::Indices& indices, std::uint32_t seed)
      : pcl::SampleConsensusModelPlane<pcl::PointXYZ>(cloud, indices, false) {
    rng_alg_.seed(seed);
  }
};

// What PCL's classes give, in RansacPlane's terms (normal scaled to unit, inliers ascending).
std::optional<RansacPlane> pclRansac(const Cloud& cloud, const Indices& pool, int iterations, double threshold_m,
                                     std::uint32_t seed) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // collinear draws are ordinary events
  pcl::PointCloud<pcl::PointXYZ>::Ptr points(new pcl::PointCloud<pcl::PointXYZ>);
  for (const auto& p : cloud) points->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  auto model = std::make_shared<SeededModel>(points, pcl::Indices(pool.begin(), pool.end()), seed);
  pcl::RandomSampleConsensus<pcl::PointXYZ> ransac(model, threshold_m);
  ransac.setMaxIterations(iterations);
  ransac.setProbability(0.99);
  ransac.setNumberOfThreads(-1);
  if (!ransac.computeModel()) return std::nullopt;
  Eigen::VectorXf c;
  ransac.getModelCoefficients(c);
  pcl::Indices inliers;
  ransac.getInliers(inliers);
  if (c.size() != 4 || !c.allFinite() || inliers.empty()) return std::nullopt;
  RansacPlane plane;
  plane.normal = c.head<3>().cast<double>();
  const double norm = plane.normal.norm();
  plane.normal /= norm;
  plane.d = c[3] / norm;
  plane.inliers.assign(inliers.begin(), inliers.end());
  std::sort(plane.inliers.begin(), plane.inliers.end());
  return plane;
}

// A scan's voxels: a few walls, a floor and a ceiling, each a patch of points with sensor
// noise, and clutter scattered among them.
Cloud generatedScan(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), coin(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.01);
  Cloud cloud;
  const int walls = 1 + static_cast<int>(coin(rng) * 5);
  for (int w = 0; w < walls + 2; ++w) {
    const bool horizontal = w >= walls;
    Eigen::Vector3d normal = horizontal ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d(unit(rng), unit(rng), 0.05 * unit(rng));
    normal.normalize();
    const Eigen::Vector3d u = normal.unitOrthogonal(), v = normal.cross(u);
    const Eigen::Vector3d origin = horizontal ? Eigen::Vector3d(0, 0, w == walls ? -0.6 : 2.2) : 6.0 * coin(rng) * normal;
    const int n = 40 + static_cast<int>(coin(rng) * 600);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector3d p = origin + 5.0 * unit(rng) * u + 1.5 * unit(rng) * v + noise(rng) * normal;
      cloud.push_back(p.cast<float>());
    }
  }
  const int clutter = static_cast<int>(coin(rng) * 400);
  for (int i = 0; i < clutter; ++i) cloud.push_back(Eigen::Vector3d(8 * unit(rng), 8 * unit(rng), 1.5 * unit(rng)).cast<float>());
  return cloud;
}

void expectSame(const std::optional<RansacPlane>& ours, const std::optional<RansacPlane>& pcl, const char* what) {
  ASSERT_EQ(ours.has_value(), pcl.has_value()) << what;
  if (!ours) return;
  EXPECT_EQ(ours->normal, pcl->normal) << what;  // to the bit
  EXPECT_EQ(ours->d, pcl->d) << what;
  EXPECT_EQ(ours->inliers, pcl->inliers) << what;
}

}  // namespace

TEST(RansacPlane, FindsWhatPclsOwnClassesFindOnGeneratedScans) {
  std::mt19937 rng(3601);
  std::uniform_real_distribution<double> coin(0.0, 1.0);
  int planes = 0;
  for (int scan = 0; scan < 60; ++scan) {
    const Cloud cloud = generatedScan(rng);
    // The whole scan, then pools as the extraction leaves them: what earlier planes left.
    for (int round = 0; round < 4; ++round) {
      Indices pool;
      const double keep = round == 0 ? 1.0 : 0.3 + 0.6 * coin(rng);
      for (int i = 0; i < static_cast<int>(cloud.size()); ++i)
        if (coin(rng) < keep) pool.push_back(i);
      const int iterations = round == 3 ? 1 + static_cast<int>(coin(rng) * 20) : 500;
      const double band = round == 2 ? 0.01 : 0.04;
      const auto seed = static_cast<std::uint32_t>(rng());
      const auto ours = ransacPlane(cloud, pool, iterations, band, seed);
      expectSame(ours, pclRansac(cloud, pool, iterations, band, seed), "generated scan");
      planes += ours ? 1 : 0;
    }
  }
  EXPECT_GT(planes, 200);  // the comparison is of planes found, not of two "none"s
}

TEST(RansacPlane, FindsWhatPclsOwnClassesFindOnDegeneratePools) {
  // Repeated points (draws of collinear samples, drawn again), a pool of three, and a plane with
  // most of its points stacked on a few spots.
  std::mt19937 rng(3602);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int k = 0; k < 20; ++k) {
    Cloud cloud;
    const int spots = 3 + k % 4;
    for (int s = 0; s < spots; ++s) {
      const Eigen::Vector3f p(float(unit(rng)), float(unit(rng)), float(0.01 * unit(rng)));
      for (int r = 0; r < 1 + k; ++r) cloud.push_back(p);
    }
    for (int i = 0; i < k * 5; ++i) cloud.push_back(Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).cast<float>());
    Indices pool(cloud.size());
    for (std::size_t i = 0; i < pool.size(); ++i) pool[i] = static_cast<int>(i);
    const auto seed = static_cast<std::uint32_t>(rng());
    expectSame(ransacPlane(cloud, pool, 500, 0.04, seed), pclRansac(cloud, pool, 500, 0.04, seed), "stacked points");
    const Indices three = {0, static_cast<int>(cloud.size()) / 2, static_cast<int>(cloud.size()) - 1};
    expectSame(ransacPlane(cloud, three, 500, 0.04, seed), pclRansac(cloud, three, 500, 0.04, seed), "a pool of three");
  }
}
