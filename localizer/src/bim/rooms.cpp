#include "extraction.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>

namespace bimloc::bim::detail {
namespace {

using Key = std::pair<long long, long long>;

// Vertices closer than 0.1 mm are one vertex: meshes repeat corners per face.
Key weld(const Eigen::Vector2d& p) {
  return {std::llround(p.x() * 1e4), std::llround(p.y() * 1e4)};
}

// The outline of the space's floor: the boundary edges of its horizontal triangles at the
// lowest z, chained into loops; the loop of largest area is the footprint.
Polygon2 floorOutline(const TriangleMesh& mesh, double z_floor) {
  std::map<std::pair<Key, Key>, int> edge_count;  // undirected edge -> uses
  std::map<Key, Eigen::Vector2d> position;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>(), b = mesh.vertices[t[1]].cast<double>(),
                          c = mesh.vertices[t[2]].cast<double>();
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() < 1e-12 || std::abs(n.z()) < 0.99 * n.norm()) continue;
    if (std::abs(a.z() - z_floor) > 0.01 || std::abs(b.z() - z_floor) > 0.01 || std::abs(c.z() - z_floor) > 0.01)
      continue;
    const Key k[3] = {weld(a.head<2>()), weld(b.head<2>()), weld(c.head<2>())};
    position[k[0]] = a.head<2>(), position[k[1]] = b.head<2>(), position[k[2]] = c.head<2>();
    for (int i = 0; i < 3; ++i) {
      Key p = k[i], q = k[(i + 1) % 3];
      if (p == q) continue;
      if (q < p) std::swap(p, q);
      ++edge_count[{p, q}];
    }
  }
  std::map<Key, std::vector<Key>> adjacent;
  for (const auto& [edge, count] : edge_count)
    if (count == 1) adjacent[edge.first].push_back(edge.second), adjacent[edge.second].push_back(edge.first);
  const auto take = [&](const Key& from, const Key& to) {
    auto& f = adjacent[from];
    f.erase(std::find(f.begin(), f.end(), to));
    auto& t = adjacent[to];
    t.erase(std::find(t.begin(), t.end(), from));
  };

  Polygon2 best;
  double best_area = 0.0;
  for (auto it = adjacent.begin(); it != adjacent.end(); ++it) {
    while (!it->second.empty()) {
      const Key start = it->first;
      Key cur = it->second.front();
      take(start, cur);
      Polygon2 loop{position[start]};
      while (cur != start && !adjacent[cur].empty()) {
        loop.push_back(position[cur]);
        const Key to = adjacent[cur].front();
        take(cur, to);
        cur = to;
      }
      const double area = std::abs(signedArea(loop));
      if (area > best_area) best_area = area, best = loop;
    }
  }
  return best;
}

}  // namespace

std::optional<Room> roomFromGeometry(const RawProduct& space, std::string& problem) {
  Room room;
  room.id = space.global_id;
  room.name = space.name;
  room.long_name = space.long_name;
  Polygon2 outline;
  if (!space.mesh.empty()) {
    double z_min = std::numeric_limits<double>::infinity(), z_max = -z_min;
    for (const auto& v : space.mesh.vertices) z_min = std::min(z_min, double(v.z())), z_max = std::max(z_max, double(v.z()));
    outline = floorOutline(space.mesh, z_min);
    room.floor_z = z_min;
    room.height_m = z_max - z_min;
  }
  if (outline.size() < 3 && space.extrusion && space.extrusion->vertical) {
    outline = space.extrusion->footprint;
    room.floor_z = space.extrusion->z_min;
    room.height_m = space.extrusion->z_max - space.extrusion->z_min;
  }
  outline = simplifyPolygon(outline, 1e-3);
  if (outline.size() < 3 || std::abs(signedArea(outline)) < 1e-4) {
    problem = space.mesh.empty() && !space.extrusion
                  ? (space.geometry_problem.empty() ? "no body geometry" : space.geometry_problem)
                  : "no floor outline in its geometry";
    return std::nullopt;
  }
  room.footprint = outline;
  room.area_m2 = signedArea(outline);
  room.centre = areaCentroid(outline);
  return room;
}

}  // namespace bimloc::bim::detail
