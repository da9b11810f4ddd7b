#include "extraction.hpp"

#include <Eigen/Geometry>

namespace bimloc::bim::detail {

void appendMesh(TriangleMesh& target, const TriangleMesh& source) {
  const auto base = static_cast<std::uint32_t>(target.vertices.size());
  target.vertices.insert(target.vertices.end(), source.vertices.begin(), source.vertices.end());
  for (const auto& t : source.triangles) {
    // Zero-area triangles (slivers left by the CSG of openings) hit nothing: drop them, so
    // a mesh file holds exactly the triangles a ray caster can use.
    const Eigen::Vector3f& a = source.vertices[t[0]];
    if ((source.vertices[t[1]] - a).cross(source.vertices[t[2]] - a).norm() < 1e-12f) continue;
    target.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
}

TriangleMesh prismMesh(const Extrusion& extrusion) {
  // corners alternate bottom, top for each profile point (see ProfileReader::bodyExtrusion).
  TriangleMesh mesh;
  const auto n = static_cast<std::uint32_t>(extrusion.corners.size() / 2);
  if (n < 3) return mesh;
  for (const auto& c : extrusion.corners) mesh.vertices.push_back(c.cast<float>());
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    const std::uint32_t b0 = 2 * i, t0 = 2 * i + 1, b1 = 2 * j, t1 = 2 * j + 1;
    mesh.triangles.push_back({b0, b1, t1});
    mesh.triangles.push_back({b0, t1, t0});
  }
  // Caps as fans: wall and space profiles are convex or nearly so; the ray caster only
  // needs the side faces to be exact.
  for (std::uint32_t i = 1; i + 1 < n; ++i) {
    mesh.triangles.push_back({0, 2 * (i + 1), 2 * i});
    mesh.triangles.push_back({1, 2 * i + 1, 2 * (i + 1) + 1});
  }
  return mesh;
}

}  // namespace bimloc::bim::detail
