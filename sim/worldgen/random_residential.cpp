// Residential floors: identical apartments, every other one mirrored, along a corridor; or a
// single house for a handful of rooms (random_styles.hpp).
#include "sim/worldgen/random_styles.hpp"

#include <algorithm>

namespace bimloc::worldgen::layout {
namespace {

// An apartment that fits together: the hall reaches the living room over a door and more,
// every door 0.2 m clear of the corners. Returns its width; depth is near + partition + far.
Apartment apartment(Random& rng, Mm partition, Mm door, Mm* width, Mm* depth) {
  Apartment ap;
  const Mm t = partition;
  ap.partition = t;
  ap.door_width = door;
  ap.near_depth = rng.steps(2500, 3200, 50);
  const Mm far = rng.steps(4500, 7000, 50);
  ap.bath = rng.steps(2500, 3000, 50);
  ap.bed = rng.steps(3000, 4000, 50);
  ap.bed2 = rng.percent(40) ? rng.steps(3000, 3800, 50) : 0;
  const Mm living = ap.bed2 > 0 ? rng.steps(3500, 5000, 50) : rng.steps(3500, 6000, 50);
  const Mm W = ap.bed + t + living + (ap.bed2 > 0 ? t + ap.bed2 : 0);
  ap.hall = std::max<Mm>(2500, ap.bed - ap.bath + door + 400) + rng.steps(0, 800, 50);
  if (W - ap.bath - ap.hall - 2 * t < 2500) ap.hall = W - ap.bath - t;  // no kitchen: the hall takes the rest
  ap.entrance_at = rng.steps(door / 2 + 200, ap.hall - door / 2 - 200, 5);
  ap.bed_door_at = rng.steps(door / 2 + 200, far - door / 2 - 200, 5);
  *width = W;
  *depth = ap.near_depth + t + far;
  return ap;
}

Item apartmentItem(const Apartment& ap, Mm width, Mm party_wall) {
  Item item;
  item.kind = Item::Kind::Apartment;
  item.apartment = ap;
  item.width = width;
  item.divider = party_wall;
  item.door = false;
  return item;
}

int roomsOf(const Apartment& ap, Mm width) {
  const bool kitchen = ap.bath + ap.hall + 2 * ap.partition < width;
  return 4 + (kitchen ? 1 : 0) + (ap.bed2 > 0 ? 1 : 0);
}

Item special(const char* use, Mm divider, bool door) {
  Item item;
  item.use = use;
  item.divider = divider;
  item.door = door;
  item.door_width = 1000;
  return item;
}

}  // namespace

void drawResidential(Floor& f, int rooms) {
  Random& rng = f.rng;
  const Mm party = rng.pick<Mm>({200, 220, 240, 250}), partition = rng.pick<Mm>({100, 120});
  const Mm door = rng.pick<Mm>({850, 900});
  Mm width = 0, depth = 0;
  const Apartment ap = apartment(rng, partition, door, &width, &depth);
  if (rooms <= 8) {  // a house: one apartment, entered from outside
    Wing w;
    w.a_start = kSiteMargin + f.exterior / 2, w.t_start = w.t_end = f.exterior;
    w.b_south = kSiteMargin + f.exterior / 2, w.t_south = w.t_north = f.exterior;
    w.a_end = w.faceStart() + width + f.exterior / 2;
    w.south.depth = depth;
    w.south.items = {apartmentItem(ap, width, party)};
    drawWing(f, w);
    f.features.push_back("house: one apartment, " + std::to_string(roomsOf(ap, width)) + " rooms");
    return;
  }
  CompositePlan p;
  p.corridor = rng.steps(1500, 2000, 50);
  p.corridor_b = p.corridor;
  p.corridor_wall = rng.pick<Mm>({200, 240, 250});
  const Item module = apartmentItem(ap, width, party);
  const std::vector<Item> specials = {special("Stair", party, true), special("Shaft", party, false),
                                      special("Store (no door)", party, false), special("Storage", party, true)};
  p.south.depth = depth;
  p.south.module = module;
  p.south.specials = specials;
  p.south.alternate = true;
  p.north = p.south;
  p.west = p.east = p.south;
  const int per_apartment = roomsOf(ap, width);
  // Counted in apartments. No L: its corner room would be an apartment deep (over 8 m).
  shareRooms(rng, p, std::max(2, (rooms - 3) / per_apartment), 0, 0, 20);
  const Mm r = rng.between(0, 99);
  p.symmetry = r < 25 ? Symmetry::MirrorY : r < 45 ? Symmetry::Rot180 : r < 65 ? Symmetry::MirrorX : Symmetry::None;
  p.entrance_east = rng.percent(50);
  drawComposite(f, p);
  f.features.push_back("apartments of " + std::to_string(per_apartment) + " rooms, every other one mirrored");
}

}  // namespace bimloc::worldgen::layout
