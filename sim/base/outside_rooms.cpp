#include "sim/base/outside_rooms.hpp"

#include "sim/base/free_space.hpp"
#include "sim/base/room_lookup.hpp"
#include "sim/base/seeded_random.hpp"
#include "sim/world/world.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <limits>

namespace bimloc::sim {
namespace {

// A doorway: within a wall's thickness of a room (as FreeSpace counts doorways indoors).
constexpr double kDoorway_m = 0.35;
// Spots drawn before giving up: the free space outside rooms can be a thin share of the box.
constexpr int kDraws = 4000;

double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

double distanceToWalls(const bim::Storey& storey, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& w : storey.walls)
    best = std::min(best, distanceToSegment(p, w.start.head<2>(), w.end.head<2>()) - 0.5 * w.thickness_m);
  return best;
}

}  // namespace

std::string outsideKind(const bim::Storey& storey, const Eigen::Vector2d& p) {
  if (roomAt(storey, p)) return "room";
  for (const auto& [dx, dy] : {std::pair{1.0, 0.0}, {-1.0, 0.0}, {0.0, 1.0}, {0.0, -1.0}})
    if (roomAt(storey, p + kDoorway_m * Eigen::Vector2d(dx, dy))) return "doorway";
  // The building's outline: the convex hull of its rooms and walls (a courtyard counts as in).
  std::vector<Eigen::Vector2d> points;
  for (const auto& r : storey.rooms) points.insert(points.end(), r.footprint.begin(), r.footprint.end());
  for (const auto& w : storey.walls) points.push_back(w.start.head<2>()), points.push_back(w.end.head<2>());
  const bim::Polygon2 hull = bim::convexHull(points);
  return hull.size() >= 3 && bim::pointInPolygon(hull, p) ? "no room" : "outside";
}

std::optional<Eigen::Vector2d> outsideRoomsSpot(const World& world, std::size_t index, double radius_m, double body_height_m,
                                                std::uint64_t seed) {
  const bim::Storey& storey = world.building().storeys.at(index);
  if (storey.walls.empty()) return std::nullopt;
  Eigen::Vector2d lo = storey.walls.front().start.head<2>(), hi = lo;
  for (const auto& w : storey.walls)
    for (const Eigen::Vector3d& q : {w.start, w.end}) lo = lo.cwiseMin(q.head<2>()), hi = hi.cwiseMax(q.head<2>());
  lo.array() -= kOutsideReach_m, hi.array() += kOutsideReach_m;
  const Eigen::Vector2d middle = 0.5 * (lo + hi);
  const FreeSpace space(world, index, radius_m, bodyCentreZ(world, index, middle, body_height_m));
  SeededRandom random(seed, RandomStream::Start);
  for (int draw = 0; draw < kDraws; ++draw) {
    const Eigen::Vector2d q(random.uniform(lo.x(), hi.x()), random.uniform(lo.y(), hi.y()));
    if (roomAt(storey, q) || distanceToWalls(storey, q) > kOutsideReach_m) continue;
    if (space.spotFree(q, FreeSpace::kMargin_m)) return q;
  }
  return std::nullopt;
}

}  // namespace bimloc::sim
