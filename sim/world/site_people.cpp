#include "sim/world/site_people.hpp"

#include "sim/common/seeded_random.hpp"
#include "sim/world/world.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace bimloc::sim {
namespace {

constexpr int kDrawsPerPerson = 100;  // per person; a room too small is found out quickly
constexpr double kChestHeight_m = 1.0;  // legs are swept at this height above the floor:
                                        // above skirting and door sills, through clutter up to 1.5 m
constexpr double kMinLeg_m = 1.0;

double pathLength(const std::vector<Eigen::Vector2d>& w) {
  double l = 0.0;
  for (std::size_t i = 1; i < w.size(); ++i) l += (w[i] - w[i - 1]).norm();
  return l;
}

std::string point(const Eigen::Vector2d& p) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "(%.2f, %.2f)", p.x(), p.y());
  return buf;
}

// The floor under p: the first surface below chest height, else the storey's elevation.
double floorAt(const World& world, std::size_t storey, const Eigen::Vector2d& p) {
  const double elevation = world.building().storeys[storey].elevation_m;
  const bim::Room* room = world.building().storeys[storey].roomAt(p);
  const double base = room ? room->floor_z : elevation;
  double z = base;
  return world.floorBelow(storey, Eigen::Vector3d(p.x(), p.y(), base + kChestHeight_m), 2.0 * kChestHeight_m, &z) ? z : base;
}

std::string legProblem(const World& world, std::size_t storey, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                       double floor_z, double radius_m) {
  const Eigen::Vector3d from(a.x(), a.y(), floor_z + kChestHeight_m), to(b.x(), b.y(), floor_z + kChestHeight_m);
  Eigen::Vector3d contact;
  if (!world.sphereClear(storey, from, radius_m, &contact))
    return point(a) + " is within " + std::to_string(radius_m).substr(0, 4) + " m of a wall at " + point(contact.head<2>());
  if (!world.sweepClear(storey, from, to, radius_m, &contact))
    return "the leg " + point(a) + " -> " + point(b) + " meets a wall at " + point(contact.head<2>());
  return "";
}

}  // namespace

Eigen::Vector2d personCentreAt(const PersonTruth& p, double t_s) {
  const auto& w = p.waypoints;
  const double length = pathLength(w);
  if (w.size() < 2 || length <= 0.0) return w.empty() ? Eigen::Vector2d::Zero() : w.front();
  double s = std::fmod(p.phase_m + p.speed_mps * t_s, 2.0 * length);
  if (s < 0.0) s += 2.0 * length;
  if (s > length) s = 2.0 * length - s;  // on the way back
  for (std::size_t i = 1; i < w.size(); ++i) {
    const double leg = (w[i] - w[i - 1]).norm();
    if (s <= leg || i + 1 == w.size()) return w[i - 1] + (leg > 0.0 ? std::min(1.0, s / leg) : 0.0) * (w[i] - w[i - 1]);
    s -= leg;
  }
  return w.back();
}

bool rayEntersCylinder(const Eigen::Vector3f& o, const Eigen::Vector3f& d, const Eigen::Vector2f& c, float r, float z0,
                       float z1, float t_min, float& t, Eigen::Vector3f& normal) {
  // Side: |o_xy + t d_xy - c|^2 = r^2, an interval [t_a, t_b] of t.
  const float px = o.x() - c.x(), py = o.y() - c.y();
  const float a = d.x() * d.x() + d.y() * d.y(), b = px * d.x() + py * d.y(), q = px * px + py * py - r * r;
  if (q <= 0.0f && o.z() >= z0 && o.z() <= z1) return false;  // starts inside
  float t_in = -std::numeric_limits<float>::infinity(), t_out = std::numeric_limits<float>::infinity();
  bool side = true;
  if (a > 0.0f) {
    const float disc = b * b - a * q;
    if (disc < 0.0f) return false;
    const float root = std::sqrt(disc);
    t_in = (-b - root) / a, t_out = (-b + root) / a;
  } else if (q > 0.0f) {
    return false;  // vertical ray beside the cylinder
  }
  // Caps: the slab z0 <= z <= z1.
  if (d.z() != 0.0f) {
    float s0 = (z0 - o.z()) / d.z(), s1 = (z1 - o.z()) / d.z();
    if (s0 > s1) std::swap(s0, s1);
    if (s0 > t_in) t_in = s0, side = false;
    t_out = std::min(t_out, s1);
  } else if (o.z() < z0 || o.z() > z1) {
    return false;
  }
  if (t_in > t_out || t_in < t_min) return false;
  t = t_in;
  if (side) {
    normal = Eigen::Vector3f(px + t * d.x(), py + t * d.y(), 0.0f) / r;
  } else {
    normal = Eigen::Vector3f(0.0f, 0.0f, d.z() > 0.0f ? -1.0f : 1.0f);
  }
  return true;
}

