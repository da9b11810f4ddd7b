#include "peers/amcl/grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace bimloc::peers::amcl {

Grid::Grid(const Eigen::Vector2d& lower, const Eigen::Vector2d& upper, double resolution) : origin(lower), resolution_m(resolution) {
  width = std::max(1, static_cast<int>(std::ceil((upper.x() - lower.x()) / resolution)));
  height = std::max(1, static_cast<int>(std::ceil((upper.y() - lower.y()) / resolution)));
  occupied.assign(static_cast<std::size_t>(width) * height, 0);
}

Eigen::Vector2i Grid::cellOf(double x, double y) const {
  // Clamped before the cast: a point far off the map must not overflow int.
  const double fx = std::clamp((x - origin.x()) / resolution_m, -1e9, 1e9), fy = std::clamp((y - origin.y()) / resolution_m, -1e9, 1e9);
  return {static_cast<int>(std::floor(fx)), static_cast<int>(std::floor(fy))};
}

std::size_t Grid::occupiedCount() const { return static_cast<std::size_t>(std::count(occupied.begin(), occupied.end(), 1)); }

void Grid::markSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  // Amanatides & Woo's traversal: every cell the segment crosses, none it does not.
  Eigen::Vector2i c = cellOf(a.x(), a.y());
  const Eigen::Vector2i end = cellOf(b.x(), b.y());
  const Eigen::Vector2d d = b - a;
  const int step_x = d.x() > 0 ? 1 : -1, step_y = d.y() > 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  const auto boundary = [&](int cell, int step, double o) { return o + resolution_m * (step > 0 ? cell + 1 : cell); };
  double t_max_x = d.x() != 0 ? (boundary(c.x(), step_x, origin.x()) - a.x()) / d.x() : inf;
  double t_max_y = d.y() != 0 ? (boundary(c.y(), step_y, origin.y()) - a.y()) / d.y() : inf;
  const double t_dx = d.x() != 0 ? resolution_m / std::abs(d.x()) : inf, t_dy = d.y() != 0 ? resolution_m / std::abs(d.y()) : inf;
  const int steps = std::abs(end.x() - c.x()) + std::abs(end.y() - c.y());
  for (int k = 0;; ++k) {
    if (contains(c.x(), c.y())) occupied[index(c.x(), c.y())] = 1;
    if (k >= steps) break;
    if (t_max_x < t_max_y) {
      c.x() += step_x, t_max_x += t_dx;
    } else {
      c.y() += step_y, t_max_y += t_dy;
    }
  }
}

void Grid::markConvex(const std::vector<Eigen::Vector2d>& polygon) {
  if (polygon.empty()) return;
  for (std::size_t k = 0; k < polygon.size(); ++k) markSegment(polygon[k], polygon[(k + 1) % polygon.size()]);
  if (polygon.size() < 3) return;
  // The interior: on each row of cell centres, the span between the edges it crosses.
  double y_lo = polygon[0].y(), y_hi = y_lo;
  for (const auto& p : polygon) y_lo = std::min(y_lo, p.y()), y_hi = std::max(y_hi, p.y());
  const int j0 = std::max(0, cellOf(0, y_lo).y()), j1 = std::min(height - 1, cellOf(0, y_hi).y());
  for (int j = j0; j <= j1; ++j) {
    const double y = centre(0, j).y();
    double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo;
    for (std::size_t k = 0; k < polygon.size(); ++k) {
      const Eigen::Vector2d& p = polygon[k];
      const Eigen::Vector2d& q = polygon[(k + 1) % polygon.size()];
      if ((p.y() - y) * (q.y() - y) > 0 || p.y() == q.y()) continue;
      const double x = p.x() + (y - p.y()) / (q.y() - p.y()) * (q.x() - p.x());
      x_lo = std::min(x_lo, x), x_hi = std::max(x_hi, x);
    }
    if (x_lo > x_hi) continue;
    const int i0 = std::max(0, static_cast<int>(std::ceil((x_lo - origin.x()) / resolution_m - 0.5)));
    const int i1 = std::min(width - 1, static_cast<int>(std::floor((x_hi - origin.x()) / resolution_m - 0.5)));
    for (int i = i0; i <= i1; ++i) occupied[index(i, j)] = 1;
  }
}

