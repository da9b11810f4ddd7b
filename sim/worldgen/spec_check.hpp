// Self-consistency of a WorldSpec. The spec is the extraction tests' ground truth, so the
// writer refuses one whose rooms are not exactly bounded by the faces of their walls, whose
// doors do not fit their walls, or whose heights do not stack.
#pragma once

#include "sim/worldgen/world_spec.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace bimloc::worldgen {
namespace spec_check_detail {

constexpr double kTol_m = 1e-6;

inline double signedArea(const std::vector<Eigen::Vector2d>& polygon) {
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return twice / 2;
}

inline bool plainAscii(const std::string& text) {
  for (char c : text) {
    if (c < 0x20 || c > 0x7e) return false;
  }
  return true;
}

// Does the segment a-b lie on one of the two faces of `wall`, within its length?
inline bool onWallFace(const WallSpec& wall, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d dir = (wall.end - wall.start).normalized();
  const Eigen::Vector2d left(-dir.y(), dir.x());
  const double length = (wall.end - wall.start).norm();
  for (double side : {1.0, -1.0}) {
    bool on = true;
    for (const Eigen::Vector2d* p : {&a, &b}) {
      const Eigen::Vector2d q = *p - wall.start;
      const double along = q.dot(dir);
      on = on && std::abs(q.dot(left) - side * wall.thickness_m / 2) < kTol_m &&
           along > -kTol_m && along < length + kTol_m;
    }
    if (on) return true;
  }
  return false;
}

[[noreturn]] inline void fail(const std::string& where, const std::string& what) {
  throw std::invalid_argument("world spec " + where + ": " + what);
}

// Stairs climb exactly to the next storey; voids only in slabs above the ground floor.
inline void checkStairs(const WorldSpec& spec, std::size_t s) {
  const StoreySpec& storey = spec.storeys[s];
  const std::string at = "'" + spec.name + "' storey '" + storey.name + "'";
  if (!storey.stairs.empty() && s + 1 >= spec.storeys.size()) fail(at, "a stair goes up from the top storey");
  for (const StairSpec& stair : storey.stairs) {
    const std::string st = at + " stair '" + stair.name + "'";
    if (stair.name.empty() || !plainAscii(stair.name) || stair.flights.empty()) fail(st, "needs a plain ASCII name and flights");
    double rise = 0.0;
    for (const StairFlightSpec& f : stair.flights) {
      if (f.name.empty() || !plainAscii(f.name) || f.risers < 2 || !(f.riser_m > 0) || !(f.going_m > 0) ||
          !(f.width_m > 0) || std::abs(f.direction.norm() - 1) > kTol_m || std::abs(f.z_m - rise) > kTol_m) {
        fail(st, "flight '" + f.name + "': needs a name, 2+ risers, positive sizes, a unit direction, and to start "
                 "where the one before ended");
      }
      rise += f.rise_m();
    }
    if (std::abs(rise - storey.height_m) > kTol_m) fail(st, "does not climb the storey height");
    for (const LandingSpec& l : stair.landings) {
      if (l.outline.size() < 3 || !(signedArea(l.outline) > 0) || !(l.thickness_m > 0) || !plainAscii(l.name))
        fail(st, "landing '" + l.name + "': needs a counter-clockwise outline and a thickness");
    }
  }
  if (!storey.floor_openings.empty() && s == 0) fail(at, "a void in the ground floor's slab");
  for (const auto& outline : storey.floor_openings)
    if (outline.size() < 3 || !(signedArea(outline) > 0)) fail(at, "a floor void must be a counter-clockwise polygon");
}

}  // namespace spec_check_detail

