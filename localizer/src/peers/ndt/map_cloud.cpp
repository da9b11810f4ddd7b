#include "peers/ndt/map_cloud.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::peers {

Cloud3 sampleMesh(const bim::TriangleMesh& mesh, double spacing_m) {
  Cloud3 out;
  if (!(spacing_m > 0)) return out;
  const auto steps = [spacing_m](double length) { return std::max(1, static_cast<int>(std::ceil(length / spacing_m))); };
  for (const auto& t : mesh.triangles) {
    if (t[0] >= mesh.vertices.size() || t[1] >= mesh.vertices.size() || t[2] >= mesh.vertices.size()) continue;
    Eigen::Vector3d v[3] = {mesh.vertices[t[0]].cast<double>(), mesh.vertices[t[1]].cast<double>(), mesh.vertices[t[2]].cast<double>()};
    if (!v[0].allFinite() || !v[1].allFinite() || !v[2].allFinite()) continue;
    // a-b the longest edge, c the apex.
    int longest = 0;
    double best = -1;
    for (int e = 0; e < 3; ++e) {
      const double l = (v[(e + 1) % 3] - v[e]).norm();
      if (l > best) best = l, longest = e;
    }
    const Eigen::Vector3d a = v[longest], b = v[(longest + 1) % 3], c = v[(longest + 2) % 3];
    const double base = (b - a).norm();
    if (!(base > 0)) {
      out.push_back(a.cast<float>());
      continue;
    }
    const double height = (b - a).cross(c - a).norm() / base;
    const int rows = steps(height);
    for (int r = 0; r <= rows; ++r) {
      const double s = static_cast<double>(r) / rows;  // 0 at the base, 1 at the apex
      const Eigen::Vector3d p = a + (c - a) * s, q = b + (c - b) * s;
      const int n = r == rows ? 0 : steps((q - p).norm());
      for (int k = 0; k <= n; ++k) out.push_back((n == 0 ? p : p + (q - p) * (static_cast<double>(k) / n)).cast<float>());
    }
  }
  return out;
}

Cloud2 sliceBand(const Cloud3& points, double min_z, double max_z) {
  Cloud2 out;
  for (const auto& p : points)
    if (p.allFinite() && min_z < p.z() && p.z() < max_z) out.push_back(p.head<2>());
  return out;
}

}  // namespace bimloc::peers
