// Meshes whose bytes depend on their surface alone. IFC++'s CSG (carve, and IFC++'s own
// retriangulation of its results) walks containers ordered by heap address, which changes
// from run to run and within a process: the same body comes out as the same surface cut into
// other triangles (a face split at a vertex of its neighbour in one run, a T-junction in the
// next), in another order. Here every plane of the body is cut into triangles afresh, from
// its outline alone.
#include "extraction.hpp"

#include <carve/triangulator.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <numeric>

namespace bimloc::bim::detail {
namespace {

using Key = std::array<float, 3>;
using Loop = std::vector<std::uint32_t>;

// A vertex this close to a plane lies in it, this close to an edge lies on it (float
// coordinates of a few metres are good to about 5e-7 m).
constexpr double kOnPlane_m = 5e-6;
constexpr double kOnEdge_m = 5e-6;
// A corner that turns by less than this (sine) goes straight on; a triangle that thin is a line.
constexpr double kStraight = 1e-7;

struct Triangle {
  std::array<std::uint32_t, 3> v{};
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // unit
  double offset = 0.0;                               // normal . p
  double area = 0.0;
};

struct DisjointSets {
  std::vector<std::uint32_t> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

bool straight(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d in = b - a, out = c - b;
  return in.dot(out) > 0.0 && in.cross(out).norm() <= kStraight * in.norm() * out.norm();
}

// One plane, facing one way: the corners of the smaller triangle lie in the larger's plane.
bool coplanar(const Triangle& p, const Triangle& q, const std::vector<Eigen::Vector3d>& points) {
  if (p.normal.dot(q.normal) < 0.99) return false;
  const Triangle& big = p.area >= q.area ? p : q;
  const Triangle& small = p.area >= q.area ? q : p;
  for (std::uint32_t v : small.v)
    if (std::abs(big.normal.dot(points[v]) - big.offset) > kOnPlane_m) return false;
  return true;
}

double signedArea(const std::vector<carve::geom2d::P2>& loop) {
  double area = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const auto& p = loop[i];
    const auto& q = loop[(i + 1) % loop.size()];
    area += p.x * q.y - q.x * p.y;
  }
  return 0.5 * area;
}

bool inside(const std::vector<carve::geom2d::P2>& loop, const carve::geom2d::P2& p) {
  bool in = false;
  for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++)
    if ((loop[i].y > p.y) != (loop[j].y > p.y) &&
        p.x < (loop[j].x - loop[i].x) * (p.y - loop[i].y) / (loop[j].y - loop[i].y) + loop[i].x)
      in = !in;
  return in;
}

// Directed edges that no edge of a neighbour runs back along, each `left` times.
std::vector<std::pair<std::pair<std::uint32_t, std::uint32_t>, int>> uncancelled(
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges) {
  std::sort(edges.begin(), edges.end());
  std::vector<std::pair<std::pair<std::uint32_t, std::uint32_t>, int>> out;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    const std::pair<std::uint32_t, std::uint32_t> reverse{edges[i].second, edges[i].first};
    const auto range = std::equal_range(edges.begin(), edges.end(), reverse);
    const int left = static_cast<int>(j - i) - static_cast<int>(range.second - range.first);
    if (left > 0) out.push_back({edges[i], left});
    i = j;
  }
  return out;
}

// The outline of a plane's triangles: the edges not cancelled by a neighbour's, after the
// uncancelled ones are split at the outline's vertices that lie on them (T-junctions: a
// triangle's edge with a neighbour's corner on it). next[a] = b for each outline edge a -> b.
bool outline(const std::vector<const Triangle*>& triangles, const std::vector<Eigen::Vector3d>& points,
             std::map<std::uint32_t, std::uint32_t>& next) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const Triangle* t : triangles)
    for (int k = 0; k < 3; ++k) edges.emplace_back(t->v[k], t->v[(k + 1) % 3]);
  auto open = uncancelled(edges);
  std::vector<std::uint32_t> ends;  // every T-junction is an end of an uncancelled edge
  for (const auto& [edge, left] : open) ends.push_back(edge.first), ends.push_back(edge.second);
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  std::vector<std::pair<std::uint32_t, std::uint32_t>> split;
  for (const auto& [edge, left] : open) {
    const auto [a, b] = edge;
    const Eigen::Vector3d pa = points[a], ab = points[b] - pa;
    std::vector<std::pair<double, std::uint32_t>> on;  // outline vertices strictly inside a -> b
    for (std::uint32_t v : ends) {
      if (v == a || v == b) continue;
      const double s = (points[v] - pa).dot(ab) / ab.squaredNorm();
      if (s > 0.0 && s < 1.0 && (pa + s * ab - points[v]).norm() < kOnEdge_m) on.emplace_back(s, v);
    }
    std::sort(on.begin(), on.end());
    for (int k = 0; k < left; ++k) {
      std::uint32_t from = a;
      for (const auto& [s, v] : on) split.emplace_back(from, v), from = v;
      split.emplace_back(from, b);
    }
  }
  for (const auto& [edge, left] : uncancelled(split)) {
    if (left > 1 || !next.emplace(edge.first, edge.second).second) return false;  // loops touch
  }
  return !next.empty();
}

