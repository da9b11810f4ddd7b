// The scan before RANSAC: valid points only, then one point per voxel (as S-Graphs does), so
// that dense surfaces near the sensor (the floor at the robot's feet) do not outvote the walls
// and RANSAC's cost does not grow with the scan.
#include "plane_steps.hpp"

#include <bimloc/verbosity.hpp>

#include <pcl/console/print.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <atomic>

// Here, where PCL is used: its level is one global, set before every use, so the library is
// quiet without its user having to call anything.
namespace bimloc {
namespace {
std::atomic<bool> g_verbose{false};
}  // namespace
void setVerbose(bool verbose) { g_verbose = verbose; }
bool verbose() { return g_verbose; }
}  // namespace bimloc

namespace bimloc::planes::detail {

void applyPclVerbosity() {
  pcl::console::setVerbosityLevel(verbose() ? pcl::console::L_INFO : pcl::console::L_ALWAYS);
}

Cloud validPoints(const Cloud& points, double min_range_m, double max_range_m) {
  Cloud valid;
  valid.reserve(points.size());
  const double min2 = min_range_m * min_range_m, max2 = max_range_m * max_range_m;
  for (const auto& p : points) {
    if (!p.allFinite()) continue;
    const double r2 = p.cast<double>().squaredNorm();
    if (r2 >= min2 && r2 <= max2) valid.push_back(p);
  }
  return valid;
}

Cloud voxelDownsample(const Cloud& points, double voxel_size_m) {
  if (points.empty() || !(voxel_size_m > 0)) return points;
  applyPclVerbosity();
  pcl::PointCloud<pcl::PointXYZ>::Ptr input(new pcl::PointCloud<pcl::PointXYZ>);
  // Sized once and filled (PointCloud::push_back updates width and height at every point): the
  // same points, width and height.
  input->resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) (*input)[i] = pcl::PointXYZ(points[i].x(), points[i].y(), points[i].z());
  // VoxelGrid sorts the points by voxel index: the output order depends only on the input.
  pcl::VoxelGrid<pcl::PointXYZ> grid;
  grid.setInputCloud(input);
  const float leaf = static_cast<float>(voxel_size_m);
  grid.setLeafSize(leaf, leaf, leaf);
  pcl::PointCloud<pcl::PointXYZ> output;
  grid.filter(output);
  Cloud result;
  result.reserve(output.size());
  for (const auto& p : output) result.emplace_back(p.x, p.y, p.z);
  return result;
}

}  // namespace bimloc::planes::detail
