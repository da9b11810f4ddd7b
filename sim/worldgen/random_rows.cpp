// Rows of rooms: filling a length with identical modules, turning and mirroring rows, and the
// one small difference that makes a symmetric floor near-symmetric (random_layout.hpp).
#include "sim/worldgen/random_layout.hpp"

#include <algorithm>
#include <stdexcept>

namespace bimloc::worldgen::layout {
namespace {

constexpr Mm kMinRoom = 2500, kMaxRoom = 8000;
constexpr Mm kJambClearance = 150;  // from a door's edge to the room's corner, at least

Item special(Random& rng, const std::vector<Item>& specials, Mm width, Mm divider) {
  Item item = rng.pick(specials);
  item.width = width;
  item.divider = divider;
  const Mm latest = width - item.door_width / 2 - kJambClearance;
  item.door_at = item.door_at == 0 ? width / 2 / 5 * 5 : std::min(item.door_at, latest);
  return item;
}

Item flipped(Item item) {
  item.door_from_end = !item.door_from_end;
  item.mirrored = !item.mirrored;
  return item;
}

// Where a room's door centre is, from its start face.
Mm doorFromStart(const Item& item) { return item.door_from_end ? item.width - item.door_at : item.door_at; }

bool doorFits(const Item& item) {
  if (!item.door || item.kind != Item::Kind::Room) return true;
  const Mm c = doorFromStart(item), half = item.door_width / 2 + kJambClearance;
  return c >= half && c <= item.width - half;
}

}  // namespace

std::vector<Item> fillRow(Random& rng, Mm length, const Item& module, const std::vector<Item>& specials) {
  const Mm w = module.width, t = module.divider;
  Mm k = std::max<Mm>(0, (length + t) / (w + t));
  Mm rem = length - (k * w + (k - 1) * t);
  std::vector<Mm> extras;
  if (rem > 0) {
    if (rem - t < kMinRoom && k > 0) --k, rem += w + t;
    const Mm x = rem - t;  // one more room and its divider
    if (x < kMinRoom) throw std::logic_error("random layout: a row of " + std::to_string(length) + " mm is too short");
    if (x <= kMaxRoom) {
      extras.push_back(x);
    } else {
      const Mm a = (x - t) / 2 / 5 * 5;
      extras.push_back(a), extras.push_back(x - t - a);
    }
  }
  std::vector<Item> items(static_cast<std::size_t>(k), module);
  for (Mm x : extras) {
    // At the start, the end or amid the modules, but after three of them at least: the row
    // keeps a run of three identical rooms.
    const int where = static_cast<int>(rng.between(0, 3));
    const std::size_t at = where == 0 ? 0 : where == 1 || k < 4 ? items.size() : static_cast<std::size_t>(rng.between(3, k));
    items.insert(items.begin() + static_cast<long>(std::min(at, items.size())), special(rng, specials, x, t));
  }
  return items;
}

std::vector<Item> reversedItems(const std::vector<Item>& items) {
  std::vector<Item> out;
  for (std::size_t i = items.size(); i-- > 0;) {
    out.push_back(flipped(items[i]));
    out.back().divider = i > 0 ? items[i - 1].divider : items[i].divider;
  }
  return out;
}

std::vector<Item> palindrome(const std::vector<Item>& half, const Item& centre) {
  std::vector<Item> out = half;
  if (centre.width > 0) {
    out.push_back(centre);
    out.back().divider = half.empty() ? centre.divider : half.back().divider;
  }
  const std::vector<Item> back = reversedItems(half);
  out.insert(out.end(), back.begin(), back.end());
  return out;
}

std::string perturb(Random& rng, std::vector<Row*> rows) {
  struct Slot {
    Row* row;
    std::size_t k;
  };
  std::vector<Slot> doors, pairs, halls, apartments;
  for (Row* row : rows)
    for (std::size_t k = 0; k < row->items.size(); ++k) {
      const Item& item = row->items[k];
      if (item.kind == Item::Kind::Apartment) apartments.push_back({row, k});
      if (item.kind != Item::Kind::Room) continue;
      if (item.door) doors.push_back({row, k});
      if (k + 1 < row->items.size() && row->items[k + 1].kind == Item::Kind::Room) pairs.push_back({row, k});
      if (item.width >= 5000 && row->depth >= 4000 && item.free_wall == 0) halls.push_back({row, k});
    }
  const Mm sign = rng.percent(50) ? 1 : -1;
  // Try the kinds of difference from a random one on, until one applies.
  const int first = static_cast<int>(rng.between(0, 4));
  for (int n = 0; n < 5; ++n) {
    switch ((first + n) % 5) {
      case 0:  // a door moved along its wall
        for (int attempt = 0; attempt < 4 && !doors.empty(); ++attempt) {
          const Slot s = rng.pick(doors);
          Item& item = s.row->items[s.k];
          const Mm before = item.door_at, d = rng.steps(300, 800, 50) * (attempt % 2 == 0 ? sign : -sign);
          item.door_at += d;
          if (doorFits(item)) return item.note = "door moved " + std::to_string(std::abs(d)) + " mm";
          item.door_at = before;
        }
        break;
      case 1:  // two neighbours, one wider and one narrower
        for (int attempt = 0; attempt < 4 && !pairs.empty(); ++attempt) {
          const Slot s = rng.pick(pairs);
          Item &a = s.row->items[s.k], &b = s.row->items[s.k + 1];
          const Mm d = rng.steps(200, 600, 50) * (attempt % 2 == 0 ? sign : -sign);
          a.width += d, b.width -= d;
          if (std::min(a.width, b.width) >= kMinRoom && std::max(a.width, b.width) <= kMaxRoom && doorFits(a) &&
              doorFits(b)) {
            return a.note = "wall to the next room moved " + std::to_string(std::abs(d)) + " mm";
          }
          a.width -= d, b.width += d;
        }
        break;
      case 2:  // a short free-standing wall in a larger room
        if (!halls.empty()) {
          const Slot s = rng.pick(halls);
          Item& item = s.row->items[s.k];
          item.free_wall = rng.steps(1000, std::min<Mm>(2000, item.width - 2000), 100);
          return item.note = "short free-standing wall (" + std::to_string(item.free_wall) + " mm)";
        }
        break;
      case 3:  // an apartment's entrance elsewhere along its hall
        for (int attempt = 0; attempt < 4 && !apartments.empty(); ++attempt) {
          const Slot s = rng.pick(apartments);
          Apartment& ap = s.row->items[s.k].apartment;
          const Mm d = rng.steps(300, 600, 50), lo = ap.door_width / 2 + kJambClearance, hi = ap.hall - lo;
          const Mm moved = ap.entrance_at + d <= hi ? ap.entrance_at + d : ap.entrance_at - d;
          if (moved < lo || moved > hi) continue;
          ap.entrance_at = moved;
          return s.row->items[s.k].note = "entrance door moved " + std::to_string(d) + " mm";
        }
        break;
      default:  // a door missing: the room is closed
        if (!doors.empty()) {
          const Slot s = rng.pick(doors);
          Item& item = s.row->items[s.k];
          item.door = false;
          item.use = "Store (no door)";
          return item.note = "door missing";
        }
        break;
    }
  }
  return "";
}

}  // namespace bimloc::worldgen::layout
