// Office and school floors: rows of identical rooms on a corridor (random_styles.hpp).
#include "sim/worldgen/random_styles.hpp"

#include <algorithm>

namespace bimloc::worldgen::layout {
namespace {

// A module: width, and a door that all its copies share (same side, same distance).
Item module(Random& rng, const char* use, Mm width, Mm divider, Mm door_width, Mm latest_door_at) {
  Item m = room(use, divider, true, door_width);
  m.width = width;
  m.door_from_end = rng.percent(50);
  const Mm first = door_width / 2 + 200, last = std::min(latest_door_at, width - door_width / 2 - 200);
  m.door_at = rng.percent(25) ? width / 2 / 5 * 5 : rng.steps(first, std::max(first, last), 5);
  return m;
}

Symmetry symmetryFor(Random& rng, int percent) {
  if (!rng.percent(percent)) return Symmetry::None;
  const Mm r = rng.between(0, 2);
  return r == 0 ? Symmetry::Rot180 : r == 1 ? Symmetry::MirrorX : Symmetry::MirrorY;
}

}  // namespace

void shareRooms(Random& rng, CompositePlan& p, int rooms, int fixed_rooms, int percent_l, int percent_t) {
  constexpr Mm kLongestRow = 70000;
  const int rows_a = p.north.depth > 0 ? 2 : 1;
  // At least three rooms a row, the row of identical rooms these floors are for; apartments: one.
  const int least = p.south.module.kind == Item::Kind::Room ? 3 : 1;
  const int movable = std::max(1, rooms - fixed_rooms);
  const Mm pitch = std::max(p.south.module.width, p.west.module.width) + p.south.module.divider;
  const auto short_enough = [&](int rows) { return movable / rows * pitch <= kLongestRow; };
  const Mm r = rng.between(0, 99);
  p.shape = r < percent_l ? Shape::L : r < percent_l + percent_t ? Shape::T : Shape::I;
  if (p.shape == Shape::I && !short_enough(rows_a)) p.shape = Shape::T;
  if (p.shape == Shape::L && !short_enough(rows_a + 2)) p.shape = Shape::T;
  p.branches = 1;
  while (p.shape == Shape::T && !short_enough(rows_a + 2 * p.branches) && p.branches < 4) ++p.branches;
  const int rows = rows_a + (p.shape == Shape::I ? 0 : 2 * p.branches);
  p.modules = p.modules_b = std::max(least, movable / rows - (least > 1 ? 1 : 0));  // the rest: special rooms
}

void drawOffice(Floor& f, int rooms) {
  Random& rng = f.rng;
  CompositePlan p;
  const Mm t = rng.pick<Mm>({100, 120, 150});
  p.corridor_wall = rng.pick<Mm>({200, 220, 240, 250});
  p.corridor = rng.steps(1500, 2500, 50);
  p.corridor_b = rng.percent(50) ? p.corridor : rng.steps(1500, 2500, 50);
  const Mm door = rng.pick<Mm>({850, 900, 950, 1000});
  const std::vector<Item> specials = {
      room("Meeting room", t, true, 1000), room("Meeting room", t, true, 900), room("WC", t, true, 900),
      room("Store (no door)", t, false, 900), room("Kitchenette", t, true, door), room("Copy room", t, true, door),
      room("Server room", t, true, 900), room("Shaft", t, false, 900)};
  p.south.depth = rng.steps(4000, 6500, 50);
  p.south.module = module(rng, "Office", rng.steps(2700, 4500, 50), t, door, 1200);
  p.south.specials = specials;
  p.north = p.south;
  if (rng.percent(40)) p.north.depth = rng.steps(4000, 6500, 50);
  if (rng.percent(40)) p.north.module = module(rng, "Office", rng.steps(2700, 4500, 50), t, door, 1200);
  p.west = p.south, p.east = p.north;
  p.west.depth = rng.steps(4000, 6500, 50);
  p.east.depth = rng.percent(50) ? p.west.depth : rng.steps(4000, 6500, 50);
  const bool end_hall = rng.percent(20);
  shareRooms(rng, p, rooms, 2 + (end_hall ? 1 : 0), 25, 30);
  p.symmetry = symmetryFor(rng, p.shape == Shape::L ? 0 : p.shape == Shape::T ? 70 : 60);
  p.entrance_east = rng.percent(40);
  p.entrance_b = rng.percent(50);
  p.fire_wall_every = rng.percent(50) ? rng.steps(25000, 40000, 1000) : 0;
  if (end_hall) {
    p.end_hall = rng.steps(8000, 14000, 50);
    p.end_hall_use = "Open-plan office";
    p.end_hall_free_walls = static_cast<int>(rng.between(1, 3));
  }
  drawComposite(f, p);
}

void drawSchool(Floor& f, int rooms) {
  Random& rng = f.rng;
  CompositePlan p;
  const Mm t = rng.pick<Mm>({120, 150, 180, 200});
  p.corridor_wall = rng.pick<Mm>({200, 240, 250});
  p.corridor = rng.steps(2000, 2500, 50);
  p.corridor_b = p.corridor;
  p.corridor_use = "Corridor";
  const std::vector<Item> specials = {
      room("WC (girls)", t, true, 900), room("WC (boys)", t, true, 900), room("Store (no door)", t, false, 900),
      room("Staff room", t, true, 1000), room("Library", t, true, 1000), room("Cleaning (no door)", t, false, 900),
      room("Stair", t, true, 1000)};
  p.south.depth = rng.steps(6500, 8000, 50);
  p.south.module = module(rng, "Classroom", rng.steps(6500, 8000, 50), t, 1000, 1500);
  p.south.specials = specials;
  p.north = p.south;
  if (rng.percent(45)) {
    p.north.depth = 0;  // single-loaded: the corridor runs along the facade
  } else if (rng.percent(40)) {
    p.north.depth = rng.steps(4000, 6000, 50);
    p.north.module = module(rng, "Group room", rng.steps(3000, 4500, 50), t, 1000, 1200);
  }
  p.west = p.south, p.east = p.south;
  p.west.depth = p.east.depth = rng.steps(6500, 8000, 50);
  const bool end_hall = rng.percent(60);
  shareRooms(rng, p, rooms, 2 + (end_hall ? 1 : 0), 30, 15);
  p.symmetry = symmetryFor(rng, p.shape == Shape::L ? 0 : p.shape == Shape::T ? 70 : 55);
  p.entrance_east = rng.percent(50);
  p.entrance_b = rng.percent(50);
  if (end_hall) {
    p.end_hall = rng.steps(10000, 16000, 50);
    p.end_hall_use = "Assembly hall";
    p.end_hall_free_walls = static_cast<int>(rng.between(0, 2));
  }
  drawComposite(f, p);
}

}  // namespace bimloc::worldgen::layout