// The triangles of one plane cut afresh from their outline: outer loops and their holes,
// corners that go straight on dropped, every loop from its smallest vertex. False (and
// nothing added) where the outline is not a set of polygons with holes.
bool remeshPlane(const std::vector<const Triangle*>& triangles, const std::vector<Eigen::Vector3d>& points,
                 std::vector<std::array<std::uint32_t, 3>>& out) {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (const Triangle* t : triangles) normal += t->area * t->normal;
  if (normal.norm() == 0.0) return false;
  normal.normalize();
  std::map<std::uint32_t, std::uint32_t> next;
  if (!outline(triangles, points, next)) return false;
  std::vector<Loop> loops;
  while (!next.empty()) {
    Loop loop{next.begin()->first};
    std::uint32_t at = next.begin()->second;
    next.erase(next.begin());
    while (at != loop.front()) {
      loop.push_back(at);
      const auto it = next.find(at);
      if (it == next.end()) return false;  // an open chain
      at = it->second;
      next.erase(it);
    }
    for (bool changed = true; changed && loop.size() > 3;) {
      changed = false;
      for (std::size_t i = 0; i < loop.size() && loop.size() > 3 && !changed; ++i) {
        const std::size_t n = loop.size();
        if (straight(points[loop[(i + n - 1) % n]], points[loop[i]], points[loop[(i + 1) % n]])) {
          loop.erase(loop.begin() + static_cast<std::ptrdiff_t>(i));
          changed = true;
        }
      }
    }
    if (loop.size() < 3) return false;
    std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
    loops.push_back(std::move(loop));
  }
  std::sort(loops.begin(), loops.end());

  int axis = 0;
  normal.cwiseAbs().maxCoeff(&axis);
  int u = (axis + 1) % 3, w = (axis + 2) % 3;
  if (normal[axis] < 0) std::swap(u, w);  // counter-clockwise seen from the normal
  const auto project = [&](const Loop& loop) {
    std::vector<carve::geom2d::P2> p;
    for (std::uint32_t i : loop) p.push_back(carve::geom::VECTOR(points[i][u], points[i][w]));
    return p;
  };
  // Outer loops run counter-clockwise, holes clockwise; a hole belongs to the smallest outer
  // loop around it.
  std::vector<std::size_t> outers, holes;
  std::vector<std::vector<carve::geom2d::P2>> projected;
  std::vector<double> area;
  for (std::size_t i = 0; i < loops.size(); ++i) {
    projected.push_back(project(loops[i]));
    area.push_back(signedArea(projected.back()));
    (area.back() > 0 ? outers : holes).push_back(i);
  }
  std::map<std::size_t, std::vector<std::size_t>> holes_of;
  for (std::size_t h : holes) {
    std::size_t best = loops.size();
    for (std::size_t o : outers)
      if (inside(projected[o], projected[h][0]) && (best == loops.size() || area[o] < area[best])) best = o;
    if (best == loops.size()) return false;
    holes_of[best].push_back(h);
  }

  std::vector<std::array<std::uint32_t, 3>> made;
  for (std::size_t o : outers) {
    std::vector<std::vector<carve::geom2d::P2>> poly{projected[o]};
    std::vector<const Loop*> ids{&loops[o]};
    double expected = area[o];
    for (std::size_t h : holes_of[o]) poly.push_back(projected[h]), ids.push_back(&loops[h]), expected += area[h];
    std::vector<carve::geom2d::P2> merged;
    Loop merged_ids;
    std::vector<carve::triangulate::tri_idx> tris;
    try {
      if (poly.size() == 1) {
        merged = poly[0], merged_ids = loops[o];
      } else {
        for (const auto& [loop, index] : carve::triangulate::incorporateHolesIntoPolygon(poly)) {
          merged.push_back(poly[loop][index]);
          merged_ids.push_back((*ids[loop])[index]);
        }
      }
      carve::triangulate::triangulate(merged, tris);
    } catch (...) {
      return false;
    }
    // The new triangles must cover the outline exactly once.
    double covered = 0.0;
    for (const auto& t : tris) covered += std::abs(signedArea({merged[t.a], merged[t.b], merged[t.c]}));
    if (tris.empty() || !(expected > 0) || std::abs(covered - expected) > 1e-6 * expected + 1e-12) return false;
    for (const auto& t : tris) {
      std::array<std::uint32_t, 3> tri{merged_ids[t.a], merged_ids[t.b], merged_ids[t.c]};
      const Eigen::Vector3d n = (points[tri[1]] - points[tri[0]]).cross(points[tri[2]] - points[tri[0]]);
      if (n.dot(normal) < 0) std::swap(tri[1], tri[2]);
      made.push_back(tri);
    }
  }
  out.insert(out.end(), made.begin(), made.end());
  return true;
}

}  // namespace

