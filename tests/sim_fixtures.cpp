#include "sim_fixtures.hpp"

#include "sim/world/mesh_io.hpp"
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

}  // namespace bimloc::test