std::string personPathProblem(const World& world, std::size_t storey, const PersonPath& path, double radius_m) {
  for (std::size_t i = 1; i < path.waypoints.size(); ++i) {
    const double floor_z = floorAt(world, storey, path.waypoints[i - 1]);
    const std::string problem = legProblem(world, storey, path.waypoints[i - 1], path.waypoints[i], floor_z, radius_m);
    if (!problem.empty()) return problem;
  }
  return "";
}

void placePeople(const World& world, const SitePeople& config, std::uint64_t seed, SiteTruth& truth) {
  for (const PersonPath& path : config.paths) {
    const std::size_t storey = world.storeyIndex(path.storey.empty() ? "0" : path.storey);
    // The scenario's check holds a given path against the plan; on the site, a wall shifted
    // or a box placed onto it only earns a warning (a person is an occluder, not a body).
    const std::string problem = personPathProblem(world, storey, path, config.radius_m);
    if (!problem.empty()) truth.warnings.push_back("a given person's path on the site: " + problem);
    PersonTruth p;
    p.storey = storey, p.waypoints = path.waypoints, p.speed_mps = path.speed_mps;
    p.radius_m = config.radius_m, p.height_m = config.height_m, p.floor_z = floorAt(world, storey, path.waypoints.front());
    truth.people.push_back(p);
  }
  if (config.count_per_storey <= 0) return;
  const auto& storeys = world.building().storeys;
  for (std::size_t s = 0; s < storeys.size(); ++s) {
    SeededRandom random(seed ^ (0x9E0971Eull * (s + 1)), RandomStream::SitePeople);
    std::vector<const bim::Room*> rooms;
    double total = 0.0;
    for (const bim::Room& r : storeys[s].rooms)
      if (r.footprint.size() >= 3 && r.area_m2 >= 4.0) rooms.push_back(&r), total += r.area_m2;
    int made = 0;
    for (int k = 0; k < config.count_per_storey && !rooms.empty(); ++k) {
      for (int draw = 0; draw < kDrawsPerPerson; ++draw) {
        // Every draw takes the same numbers, so a rejection does not shift the ones after it.
        double r[11];
        for (double& v : r) v = random.uniform();
        double pick = r[0] * total;  // a room by area: more people walk the big rooms and halls
        std::size_t i = 0;
        for (; i + 1 < rooms.size() && pick > rooms[i]->area_m2; ++i) pick -= rooms[i]->area_m2;
        const bim::Room& room = *rooms[i];
        Eigen::Vector2d lo = room.footprint.front(), hi = lo;
        for (const auto& q : room.footprint) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
        const int points = 2 + static_cast<int>(r[1] * 3.0);  // 2..4
        PersonTruth p;
        p.storey = s, p.room = room.name, p.speed_mps = config.speed_mps, p.radius_m = config.radius_m;
        p.height_m = config.height_m;
        for (int j = 0; j < points; ++j)
          p.waypoints.emplace_back(lo.x() + r[2 + 2 * j] * (hi.x() - lo.x()), lo.y() + r[3 + 2 * j] * (hi.y() - lo.y()));
        bool ok = true;
        for (const auto& w : p.waypoints) ok = ok && bim::pointInPolygon(room.footprint, w);
        for (std::size_t j = 1; ok && j < p.waypoints.size(); ++j) ok = (p.waypoints[j] - p.waypoints[j - 1]).norm() >= kMinLeg_m;
        if (!ok) continue;
        p.floor_z = floorAt(world, s, p.waypoints.front());
        for (std::size_t j = 1; ok && j < p.waypoints.size(); ++j)
          ok = legProblem(world, s, p.waypoints[j - 1], p.waypoints[j], p.floor_z, p.radius_m).empty();
        if (!ok) continue;
        p.phase_m = r[10] * 2.0 * pathLength(p.waypoints);  // not all in step
        truth.people.push_back(p);
        ++made;
        break;
      }
    }
    if (made < config.count_per_storey && !storeys[s].walls.empty())
      truth.warnings.push_back("storey '" + storeys[s].name + "': " + std::to_string(config.count_per_storey - made) + " of " +
                               std::to_string(config.count_per_storey) + " people left out (no room with a clear walk)");
  }
}

}  // namespace bimloc::sim
