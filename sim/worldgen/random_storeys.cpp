#include "sim/worldgen/random_storeys.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bimloc::worldgen {
namespace {

constexpr double kStackTol_m = 1e-6;

double polygonArea(const std::vector<Eigen::Vector2d>& p) {
  double twice = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) twice += p[i].x() * p[(i + 1) % p.size()].y() - p[(i + 1) % p.size()].x() * p[i].y();
  return twice / 2;
}

// The one door of room `room`: its centre, or nullopt.
std::optional<Eigen::Vector2d> onlyDoorOf(const PlanGrid::Result& r, int room) {
  std::optional<Eigen::Vector2d> centre;
  for (std::size_t i = 0; i < r.storey.doors.size(); ++i) {
    if (r.door_rooms[i].first != room && r.door_rooms[i].second != room) continue;
    if (centre) return std::nullopt;
    const DoorSpec& d = r.storey.doors[i];
    const WallSpec& w = r.storey.walls[static_cast<std::size_t>(d.wall)];
    centre = w.start + (w.end - w.start).normalized() * d.offset_m;
  }
  return centre;
}

}  // namespace

std::optional<StairWell> stairWellOf(const PlanGrid::Result& r, int room) {
  const RoomSpec& spec = r.storey.rooms.at(static_cast<std::size_t>(room));
  Eigen::Vector2d lo = spec.footprint.front(), hi = lo;
  for (const auto& p : spec.footprint) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Eigen::Vector2d size = hi - lo;
  if (std::abs(polygonArea(spec.footprint) - size.x() * size.y()) > kStackTol_m) return std::nullopt;
  const auto door = onlyDoorOf(r, room);
  if (!door) return std::nullopt;
  // The side the door's centre is nearest to (it lies in a wall beyond that side).
  const double to_side[4] = {door->y() - lo.y(), hi.y() - door->y(), door->x() - lo.x(), hi.x() - door->x()};
  const int side = static_cast<int>(std::min_element(std::begin(to_side), std::end(to_side)) - std::begin(to_side));
  StairWell w;
  if (side < 2) {  // south or north: the flights run along y
    w.origin = side == 0 ? lo : Eigen::Vector2d(lo.x(), hi.y());
    w.inward = side == 0 ? Eigen::Vector2d::UnitY() : Eigen::Vector2d(-Eigen::Vector2d::UnitY());
    w.across = Eigen::Vector2d::UnitX();
    w.depth_m = size.y(), w.width_m = size.x();
  } else {
    w.origin = side == 2 ? lo : Eigen::Vector2d(hi.x(), lo.y());
    w.inward = side == 2 ? Eigen::Vector2d::UnitX() : Eigen::Vector2d(-Eigen::Vector2d::UnitX());
    w.across = Eigen::Vector2d::UnitY();
    w.depth_m = size.x(), w.width_m = size.y();
  }
  return w;
}

bool firstFlightOnLowSide(const PlanGrid::Result& r, int room, const StairWell& well) {
  const auto door = onlyDoorOf(r, room);
  return !door || (*door - well.origin).dot(well.across) <= well.width_m / 2 + kStackTol_m;
}

int roomForStair(const PlanGrid::Result& r, const std::string& use, double storey_height_m) {
  for (std::size_t k = 0; k < r.storey.rooms.size(); ++k) {
    if (r.storey.rooms[k].long_name != use) continue;
    const auto well = stairWellOf(r, static_cast<int>(k));
    if (well && fitHalfTurnStair(*well, storey_height_m, true, "probe")) return static_cast<int>(k);
  }
  return -1;
}

void stackStoreys(WorldSpec& spec, int storeys, const StairWell& well, bool first_on_low_side) {
  if (storeys <= 1) return;
  const StoreySpec ground = spec.storeys.at(0);
  const auto fitted = fitHalfTurnStair(well, ground.height_m, first_on_low_side, "probe");
  if (!fitted) throw std::logic_error("stacking storeys: the stair does not fit its well");
  spec.storeys.clear();
  for (int k = 0; k < storeys; ++k) {
    StoreySpec s = ground;
    const std::string prefix = "S" + std::to_string(k) + "-";
    if (k > 0) {
      s.name = "Floor " + std::to_string(k);
      s.elevation_m = ground.elevation_m + k * ground.height_m;
      for (WallSpec& w : s.walls) w.name = prefix + w.name;
      for (RoomSpec& room : s.rooms) room.name = prefix + room.name;
      // Entrances are on the ground floor; above it a door in the facade would open onto air.
      s.doors.erase(std::remove_if(s.doors.begin(), s.doors.end(),
                                   [&](const DoorSpec& d) { return s.walls[static_cast<std::size_t>(d.wall)].exterior; }),
                    s.doors.end());
      s.floor_openings = {fitted->void_outline};
    }
    if (k + 1 < storeys) {
      const std::string above = "Floor " + std::to_string(k + 1);
      s.stairs = {fitHalfTurnStair(well, ground.height_m, first_on_low_side, "Stair " + s.name + " to " + above)->stair};
    }
    spec.storeys.push_back(std::move(s));
  }
  for (std::size_t k = 0; k < spec.storeys.size(); ++k)
    for (WallSpec& w : spec.storeys[k].walls) w.height_m = clearHeight(spec, k);
}

}  // namespace bimloc::worldgen
