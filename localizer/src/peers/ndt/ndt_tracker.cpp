#include "peers/ndt/ndt_tracker.hpp"

#include <bimloc/verbosity.hpp>

#include <pcl/console/print.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/ndt.h>
#include <pcl/search/kdtree.h>

namespace bimloc::peers {

using PclCloud = pcl::PointCloud<pcl::PointXYZ>;

namespace {
// PCL prints to stderr (a flat voxel's "Invalid eigen value"): quiet unless bimloc::verbose(),
// as planes/ransac_plane.cpp sets it before PCL runs.
struct QuietPcl {
  QuietPcl() { pcl::console::setVerbosityLevel(verbose() ? pcl::console::L_INFO : pcl::console::L_ALWAYS); }
};

PclCloud::Ptr toPcl(const Cloud3& points) {
  PclCloud::Ptr out(new PclCloud);
  out->reserve(points.size());
  for (const auto& p : points)
    if (p.allFinite()) out->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  return out;
}
}  // namespace

struct NdtTracker::Impl {
  NdtConfig config;
  PclCloud::Ptr map;
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree;  // the map's; NDT's Registration base shares it
  mutable pcl::NormalDistributionsTransform<pcl::PointXYZ, pcl::PointXYZ> ndt;

  void measure(const PclCloud& scan_in_map, NdtAlignment& a) const {
    const double max2 = config.fitness_max_distance_m * config.fitness_max_distance_m;
    pcl::Indices k(1);
    std::vector<float> d2(1);
    double sum = 0;
    std::size_t n = 0;
    for (const auto& p : scan_in_map) {
      if (tree->nearestKSearch(p, 1, k, d2) < 1 || d2[0] > max2) continue;
      sum += d2[0];
      ++n;
    }
    a.fitness_m2 = n ? sum / static_cast<double>(n) : max2;
    a.inlier_fraction = scan_in_map.empty() ? 0.0 : static_cast<double>(n) / static_cast<double>(scan_in_map.size());
    a.good = n > 0 && a.fitness_m2 <= config.max_fitness_m2 && a.inlier_fraction >= config.min_inlier_fraction;
  }
};

NdtTracker::NdtTracker(const Cloud3& map, const NdtConfig& config) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.config = config;
  m.map = toPcl(map);
  if (m.map->empty()) return;
  m.tree.reset(new pcl::search::KdTree<pcl::PointXYZ>);
  m.tree->setInputCloud(m.map);
  m.ndt.setResolution(static_cast<float>(config.ndt_resolution_m));
  m.ndt.setStepSize(config.ndt_step_size_m);
  m.ndt.setMaximumIterations(config.ndt_max_iterations);
  // PCL 1.13 ends when the squared translation of a step is below the epsilon (ndt.hpp).
  m.ndt.setTransformationEpsilon(config.ndt_epsilon_m * config.ndt_epsilon_m);
  const QuietPcl quiet;
  m.ndt.setInputTarget(m.map);
  m.ndt.setSearchMethodTarget(m.tree, true);  // the tree above, never rebuilt
}

NdtTracker::~NdtTracker() = default;

bool NdtTracker::ready() const { return !impl_->map->empty(); }

NdtAlignment NdtTracker::align(const Cloud3& scan, const Eigen::Isometry3d& guess_map_lidar) const {
  NdtAlignment a;
  a.T_map_lidar = guess_map_lidar;
  PclCloud::Ptr source = toPcl(scan);
  if (!ready() || source->empty()) return a;
  Impl& m = *impl_;
  const QuietPcl quiet;
  m.ndt.setInputSource(source);
  PclCloud aligned;
  m.ndt.align(aligned, guess_map_lidar.matrix().cast<float>());
  const Eigen::Matrix4d T = m.ndt.getFinalTransformation().cast<double>();
  a.iterations = m.ndt.getFinalNumIteration();
  if (!T.allFinite()) return a;
  a.T_map_lidar.matrix() = T;
  // Re-orthonormalize (float accumulation) so that the pose stays a rigid motion.
  a.T_map_lidar.linear() = Eigen::Quaterniond(a.T_map_lidar.linear()).normalized().toRotationMatrix();
  m.measure(aligned, a);
  return a;
}

NdtAlignment NdtTracker::fitness(const Cloud3& scan, const Eigen::Isometry3d& T_map_lidar) const {
  NdtAlignment a;
  a.T_map_lidar = T_map_lidar;
  if (!ready()) return a;
  PclCloud moved;
  const Eigen::Isometry3f T = T_map_lidar.cast<float>();
  for (const auto& p : scan)
    if (p.allFinite()) {
      const Eigen::Vector3f q = T * p;
      moved.push_back(pcl::PointXYZ(q.x(), q.y(), q.z()));
    }
  impl_->measure(moved, a);
  return a;
}

}  // namespace bimloc::peers
