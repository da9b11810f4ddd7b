#include "room_footprint.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::bim::detail {
namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

void douglasPeucker(const Polygon2& p, std::size_t first, std::size_t last, double tol, std::vector<bool>& keep) {
  const std::size_t n = p.size();
  double worst = -1.0;
  std::size_t at = first;
  for (std::size_t k = (first + 1) % n; k != last; k = (k + 1) % n) {
    const double d = distanceToSegment(p[k], p[first], p[last]);
    if (d > worst) worst = d, at = k;
  }
  if (worst <= tol) return;
  keep[at] = true;
  douglasPeucker(p, first, at, tol, keep);
  douglasPeucker(p, at, last, tol, keep);
}

// A footprint edge's line: through `point`, along the unit `dir`.
struct Line {
  Eigen::Vector2d point, dir;
  Eigen::Vector2d project(const Eigen::Vector2d& p) const { return point + dir * dir.dot(p - point); }
};

// The face the edge a->b (room on its left) runs along, or nullptr.
const WallFace* faceAlong(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const std::vector<WallFace>& faces,
                          const RoomInferenceConfig& config) {
  const double length = (b - a).norm();
  const Eigen::Vector2d dir = (b - a) / length, inward(-dir.y(), dir.x());
  const WallFace* best = nullptr;
  double best_overlap = 0.0, best_distance = 0.0;
  for (const auto& face : faces) {
    const Eigen::Vector2d n = face.plane.n.head<2>();
    if (n.norm() < 0.5 || n.normalized().dot(inward) < std::cos(config.snap_angle_deg * M_PI / 180.0)) continue;
    const double da = std::abs(face.plane.n.head<2>().dot(a) + face.plane.d);
    const double db = std::abs(face.plane.n.head<2>().dot(b) + face.plane.d);
    if (da > config.snap_distance_m || db > config.snap_distance_m) continue;
    const double s0 = dir.dot(face.start.head<2>() - a), s1 = dir.dot(face.end.head<2>() - a);
    const double overlap = std::min(length, std::max(s0, s1)) - std::max(0.0, std::min(s0, s1));
    // A face along a good part of the edge; a short edge must lie mostly along it.
    if (overlap < std::min(0.5 * length, 0.3)) continue;
    const double distance = da + db;
    if (!best || overlap > best_overlap + 1e-6 || (overlap > best_overlap - 1e-6 && distance < best_distance))
      best = &face, best_overlap = overlap, best_distance = distance;
  }
  return best;
}

bool segmentsMeet(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, const Eigen::Vector2d& d) {
  constexpr double eps = 1e-9;
  const double d1 = cross2(b - a, c - a), d2 = cross2(b - a, d - a), d3 = cross2(d - c, a - c), d4 = cross2(d - c, b - c);
  if (((d1 > eps && d2 < -eps) || (d1 < -eps && d2 > eps)) && ((d3 > eps && d4 < -eps) || (d3 < -eps && d4 > eps)))
    return true;
  const auto on = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
    return distanceToSegment(r, p, q) < 1e-7;
  };
  return on(a, b, c) || on(a, b, d) || on(c, d, a) || on(c, d, b);
}

}  // namespace

Polygon2 simplifyClosed(const Polygon2& polygon, double tolerance_m) {
  const std::size_t n = polygon.size();
  if (n < 4) return polygon;
  std::size_t first = 0;
  for (std::size_t k = 1; k < n; ++k)
    if (polygon[k].y() < polygon[first].y() || (polygon[k].y() == polygon[first].y() && polygon[k].x() < polygon[first].x()))
      first = k;
  std::size_t far = first;
  for (std::size_t k = 0; k < n; ++k)
    if ((polygon[k] - polygon[first]).norm() > (polygon[far] - polygon[first]).norm()) far = k;
  std::vector<bool> keep(n, false);
  keep[first] = keep[far] = true;
  douglasPeucker(polygon, first, far, tolerance_m, keep);
  douglasPeucker(polygon, far, first, tolerance_m, keep);
  Polygon2 out;
  for (std::size_t k = 0; k < n; ++k)
    if (keep[(first + k) % n]) out.push_back(polygon[(first + k) % n]);
  return out;
}

