// A wall is judged by its area, whatever its range (PlaneExtractionConfig::ring_spacing_deg).
// The VLP-16's rings are 2 degrees apart: beyond about 3 m they are farther apart than a 10 cm
// voxel, and a wall yields one row of voxels per ring. A corridor's end wall 20 m away (1.6 m
// wide, 2.5 m high) then holds about 50 voxels, below the 60 asked of a surface near the sensor,
// and a fixed count drops it: on a floor of look-alike offices that wall is what tells them
// apart (issue 28, docs/results/2026-11-29-session30.md). The truth: the box corridor's own
// walls, analytic planes; the simulated VLP-16 (Embree) scans it.
#include "sim_fixtures.hpp"

#include "sim/lidar/vlp16.hpp"
#include "sim/world/world.hpp"

#include <bimloc/planes/plane_extraction.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace bimloc;

namespace {

constexpr double kLength_m = 40, kWidth_m = 1.6, kHeight_m = 2.5;
constexpr double kBaseHeight_m = 0.5;

struct CorridorShot {
  std::vector<Eigen::Vector3f> points;  // sensor frame
  Eigen::Isometry3d T_map_sensor;
};

CorridorShot shotAt(const sim::World& world, double x, std::uint64_t seed) {
  const sim::Vlp16Config lidar;
  Eigen::Isometry3d T_map_base = Eigen::Isometry3d::Identity();
  T_map_base.translation() = Eigen::Vector3d(x, 0.5 * kWidth_m, kBaseHeight_m);
  const auto scan = sim::Vlp16(lidar).scan(world, 0, [T_map_base](double) { return T_map_base; }, 0.0, seed, 0);
  CorridorShot shot;
  for (const auto& p : scan.points) shot.points.emplace_back(p.x, p.y, p.z);
  shot.T_map_sensor = T_map_base * lidar.T_base_lidar;
  return shot;
}

// The corridor's six faces in the map frame: n.p + d = 0, n into the corridor.
struct MapPlane {
  Eigen::Vector3d n;
  double d;
};
const std::vector<MapPlane> kFaces = {{{1, 0, 0}, 0},  {{-1, 0, 0}, kLength_m}, {{0, 1, 0}, 0},
                                      {{0, -1, 0}, kWidth_m}, {{0, 0, 1}, 0}, {{0, 0, -1}, kHeight_m}};

// Which face an extracted plane is (index into kFaces), or -1: within 2 degrees and 5 cm.
int faceOf(const planes::ObservedPlane& plane, const Eigen::Isometry3d& T_map_sensor) {
  const Eigen::Vector3d n = T_map_sensor.linear() * plane.normal;
  const double d = plane.d - n.dot(T_map_sensor.translation());
  for (std::size_t i = 0; i < kFaces.size(); ++i)
    if (n.dot(kFaces[i].n) > std::cos(2.0 * M_PI / 180.0) && std::abs(d - kFaces[i].d) < 0.05) return static_cast<int>(i);
  return -1;
}

struct Found {
  bool west = false, east = false;
  int spurious = 0;
};

Found extract(const CorridorShot& shot, const planes::PlaneExtractionConfig& config) {
  Found found;
  const auto result = planes::extractPlanes(shot.points, config);
  for (const auto* list : {&result.walls, &result.horizontals})
    for (const auto& plane : *list) {
      const int face = faceOf(plane, shot.T_map_sensor);
      found.west |= face == 0, found.east |= face == 1;
      found.spurious += face < 0;
    }
  return found;
}

}  // namespace

TEST(PlanesRange, AFarEndWallIsJudgedByItsAreaNotItsVoxelCount) {
  const sim::World world = sim::World::fromMesh(test::boxRoomFile(Eigen::Vector3f(kLength_m, kWidth_m, kHeight_m)));
  planes::PlaneExtractionConfig by_area;  // the default: ring_spacing_deg 2
  planes::PlaneExtractionConfig by_count = by_area;
  by_count.ring_spacing_deg = 0;  // min_inliers voxels at every range
  int far_walls = 0, by_area_found = 0, by_count_found = 0, spurious = 0;
  for (const std::uint64_t seed : {1, 2, 3})
    for (const double x : {16.0, 20.0, 24.0}) {
      const CorridorShot shot = shotAt(world, x, seed);
      const Found area = extract(shot, by_area), count = extract(shot, by_count);
      far_walls += 2;
      by_area_found += area.west + area.east;
      by_count_found += count.west + count.east;
      spurious += area.spurious + count.spurious;
    }
  // Both end walls (16-24 m away) from every pose, where the analytic walls are; and nothing
  // that is not one of the corridor's faces.
  EXPECT_EQ(by_area_found, far_walls);
  EXPECT_EQ(spurious, 0);
  // A fixed count of voxels drops most of them: what the rule is for.
  EXPECT_LT(by_count_found, far_walls / 2);
}

TEST(PlanesRange, NearTheSensorTheCountIsUnchanged) {
  // A patch 1.2 m wide and 0.4 m high, 2 m away, as dense as a near surface is (2 cm spacing):
  // about 50 voxels, under min_inliers; where the rings are closer than a voxel the rule asks
  // the same count as before, and the patch stays out, as furniture of that size should.
  std::vector<Eigen::Vector3f> points;
  for (double y = -0.6; y <= 0.6; y += 0.02)
    for (double z = 0.0; z <= 0.4; z += 0.02) points.emplace_back(2.0f, float(y), float(z));
  const auto found = planes::extractPlanes(points);
  EXPECT_TRUE(found.walls.empty());
  // And the same patch 1.2 m high (about 150 voxels) is a wall.
  points.clear();
  for (double y = -0.6; y <= 0.6; y += 0.02)
    for (double z = 0.0; z <= 1.2; z += 0.02) points.emplace_back(2.0f, float(y), float(z));
  ASSERT_EQ(planes::extractPlanes(points).walls.size(), 1u);
}
