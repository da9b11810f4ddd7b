// Helper for writing the project's worlds by hand: walls by name and axis line, rooms and
// doors referring to walls by name. Only the world definitions (worlds.cpp) use it.
#pragma once

#include "sim/worldgen/world_spec.hpp"

#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace bimloc::worldgen {

class StoreyBuilder {
 public:
  // Every wall of the storey gets `wall_height_m` (walls run from floor to ceiling).
  StoreyBuilder(std::string name, double elevation_m, double height_m, double slab_thickness_m,
                double wall_height_m)
      : wall_height_m_(wall_height_m) {
    storey_.name = std::move(name);
    storey_.elevation_m = elevation_m;
    storey_.height_m = height_m;
    storey_.slab_thickness_m = slab_thickness_m;
  }

  void outline(std::vector<Eigen::Vector2d> polygon) { storey_.outline = std::move(polygon); }

  void wall(const std::string& name, const Eigen::Vector2d& start, const Eigen::Vector2d& end,
            double thickness_m, bool exterior) {
    storey_.walls.push_back({name, start, end, thickness_m, wall_height_m_, exterior});
  }
  // A wall along x with its axis at y, and one along y with its axis at x.
  void wallX(const std::string& name, double y, double x0, double x1, double t, bool ext) {
    wall(name, {x0, y}, {x1, y}, t, ext);
  }
  void wallY(const std::string& name, double x, double y0, double y1, double t, bool ext) {
    wall(name, {x, y0}, {x, y1}, t, ext);
  }

  // A door centred at `at` (the x of a wall along x, the y of a wall along y).
  void door(const std::string& wall_name, double at, double width_m, double height_m) {
    const int index = wallIndex(wall_name);
    const WallSpec& w = storey_.walls[index];
    const Eigen::Vector2d dir = (w.end - w.start).normalized();
    const bool along_x = std::abs(dir.x()) > 1 - 1e-12;
    if (!along_x && std::abs(dir.y()) < 1 - 1e-12) {
      throw std::logic_error("door in wall " + wall_name + ": wall is not axis-aligned");
    }
    const double offset = along_x ? (at - w.start.x()) * dir.x() : (at - w.start.y()) * dir.y();
    storey_.doors.push_back({index, offset, width_m, height_m});
  }

  void room(const std::string& name, const std::string& long_name,
            std::vector<Eigen::Vector2d> footprint, std::initializer_list<const char*> walls) {
    RoomSpec r{name, long_name, std::move(footprint), {}, {}};
    for (const char* w : walls) r.walls.push_back(wallIndex(w));
    storey_.rooms.push_back(std::move(r));
  }
  // The axis-aligned rectangle [x0, x1] × [y0, y1].
  void room(const std::string& name, const std::string& long_name, double x0, double y0,
            double x1, double y1, std::initializer_list<const char*> walls) {
    room(name, long_name, {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, walls);
  }

  const StoreySpec& storey() const { return storey_; }

 private:
  int wallIndex(const std::string& name) const {
    for (std::size_t i = 0; i < storey_.walls.size(); ++i) {
      if (storey_.walls[i].name == name) return static_cast<int>(i);
    }
    throw std::logic_error("storey " + storey_.name + " has no wall " + name);
  }

  StoreySpec storey_;
  double wall_height_m_;
};

// The box outline [x0, x1] × [y0, y1], counter-clockwise.
inline std::vector<Eigen::Vector2d> boxOutline(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

}  // namespace bimloc::worldgen
