#include "sim/render/triangulate.hpp"

#include <bimloc/bim/geometry2d.hpp>

namespace bimloc::sim::render {

namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

// p strictly inside or on the edge of the counter-clockwise triangle abc.
bool inTriangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                const Eigen::Vector2d& c) {
  return cross(a, b, p) >= 0 && cross(b, c, p) >= 0 && cross(c, a, p) >= 0;
}

}  // namespace

std::vector<std::array<int, 3>> triangulate(const std::vector<Eigen::Vector2d>& polygon) {
  std::vector<std::array<int, 3>> out;
  std::vector<int> left;
  for (int i = 0; i < static_cast<int>(polygon.size()); ++i) left.push_back(i);
  if (left.size() < 3) return out;
  const double orientation = bim::signedArea(polygon) >= 0 ? 1.0 : -1.0;
  auto corner = [&](int k) { return orientation * cross(polygon[left[(k + left.size() - 1) % left.size()]],
                                                        polygon[left[k]], polygon[left[(k + 1) % left.size()]]); };
  while (left.size() > 3) {
    bool clipped = false;
    for (std::size_t k = 0; k < left.size() && !clipped; ++k) {
      if (corner(static_cast<int>(k)) <= 0) continue;  // reflex or flat: not an ear
      const int ia = left[(k + left.size() - 1) % left.size()], ib = left[k], ic = left[(k + 1) % left.size()];
      Eigen::Vector2d a = polygon[ia], b = polygon[ib], c = polygon[ic];
      if (orientation < 0) std::swap(a, c);
      bool empty = true;
      for (const int j : left)
        if (j != ia && j != ib && j != ic && inTriangle(polygon[j], a, b, c)) {
          empty = false;
          break;
        }
      if (!empty) continue;
      out.push_back({ia, ib, ic});
      left.erase(left.begin() + static_cast<std::ptrdiff_t>(k));
      clipped = true;
    }
    if (!clipped) break;  // not a simple polygon: fan the rest below
  }
  for (std::size_t k = 1; k + 1 < left.size(); ++k) out.push_back({left[0], left[k], left[k + 1]});
  return out;
}

}  // namespace bimloc::sim::render
