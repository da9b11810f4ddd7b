// Face openings: where a wall's face has no surface (paper, "Building Information
// Extraction", takes a wall as two planes; a real wall's face has holes).
//
// A window's glass, a door leaf, the reveal behind a recess are planes parallel to the face a
// few centimetres to decimetres behind it (FZK-Haus: the panes 0.12-0.18 m behind the face of
// its 0.30 m outer walls). Inside the association gate of the face, a plane fitted to one of
// them is taken for the wall and pulls the pose by that much. The wall's body mesh, with its
// openings already cut (by cutOpenings for box bodies and rebuilt ones, else by IFC++), knows where the face
// is: we rasterise the body's triangles lying on each face, and the empty parts of the face
// that are enclosed by it are its openings.
#include "extraction.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

namespace bimloc::bim::detail {
namespace {

constexpr double kCell_m = 0.05;          // raster resolution on the face
constexpr double kOnFace_m = 0.01;        // a triangle this close to the face's plane is on it
constexpr double kMinOpening_m = 0.3;     // smaller holes (ducts, sockets) hide no plane a scan keeps
constexpr std::size_t kMaxCells = 4000000;  // a 10 km wall at 5 cm: beyond, no openings are sought

struct Raster {
  int nu = 0, nz = 0;
  std::vector<char> covered;
  char& at(int u, int z) { return covered[static_cast<std::size_t>(z) * static_cast<std::size_t>(nu) + static_cast<std::size_t>(u)]; }
};

bool insideTriangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& x, const Eigen::Vector2d& y) {
    return (x - o).x() * (y - o).y() - (x - o).y() * (y - o).x();
  };
  const double d1 = cross(a, b, p), d2 = cross(b, c, p), d3 = cross(c, a, p);
  const double eps = 1e-9;
  const bool neg = d1 < -eps || d2 < -eps || d3 < -eps, pos = d1 > eps || d2 > eps || d3 > eps;
  return !(neg && pos);
}

// The face's surface from the body's triangles on it, in (along, up) cells.
Raster rasterise(const WallFace& face, double z0, double height_m, const TriangleMesh& body) {
  Raster r;
  const double length = face.length_m();
  r.nu = static_cast<int>(std::ceil(length / kCell_m));
  r.nz = static_cast<int>(std::ceil(height_m / kCell_m));
  if (r.nu <= 0 || r.nz <= 0 || static_cast<std::size_t>(r.nu) * static_cast<std::size_t>(r.nz) > kMaxCells) return {};
  r.covered.assign(static_cast<std::size_t>(r.nu) * static_cast<std::size_t>(r.nz), 0);
  const Eigen::Vector3d t = (face.end - face.start) / length;
  const double facing = std::cos(5.0 * M_PI / 180.0);
  for (const auto& tri : body.triangles) {
    Eigen::Vector3d p[3];
    for (int i = 0; i < 3; ++i) p[i] = body.vertices[tri[static_cast<std::size_t>(i)]].cast<double>();
    const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);
    if (!(n.norm() > 1e-12) || n.normalized().dot(face.plane.n) < facing) continue;
    if (std::abs(face.plane.signedDistance((p[0] + p[1] + p[2]) / 3.0)) > kOnFace_m) continue;
    Eigen::Vector2d q[3];
    for (int i = 0; i < 3; ++i) q[i] = Eigen::Vector2d(t.dot(p[i] - face.start), p[i].z() - z0);
    const Eigen::Vector2d lo = q[0].cwiseMin(q[1]).cwiseMin(q[2]), hi = q[0].cwiseMax(q[1]).cwiseMax(q[2]);
    const int u0 = std::max(0, static_cast<int>(std::floor(lo.x() / kCell_m))), u1 = std::min(r.nu - 1, static_cast<int>(std::floor(hi.x() / kCell_m)));
    const int z0c = std::max(0, static_cast<int>(std::floor(lo.y() / kCell_m))), z1c = std::min(r.nz - 1, static_cast<int>(std::floor(hi.y() / kCell_m)));
    for (int z = z0c; z <= z1c; ++z)
      for (int u = u0; u <= u1; ++u)
        if (!r.at(u, z) && insideTriangle(Eigen::Vector2d((u + 0.5) * kCell_m, (z + 0.5) * kCell_m), q[0], q[1], q[2])) r.at(u, z) = 1;
  }
  return r;
}

}  // namespace

std::vector<FaceOpening> faceOpenings(const WallFace& face, double z0, double height_m, const TriangleMesh& body) {
  std::vector<FaceOpening> out;
  Raster r = rasterise(face, z0, height_m, body);
  if (r.covered.empty() || std::none_of(r.covered.begin(), r.covered.end(), [](char c) { return c != 0; })) return out;
  // Empty cells, 4-connected; a component that spans the whole height is no hole but a gap
  // between parts of the face (a mitred corner, a wall drawn in two pieces).
  for (int z = 0; z < r.nz; ++z)
    for (int u = 0; u < r.nu; ++u) {
      if (r.at(u, z)) continue;
      int umin = u, umax = u, zmin = z, zmax = z;
      std::deque<std::pair<int, int>> queue{{u, z}};
      r.at(u, z) = 2;
      while (!queue.empty()) {
        const auto [cu, cz] = queue.front();
        queue.pop_front();
        umin = std::min(umin, cu), umax = std::max(umax, cu), zmin = std::min(zmin, cz), zmax = std::max(zmax, cz);
        const int nu[4] = {cu - 1, cu + 1, cu, cu}, nz[4] = {cz, cz, cz - 1, cz + 1};
        for (int k = 0; k < 4; ++k)
          if (nu[k] >= 0 && nu[k] < r.nu && nz[k] >= 0 && nz[k] < r.nz && r.at(nu[k], nz[k]) == 0) {
            r.at(nu[k], nz[k]) = 2;
            queue.emplace_back(nu[k], nz[k]);
          }
      }
      const double w = (umax - umin + 1) * kCell_m, h = (zmax - zmin + 1) * kCell_m;
      if (zmin == 0 && zmax == r.nz - 1) continue;
      if (w < kMinOpening_m || h < kMinOpening_m) continue;
      out.push_back({umin * kCell_m, std::min(face.length_m(), (umax + 1) * kCell_m), z0 + zmin * kCell_m,
                     z0 + std::min(height_m, (zmax + 1) * kCell_m)});
    }
  return out;
}

}  // namespace bimloc::bim::detail
