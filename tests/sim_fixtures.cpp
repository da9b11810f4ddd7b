#include "sim_fixtures.hpp"

#include "sim/lidar/vlp16.hpp"
#include "sim/world/mesh_io.hpp"
#include "sim/world/world.hpp"
#include "test_support.hpp"

#include <limits>

namespace bimloc::test {

bim::TriangleMesh boxRoom(const Eigen::Vector3f& s) {
  bim::TriangleMesh m;
  for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1 ? s.x() : 0.f, i & 2 ? s.y() : 0.f, i & 4 ? s.z() : 0.f);
  const std::uint32_t quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

double boxRange(const Eigen::Vector3d& size, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir) {
  double t = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (dir[a] > 1e-12) t = std::min(t, (size[a] - origin[a]) / dir[a]);
    if (dir[a] < -1e-12) t = std::min(t, -origin[a] / dir[a]);
  }
  return t;
}

std::string boxRoomFile(const Eigen::Vector3f& size) {
  const std::string path = tempDir("box") + "/box.ply";
  sim::writeMesh(boxRoom(size), path);
  return path;
}

const sim::World& officeWorld() {
  static const sim::World world = sim::World::fromPlan(std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc");
  return world;
}

Eigen::Isometry3d pose(double x, double y, double yaw, double z) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

std::vector<planes::ObservedPlane> wallsSeenFrom(const Eigen::Isometry3d& T_map_base, const Eigen::Isometry3d& T_base_lidar) {
  sim::Vlp16Config c;
  c.T_base_lidar = T_base_lidar;
  const auto scan = sim::Vlp16(c).scan(officeWorld(), 0, [&](double) { return T_map_base; }, 0.0, 1, 0);
  std::vector<Eigen::Vector3f> points;
  for (const auto& p : scan.points) points.emplace_back(p.x, p.y, p.z);
  return planes::extractPlanes(points).walls;
}

}  // namespace bimloc::test