// Throws std::invalid_argument naming the world, storey and element of the first problem.
inline void checkWorldSpec(const WorldSpec& spec) {
  using namespace spec_check_detail;
  const std::string world = "'" + spec.name + "'";
  if (spec.name.empty() || !plainAscii(spec.name) || !plainAscii(spec.description)) {
    fail(world, "name must be non-empty plain ASCII");
  }
  if (spec.storeys.empty()) fail(world, "has no storey");
  if (!(spec.roof_thickness_m > 0)) fail(world, "roof thickness must be positive");
  std::set<std::string> wall_names, room_names;
  for (std::size_t s = 0; s < spec.storeys.size(); ++s) {
    const StoreySpec& storey = spec.storeys[s];
    const std::string at = world + " storey '" + storey.name + "'";
    if (storey.name.empty() || !plainAscii(storey.name)) fail(at, "bad name");
    if (!(storey.slab_thickness_m > 0) || !(clearHeight(spec, s) > 0)) {
      fail(at, "slab thickness and clear height must be positive");
    }
    if (s > 0 && std::abs(spec.storeys[s - 1].elevation_m + spec.storeys[s - 1].height_m -
                          storey.elevation_m) > kTol_m) {
      fail(at, "elevation is not the storey below's elevation + height");
    }
    if (storey.outline.size() < 3 || !(signedArea(storey.outline) > 0)) {
      fail(at, "outline must be a counter-clockwise polygon");
    }
    for (const WallSpec& wall : storey.walls) {
      const std::string w = at + " wall '" + wall.name + "'";
      if (wall.name.empty() || !plainAscii(wall.name) || !wall_names.insert(wall.name).second) {
        fail(w, "name must be unique plain ASCII");
      }
      if (!((wall.end - wall.start).norm() > kTol_m) || !(wall.thickness_m > 0) ||
          !(wall.height_m > 0) || wall.height_m > clearHeight(spec, s) + kTol_m) {
        fail(w, "needs positive length and thickness, height up to the ceiling at most");
      }
    }
    const int wall_count = static_cast<int>(storey.walls.size());
    for (std::size_t i = 0; i < storey.doors.size(); ++i) {
      const DoorSpec& door = storey.doors[i];
      const std::string d = at + " door " + std::to_string(i);
      if (door.wall < 0 || door.wall >= wall_count) fail(d, "wall index out of range");
      const WallSpec& wall = storey.walls[door.wall];
      const double length = (wall.end - wall.start).norm();
      if (!(door.width_m > 0) || !(door.height_m > 0) || door.height_m >= wall.height_m ||
          door.offset_m - door.width_m / 2 < -kTol_m ||
          door.offset_m + door.width_m / 2 > length + kTol_m) {
        fail(d, "does not fit in wall '" + wall.name + "'");
      }
    }
    for (const RoomSpec& room : storey.rooms) {
      const std::string r = at + " room '" + room.name + "'";
      if (room.name.empty() || !plainAscii(room.name) || !plainAscii(room.long_name) ||
          !room_names.insert(room.name).second) {
        fail(r, "name must be unique plain ASCII");
      }
      if (room.footprint.size() < 3 || !(signedArea(room.footprint) > 0)) {
        fail(r, "footprint must be a counter-clockwise polygon");
      }
      std::vector<bool> used(room.walls.size(), false);
      for (std::size_t e = 0; e < room.footprint.size(); ++e) {
        const Eigen::Vector2d& a = room.footprint[e];
        const Eigen::Vector2d& b = room.footprint[(e + 1) % room.footprint.size()];
        bool bounded = false;
        for (std::size_t k = 0; k < room.walls.size(); ++k) {
          if (room.walls[k] < 0 || room.walls[k] >= wall_count) fail(r, "wall index out of range");
          if (onWallFace(storey.walls[room.walls[k]], a, b)) bounded = used[k] = true;
        }
        const bool open = std::find(room.open_edges.begin(), room.open_edges.end(), static_cast<int>(e)) != room.open_edges.end();
        if (!bounded && !open) fail(r, "footprint edge " + std::to_string(e) + " is on no face of its walls");
      }
      for (std::size_t k = 0; k < room.walls.size(); ++k) {
        if (!used[k]) fail(r, "wall '" + storey.walls[room.walls[k]].name + "' bounds no edge");
      }
    }
    checkStairs(spec, s);
  }
}

}  // namespace bimloc::worldgen