std::vector<Eigen::Vector2d> clipToSlab(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, double z0, double z1) {
  // Sutherland-Hodgman against z >= z0, then z <= z1.
  std::vector<Eigen::Vector3d> poly{a, b, c};
  const auto clip = [&poly](double z, double sign) {
    std::vector<Eigen::Vector3d> out;
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const Eigen::Vector3d& p = poly[k];
      const Eigen::Vector3d& q = poly[(k + 1) % poly.size()];
      const double dp = sign * (p.z() - z), dq = sign * (q.z() - z);
      if (dp >= 0) out.push_back(p);
      if ((dp >= 0) != (dq >= 0)) out.push_back(p + (q - p) * (dp / (dp - dq)));
    }
    poly = std::move(out);
  };
  clip(z0, 1.0);
  if (!poly.empty()) clip(z1, -1.0);
  std::vector<Eigen::Vector2d> flat;
  for (const auto& p : poly) flat.push_back(p.head<2>());
  return flat;
}

namespace {

bool isDoorPart(const bim::MeshPart& part) { return part.ifc_class == "IfcDoor" || part.ifc_class == "IfcDoorStandardCase"; }

// Triangles of door leaves, to leave out of the map.
std::vector<bool> doorTriangles(const bim::Storey& storey) {
  std::vector<bool> door(storey.mesh.triangles.size(), false);
  for (const auto& part : storey.mesh_parts) {
    if (!isDoorPart(part)) continue;
    const std::size_t end = std::min<std::size_t>(door.size(), std::size_t{part.first_triangle} + part.triangle_count);
    for (std::size_t t = part.first_triangle; t < end; ++t) door[t] = true;
  }
  return door;
}

// A grid of at most this many cells (about 40 MB with the likelihood field): a larger plan
// gets coarser cells, with a warning.
constexpr double kMaxCells = 1e7;

}  // namespace

StoreySlice sliceStorey(const bim::Storey& storey, const AmclConfig& config) {
  StoreySlice out;
  const double z0 = storey.elevation_m + config.band_min_m, z1 = storey.elevation_m + config.band_max_m;
  const auto& mesh = storey.mesh;
  const std::vector<bool> door = config.map_doors ? std::vector<bool>(mesh.triangles.size(), false) : doorTriangles(storey);
  std::vector<std::vector<Eigen::Vector2d>> pieces;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  std::size_t bad = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (door[t]) continue;
    const auto& tri = mesh.triangles[t];
    if (tri[0] >= mesh.vertices.size() || tri[1] >= mesh.vertices.size() || tri[2] >= mesh.vertices.size()) {
      ++bad;
      continue;
    }
    const Eigen::Vector3d a = mesh.vertices[tri[0]].cast<double>(), b = mesh.vertices[tri[1]].cast<double>(), c = mesh.vertices[tri[2]].cast<double>();
    if (!a.allFinite() || !b.allFinite() || !c.allFinite()) {
      ++bad;
      continue;
    }
    auto piece = clipToSlab(a, b, c, z0, z1);
    if (piece.empty()) continue;
    for (const auto& p : piece) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    pieces.push_back(std::move(piece));
  }
  if (bad) out.warnings.push_back("amcl: skipped " + std::to_string(bad) + " triangles of storey '" + storey.name + "' with bad vertices");
  for (const auto& room : storey.rooms)
    for (const auto& p : room.footprint)
      if (p.allFinite()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if (!(lo.x() <= hi.x())) lo = hi = Eigen::Vector2d::Zero();  // nothing at all: a token map
  const double margin = config.likelihood_max_dist_m + config.map_resolution_m;
  lo -= Eigen::Vector2d::Constant(margin), hi += Eigen::Vector2d::Constant(margin);
  double resolution = config.map_resolution_m;
  const double cells = (hi - lo).prod() / (resolution * resolution);
  if (cells > kMaxCells) {
    resolution *= std::sqrt(cells / kMaxCells);
    std::ostringstream w;
    w << "amcl: storey '" << storey.name << "' spans " << (hi - lo).x() << " x " << (hi - lo).y() << " m: map cells of " << resolution
      << " m instead of " << config.map_resolution_m << " m";
    out.warnings.push_back(w.str());
  }
  out.grid = Grid(lo, hi, resolution);
  for (const auto& piece : pieces) out.grid.markConvex(piece);
  return out;
}

}  // namespace bimloc::peers::amcl
