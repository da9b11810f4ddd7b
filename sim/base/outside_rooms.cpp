#include "sim/base/outside_rooms.hpp"

#include "sim/base/free_space.hpp"
#include "sim/base/room_lookup.hpp"
#include "sim/common/seeded_random.hpp"
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
// Spots where the body fits whose way into the rooms is searched before giving up on a kind
// of place (each is a path search).
constexpr int kReachChecks = 8;  // per kind of place
constexpr std::size_t kNearestRooms = 3;

double distanceToWalls(const bim::Storey& storey, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& w : storey.walls)
    best = std::min(best, bim::distanceToSegment(p, w.start.head<2>(), w.end.head<2>()) - 0.5 * w.thickness_m);
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
  if (storey.walls.empty() || storey.rooms.empty()) return std::nullopt;
  Eigen::Vector2d lo = storey.walls.front().start.head<2>(), hi = lo;
  for (const auto& w : storey.walls)
    for (const Eigen::Vector3d& q : {w.start, w.end}) lo = lo.cwiseMin(q.head<2>()), hi = hi.cwiseMax(q.head<2>());
  const Eigen::Vector2d inner_lo = lo, inner_hi = hi;
  lo.array() -= kOutsideReach_m, hi.array() += kOutsideReach_m;
  // The start must be a place the robot can be: one it can walk from into a room (not the air
  // beside an upper storey, nor a shaft closed on every side), checked as the planner will:
  // the body at its height above the floor under the spot, a path to the nearest room.
  const auto reachable = [&](FreeSpace& space, const Eigen::Vector2d& q) {
    // The nearest rooms by centre: the one behind a doorway may be closed, the next one not.
    std::vector<const bim::Room*> rooms;
    for (const auto& r : storey.rooms) rooms.push_back(&r);
    const std::size_t tried = std::min<std::size_t>(kNearestRooms, rooms.size());
    std::partial_sort(rooms.begin(), rooms.begin() + static_cast<std::ptrdiff_t>(tried), rooms.end(),
                      [&](const bim::Room* a, const bim::Room* b) { return (a->centre - q).norm() < (b->centre - q).norm(); });
    for (std::size_t k = 0; k < tried; ++k) {
      const auto goal = space.freeSpotNear(rooms[k]->centre, &rooms[k]->footprint, kOutsideReach_m);
      if (goal && !space.path(q, *goal).empty()) return true;
    }
    return false;
  };
  // Uniform draws land almost always in front of the building: a doorway or a hall inside it
  // is a sliver of the area. So the seed picks the kind of place first: just off a room's edge
  // (doorways), inside the building's outline, or anywhere within reach of the walls.
  const int kind = static_cast<int>(seed % 3);
  std::vector<Eigen::Vector2d> points;
  for (const auto& r : storey.rooms) points.insert(points.end(), r.footprint.begin(), r.footprint.end());
  const bim::Polygon2 hull = bim::convexHull(points);
  SeededRandom random(seed, RandomStream::Start);
  const auto offEdge = [&]() {
    const bim::Room& r = storey.rooms[std::min(storey.rooms.size() - 1, static_cast<std::size_t>(random.uniform() * storey.rooms.size()))];
    const std::size_t n = r.footprint.size();
    const std::size_t e = std::min(n - 1, static_cast<std::size_t>(random.uniform() * n));
    const Eigen::Vector2d a = r.footprint[e], b = r.footprint[(e + 1) % n];
    const Eigen::Vector2d along = b - a;
    const Eigen::Vector2d out = along.norm() > 0 ? Eigen::Vector2d(along.y(), -along.x()).normalized() : Eigen::Vector2d::Zero();
    const double t = random.uniform(), depth = random.uniform(0.05, kDoorway_m);
    return Eigen::Vector2d(a + t * along + depth * out);  // footprints are counter-clockwise: out is to the right
  };
  // The seed's kind first, then the others: a plan may have no such place (no hall without a
  // space; no way in from outside an upper storey).
  for (int k = 0; k < 3; ++k) {
    const int now = (kind + k) % 3;
    int checked = 0;
    for (int draw = 0; draw < kDraws && checked < kReachChecks; ++draw) {
      Eigen::Vector2d q;
      if (now == 1) q = offEdge();
      else if (now == 2) q = {random.uniform(inner_lo.x(), inner_hi.x()), random.uniform(inner_lo.y(), inner_hi.y())};
      else q = {random.uniform(lo.x(), hi.x()), random.uniform(lo.y(), hi.y())};
      if (now == 2 && (hull.size() < 3 || !bim::pointInPolygon(hull, q))) continue;
      if (roomAt(storey, q) || distanceToWalls(storey, q) > kOutsideReach_m) continue;
      FreeSpace space(world, index, radius_m, bodyCentreZ(world, index, q, body_height_m));
      if (!space.spotFree(q, FreeSpace::kMargin_m)) continue;
      ++checked;
      if (reachable(space, q)) return q;
    }
  }
  return std::nullopt;
}

}  // namespace bimloc::sim