void canonicalSurface(TriangleMesh& mesh) {
  // Vertices numbered in coordinate order: the numbers depend on the points alone.
  const auto key = [](const Eigen::Vector3f& v) { return Key{v.x() + 0.0f, v.y() + 0.0f, v.z() + 0.0f}; };
  std::vector<Key> keys;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      if (mesh.vertices[t[k]].allFinite()) keys.push_back(key(mesh.vertices[t[k]]));
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<Eigen::Vector3d> points;
  for (const auto& k : keys) points.emplace_back(k[0], k[1], k[2]);
  const auto id = [&](const Eigen::Vector3f& v) {
    return static_cast<std::uint32_t>(std::lower_bound(keys.begin(), keys.end(), key(v)) - keys.begin());
  };

  std::vector<Triangle> triangles;
  for (const auto& t : mesh.triangles) {
    if (!mesh.vertices[t[0]].allFinite() || !mesh.vertices[t[1]].allFinite() || !mesh.vertices[t[2]].allFinite())
      continue;
    Triangle tri;
    tri.v = {id(mesh.vertices[t[0]]), id(mesh.vertices[t[1]]), id(mesh.vertices[t[2]])};
    const Eigen::Vector3d &a = points[tri.v[0]], &b = points[tri.v[1]], &c = points[tri.v[2]];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    // A triangle with a repeated corner or three corners on a line covers nothing.
    if (n.norm() == 0.0 || n.norm() <= kStraight * (b - a).norm() * (c - a).norm()) continue;
    tri.normal = n.normalized();
    tri.offset = tri.normal.dot(a);
    tri.area = 0.5 * n.norm();
    std::rotate(tri.v.begin(), std::min_element(tri.v.begin(), tri.v.end()), tri.v.end());
    triangles.push_back(tri);
  }
  std::sort(triangles.begin(), triangles.end(), [](const Triangle& a, const Triangle& b) { return a.v < b.v; });

  // Planes: triangles of one plane joined where they share a corner (not only an edge: a
  // T-junction leaves neighbours without a common edge).
  DisjointSets sets(triangles.size());
  std::vector<std::pair<std::uint32_t, std::uint32_t>> corners;  // (vertex, triangle)
  for (std::uint32_t i = 0; i < triangles.size(); ++i)
    for (std::uint32_t v : triangles[i].v) corners.emplace_back(v, i);
  std::sort(corners.begin(), corners.end());
  for (std::size_t begin = 0; begin < corners.size();) {
    std::size_t end = begin;
    while (end < corners.size() && corners[end].first == corners[begin].first) ++end;
    for (std::size_t x = begin; x < end; ++x)
      for (std::size_t y = x + 1; y < end; ++y) {
        const std::uint32_t p = corners[x].second, q = corners[y].second;
        if (sets.find(p) != sets.find(q) && coplanar(triangles[p], triangles[q], points)) sets.join(p, q);
      }
    begin = end;
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> planes;  // (first triangle of the plane, triangle)
  for (std::uint32_t i = 0; i < triangles.size(); ++i) planes.emplace_back(sets.find(i), i);
  std::sort(planes.begin(), planes.end());

  std::vector<std::array<std::uint32_t, 3>> result;
  std::vector<const Triangle*> plane;
  for (std::size_t begin = 0; begin < planes.size();) {
    std::size_t end = begin;
    while (end < planes.size() && planes[end].first == planes[begin].first) ++end;
    if (end - begin == 1) {
      result.push_back(triangles[planes[begin].second].v);
    } else {
      plane.clear();
      for (std::size_t k = begin; k < end; ++k) plane.push_back(&triangles[planes[k].second]);
      if (!remeshPlane(plane, points, result))
        for (const Triangle* t : plane) result.push_back(t->v);  // as they were (in a fixed order)
    }
    begin = end;
  }
  // Each triangle from its smallest vertex, triangles sorted, vertices numbered by first use:
  // vertex numbers follow coordinates, so this order depends on the surface alone.
  for (auto& t : result) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  std::sort(result.begin(), result.end());
  TriangleMesh out;
  out.triangles.reserve(result.size());
  std::vector<std::uint32_t> renumber(points.size(), UINT32_MAX);
  for (auto t : result) {
    for (auto& v : t) {
      if (renumber[v] == UINT32_MAX) {
        renumber[v] = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(points[v].cast<float>());
      }
      v = renumber[v];
    }
    out.triangles.push_back(t);
  }
  mesh = std::move(out);
}

}  // namespace bimloc::bim::detail
