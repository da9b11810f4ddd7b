#include "buried_faces.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <cmath>

namespace bimloc::bim {
namespace {

// Just in front of a face: beyond the rounding of the plan's coordinates (mm), well inside
// any wall's thickness (>= 5 cm).
constexpr double kFrontM = 0.02;
constexpr int kSamples = 20;

// The wall's body across the floor: the quad between its two faces.
bim::Polygon2 body(const bim::Wall& w) {
  return {w.faces[0].start.head<2>(), w.faces[0].end.head<2>(), w.faces[1].start.head<2>(), w.faces[1].end.head<2>()};
}

// Whether the two walls share heights: the covering wall must stand where the face is.
bool overlapInHeight(const bim::Wall& a, const bim::Wall& b) {
  if (a.height_m <= 0.0 || b.height_m <= 0.0) return true;  // unknown: assume they do
  const double lo = std::max(a.start.z(), b.start.z()), hi = std::min(a.start.z() + a.height_m, b.start.z() + b.height_m);
  return hi - lo > 0.5 * std::min(a.height_m, b.height_m);
}

}  // namespace

std::vector<bool> buriedFaces(const bim::Storey& storey) {
  const std::size_t n = storey.walls.size();
  std::vector<bool> buried(2 * n, false);
  std::vector<bim::Polygon2> bodies;
  bodies.reserve(n);
  for (const auto& w : storey.walls) bodies.push_back(body(w));
  for (std::size_t w = 0; w < n; ++w)
    for (int f = 0; f < 2; ++f) {
      const bim::WallFace& face = storey.walls[w].faces[f];
      const Eigen::Vector2d a = face.start.head<2>(), b = face.end.head<2>();
      const Eigen::Vector2d front = kFrontM * face.plane.n.head<2>().normalized();
      if (!a.allFinite() || !b.allFinite() || !front.allFinite() || (b - a).norm() < 1e-6) continue;
      int covered = 0;
      for (int k = 0; k < kSamples; ++k) {
        const Eigen::Vector2d p = a + (k + 0.5) / kSamples * (b - a) + front;
        for (std::size_t o = 0; o < n; ++o)
          if (o != w && overlapInHeight(storey.walls[w], storey.walls[o]) && bim::pointInPolygon(bodies[o], p)) {
            ++covered;
            break;
          }
      }
      buried[2 * w + static_cast<std::size_t>(f)] = covered >= kBuriedShare * kSamples;
    }
  return buried;
}

}  // namespace bimloc::bim