Polygon2 snapToFaces(const Polygon2& polygon, const std::vector<WallFace>& faces, const RoomInferenceConfig& config) {
  const std::size_t n = polygon.size();
  if (n < 3) return polygon;
  std::vector<Line> lines(n);
  std::vector<bool> snapped(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = polygon[i], b = polygon[(i + 1) % n];
    const Eigen::Vector2d dir = (b - a).normalized();
    lines[i] = {a, dir};
    if (const WallFace* face = faceAlong(a, b, faces, config)) {
      const Eigen::Vector2d normal = face->plane.n.head<2>().normalized();
      Eigen::Vector2d along(normal.y(), -normal.x());  // the room is on the left of the edge
      if (along.dot(dir) < 0) along = -along;
      lines[i] = {a - (normal.dot(a) + face->plane.d) * normal, along};
      snapped[i] = true;
    }
  }
  const double sin_min = std::sin(20.0 * M_PI / 180.0);
  // Short runs of unsnapped edges between two snapped edges that meet are dropped: the raster
  // rounds a room's corners (the closing fills the walls' inner corners), the faces don't.
  std::vector<bool> keep(n, true);
  const double short_run = 2.0 * config.snap_distance_m + 2.0 * config.cell_m;
  for (std::size_t i = 0; i < n; ++i) {
    if (!snapped[i] || snapped[(i + 1) % n]) continue;
    std::size_t j = (i + 1) % n;
    double length = 0.0;
    while (!snapped[j] && j != i) length += (polygon[(j + 1) % n] - polygon[j]).norm(), j = (j + 1) % n;
    if (j == i || length > short_run || std::abs(cross2(lines[i].dir, lines[j].dir)) < sin_min) continue;
    for (std::size_t k = (i + 1) % n; k != j; k = (k + 1) % n) keep[k] = false;
  }
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < n; ++i)
    if (keep[i]) kept.push_back(i);
  if (kept.size() < 3) return polygon;

  Polygon2 result;
  const std::size_t m = kept.size();
  for (std::size_t k = 0; k < m; ++k) {
    const Line& before = lines[kept[(k + m - 1) % m]];
    const Line& after = lines[kept[k]];
    const Eigen::Vector2d v = polygon[kept[k]];
    const double s = cross2(before.dir, after.dir);
    if (std::abs(s) > sin_min) {
      const Eigen::Vector2d x = before.point + cross2(after.point - before.point, after.dir) / s * before.dir;
      if ((x - v).norm() <= short_run + config.snap_distance_m) {
        result.push_back(x);
        continue;
      }
    }
    // Nearly parallel lines (a step between two faces), or a far intersection: join them.
    result.push_back(before.project(v));
    if ((after.project(v) - before.project(v)).norm() > 1e-4) result.push_back(after.project(v));
  }
  result = simplifyPolygon(result, 1e-4);
  const double area = std::abs(signedArea(polygon));
  if (result.size() < 3 || !isSimplePolygon(result) || std::abs(signedArea(result) - area) > 0.25 * area)
    return polygon;
  return result;
}

bool isSimplePolygon(const Polygon2& p) {
  const std::size_t n = p.size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i) {  // no spike: an edge folding back onto the one before
    const Eigen::Vector2d u = p[i] - p[(i + n - 1) % n], w = p[(i + 1) % n] - p[i];
    if (std::abs(cross2(u, w)) < 1e-9 * u.norm() * w.norm() + 1e-12 && u.dot(w) < 0) return false;
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (j == i + 1 || (i == 0 && j == n - 1)) continue;  // adjacent edges share a vertex
      if (segmentsMeet(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n])) return false;
    }
  return true;
}

}  // namespace bimloc::bim::detail
