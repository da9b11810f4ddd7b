// Hall floors: an open hall with free-standing walls and rows of small rooms opening into it;
// for many rooms, a hall at the end of a wing of offices (random_styles.hpp).
#include "sim/worldgen/random_styles.hpp"

#include <algorithm>

namespace bimloc::worldgen::layout {

void drawHall(Floor& f, int rooms) {
  Random& rng = f.rng;
  CompositePlan p;
  const Mm t = rng.pick<Mm>({100, 120, 150, 200});
  p.corridor_wall = rng.pick<Mm>({200, 240, 250});
  const std::vector<Item> specials = {room("WC", t, true, 900),          room("Equipment store", t, true, 1200),
                                      room("Store (no door)", t, false, 900), room("First aid", t, true, 1000),
                                      room("Office", t, true, 900),      room("Shaft", t, false, 900)};
  Item module = room(rng.percent(50) ? "Changing room" : "Store", t, true, rng.pick<Mm>({900, 1000}));
  module.width = rng.steps(3000, 5000, 50);
  module.door_from_end = rng.percent(50);
  module.door_at = rng.percent(30) ? module.width / 2 / 5 * 5 : rng.steps(module.door_width / 2 + 200, 1300, 5);
  p.south.depth = rng.steps(3000, 5000, 50);
  p.south.module = module;
  p.south.specials = specials;
  p.north = p.south;
  const Mm r = rng.between(0, 99);
  p.symmetry = r < 20 ? Symmetry::MirrorY : r < 40 ? Symmetry::Rot180 : r < 60 ? Symmetry::MirrorX : Symmetry::None;
  p.entrance_east = rng.percent(60);
  if (rooms <= 24) {  // the hall is the wing's corridor, the rooms open into it
    p.corridor = rng.steps(10000, 18000, 50);
    p.corridor_use = rng.percent(50) ? "Sports hall" : "Exhibition hall";
    p.corridor_free_walls = static_cast<int>(rng.between(1, 4));
    if (rng.percent(35)) p.north.depth = 0;
    const int rows = p.north.depth > 0 ? 2 : 1;
    p.modules = std::max(2, (rooms - 1) / rows - 1);
    // At least as long as the hall is wide, less than three times that.
    const Mm w = module.width + t;
    p.modules = std::max<int>(p.modules, static_cast<int>(p.corridor / w));
  } else {  // a hall at the end of a wing of offices and stores
    p.corridor = rng.steps(1800, 2500, 50);
    p.south.module.use = "Office";
    p.north.module.use = "Office";
    p.end_hall = rng.steps(14000, 24000, 50);
    p.end_hall_use = rng.percent(50) ? "Sports hall" : "Exhibition hall";
    p.end_hall_free_walls = static_cast<int>(rng.between(2, 4));
    p.west = p.south, p.east = p.north;
    shareRooms(rng, p, rooms, 3, 15, 25);
    p.fire_wall_every = rng.percent(50) ? rng.steps(25000, 40000, 1000) : 0;
  }
  drawComposite(f, p);
}

}  // namespace bimloc::worldgen::layout
