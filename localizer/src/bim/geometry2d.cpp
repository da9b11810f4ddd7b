#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <cmath>

namespace bimloc::bim {
namespace {

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

}  // namespace

double signedArea(const Polygon2& polygon) {
  double twice = 0.0;
  for (std::size_t i = 0, n = polygon.size(); i < n; ++i) {
    const auto& a = polygon[i];
    const auto& b = polygon[(i + 1) % n];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

Eigen::Vector2d areaCentroid(const Polygon2& polygon) {
  if (polygon.empty()) return Eigen::Vector2d::Zero();
  // Relative to the first vertex, for precision far from the origin.
  const Eigen::Vector2d o = polygon.front();
  double twice_area = 0.0;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (std::size_t i = 0, n = polygon.size(); i < n; ++i) {
    const Eigen::Vector2d a = polygon[i] - o, b = polygon[(i + 1) % n] - o;
    const double w = a.x() * b.y() - b.x() * a.y();
    twice_area += w;
    sum += w * (a + b);
  }
  if (std::abs(twice_area) < 1e-12) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const auto& p : polygon) mean += p;
    return mean / static_cast<double>(polygon.size());
  }
  return o + sum / (3.0 * twice_area);
}

bool pointInPolygon(const Polygon2& polygon, const Eigen::Vector2d& p) {
  bool inside = false;
  for (std::size_t i = 0, n = polygon.size(), j = n - 1; i < n; j = i++) {
    const auto& a = polygon[i];
    const auto& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

std::vector<int> wholeCellAnswers(const std::vector<const Polygon2*>& footprints, const std::vector<std::vector<int>>& candidates,
                                  const Eigen::Vector2d& origin, double cell_m, int nx, int ny) {
  const std::size_t cells = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  const double sure_m = 0.75 * cell_m;
  const auto centre = [&](int ix, int iy) { return Eigen::Vector2d(origin + cell_m * Eigen::Vector2d(ix + 0.5, iy + 0.5)); };
  const auto cellOf = [&](double v, double o, int n) {
    const double c = std::floor((v - o) / cell_m);
    return static_cast<int>(std::clamp(c, 0.0, static_cast<double>(n - 1)));
  };
  std::vector<char> near(cells, 0);
  for (const Polygon2* f : footprints)
    for (std::size_t i = 0, n = f->size(), j = n - 1; i < n; j = i++) {
      const Eigen::Vector2d& a = (*f)[j];
      const Eigen::Vector2d& b = (*f)[i];
      const bool finite = a.allFinite() && b.allFinite();
      const int x0 = finite ? cellOf(std::min(a.x(), b.x()) - sure_m, origin.x(), nx) : 0;
      const int x1 = finite ? cellOf(std::max(a.x(), b.x()) + sure_m, origin.x(), nx) : nx - 1;
      const int y0 = finite ? cellOf(std::min(a.y(), b.y()) - sure_m, origin.y(), ny) : 0;
      const int y1 = finite ? cellOf(std::max(a.y(), b.y()) + sure_m, origin.y(), ny) : ny - 1;
      for (int iy = y0; iy <= y1; ++iy)
        for (int ix = x0; ix <= x1; ++ix)
          if (!finite || !(distanceToSegment(centre(ix, iy), a, b) > sure_m)) near[static_cast<std::size_t>(iy) * nx + ix] = 1;
    }
  std::vector<int> sure(cells, kCellUnsure);
  for (int iy = 0; iy < ny; ++iy)
    for (int ix = 0; ix < nx; ++ix) {
      const std::size_t k = static_cast<std::size_t>(iy) * nx + ix;
      if (near[k]) continue;
      sure[k] = -1;
      for (const int r : candidates[k])
        if (pointInPolygon(*footprints[static_cast<std::size_t>(r)], centre(ix, iy))) {
          sure[k] = r;
          break;
        }
    }
  return sure;
}

bool segmentsCross(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
  const double d1 = cross(q - p, a - p), d2 = cross(q - p, b - p), d3 = cross(b - a, p - a), d4 = cross(b - a, q - a);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

Polygon2 convexHull(std::vector<Eigen::Vector2d> points) {
  // Andrew's monotone chain.
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (points.size() < 3) return points;
  Polygon2 hull(2 * points.size());
  std::size_t k = 0;
  for (const auto& p : points) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= 1e-12) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 1e-12) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

Rectangle2 minAreaRectangle(const Polygon2& hull) {
  Rectangle2 best;
  double best_area = std::numeric_limits<double>::infinity();
  // The minimum-area rectangle has a side collinear with a hull edge.
  for (std::size_t i = 0, n = hull.size(); i < n; ++i) {
    Eigen::Vector2d u = hull[(i + 1) % n] - hull[i];
    if (u.norm() < 1e-9) continue;
    u.normalize();
    const Eigen::Vector2d v(-u.y(), u.x());
    double umin = 1e300, umax = -1e300, vmin = 1e300, vmax = -1e300;
    for (const auto& p : hull) {
      umin = std::min(umin, p.dot(u)), umax = std::max(umax, p.dot(u));
      vmin = std::min(vmin, p.dot(v)), vmax = std::max(vmax, p.dot(v));
    }
    const double area = (umax - umin) * (vmax - vmin);
    if (area < best_area - 1e-12) {
      best_area = area;
      const bool u_long = umax - umin >= vmax - vmin;
      best.axis = u_long ? u : v;
      best.length = u_long ? umax - umin : vmax - vmin;
      best.width = u_long ? vmax - vmin : umax - umin;
      best.centre = 0.5 * (umin + umax) * u + 0.5 * (vmin + vmax) * v;
    }
  }
  return best;
}

double polygonIoU(const Polygon2& a, const Polygon2& b, double resolution_m) {
  const double area_a = std::abs(signedArea(a)), area_b = std::abs(signedArea(b));
  if (a.size() < 3 || b.size() < 3 || area_a + area_b <= 0) return 0.0;
  Eigen::Vector2d lo_a = a.front(), hi_a = a.front(), lo_b = b.front(), hi_b = b.front();
  for (const auto& p : a) lo_a = lo_a.cwiseMin(p), hi_a = hi_a.cwiseMax(p);
  for (const auto& p : b) lo_b = lo_b.cwiseMin(p), hi_b = hi_b.cwiseMax(p);
  const Eigen::Vector2d lo = lo_a.cwiseMax(lo_b), hi = hi_a.cwiseMin(hi_b);
  if (lo.x() >= hi.x() || lo.y() >= hi.y()) return 0.0;
  std::size_t inside = 0;
  const long nx = std::lround(std::ceil((hi.x() - lo.x()) / resolution_m));
  const long ny = std::lround(std::ceil((hi.y() - lo.y()) / resolution_m));
  const double hx = (hi.x() - lo.x()) / double(nx), hy = (hi.y() - lo.y()) / double(ny);
  for (long j = 0; j < ny; ++j)
    for (long i = 0; i < nx; ++i) {
      const Eigen::Vector2d p(lo.x() + (double(i) + 0.5) * hx, lo.y() + (double(j) + 0.5) * hy);
      inside += pointInPolygon(a, p) && pointInPolygon(b, p);
    }
  // Sampling may overshoot by a fraction of a cell row; the intersection is never larger than either.
  const double intersection = std::min({double(inside) * hx * hy, area_a, area_b});
  return intersection / (area_a + area_b - intersection);
}

Polygon2 simplifyPolygon(const Polygon2& polygon, double tol_m) {
  Polygon2 out;
  for (const auto& p : polygon)
    if (out.empty() || (p - out.back()).norm() > tol_m) out.push_back(p);
  while (out.size() > 1 && (out.front() - out.back()).norm() <= tol_m) out.pop_back();
  // Remove vertices lying on the segment between their neighbours, until none is left.
  bool changed = true;
  while (changed && out.size() > 3) {
    changed = false;
    for (std::size_t i = 0; i < out.size() && out.size() > 3; ++i) {
      const auto& a = out[(i + out.size() - 1) % out.size()];
      const auto& b = out[(i + 1) % out.size()];
      const double len = (b - a).norm();
      if (len > 0 && std::abs(cross(a, b, out[i])) / len < tol_m && (out[i] - a).dot(b - a) > 0 &&
          (out[i] - b).dot(a - b) > 0) {
        out.erase(out.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
      }
    }
  }
  if (signedArea(out) < 0) std::reverse(out.begin(), out.end());
  return out;
}

}  // namespace bimloc::bim
