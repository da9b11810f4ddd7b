// The composite floor of random_styles.hpp: wing A (+ wings B in an L, a T or a comb), an end hall,
// entrances and fire doors, drawn symmetric and then changed in one place. Free-standing walls:
// random_free_walls.cpp.
#include "sim/worldgen/random_styles.hpp"

#include <algorithm>
#include <set>

namespace bimloc::worldgen::layout {
namespace {

Item passage(Mm width, Mm walls) {
  Item p;
  p.kind = Item::Kind::Passage;
  p.width = width;
  p.divider = walls;
  p.door = false;
  return p;
}

// Double doors for entrances and corridor splits: 1.2-1.8 m, 0.15 m clear of the corners.
Mm doubleDoor(Random& rng, Mm clear) { return rng.steps(1200, std::max<Mm>(1200, std::min<Mm>(1800, clear - 300)), 10); }

// A row's longest run of identical rooms (size and door alike), and their use.
std::pair<int, std::string> identicalRun(const Row& row) {
  const auto same = [](const Item& a, const Item& b) {
    return a.kind == Item::Kind::Room && b.kind == Item::Kind::Room && a.width == b.width && a.use == b.use &&
           a.door == b.door && a.door_at == b.door_at && a.door_from_end == b.door_from_end && a.free_wall == 0 &&
           b.free_wall == 0;
  };
  std::pair<int, std::string> best{0, ""};
  for (std::size_t k = 0, run = 1; k < row.items.size(); ++k) {
    run = k > 0 && same(row.items[k - 1], row.items[k]) ? run + 1 : 1;
    if (static_cast<int>(run) > best.first && row.items[k].kind == Item::Kind::Room) best = {static_cast<int>(run), row.items[k].use};
  }
  return best;
}

bool sameItems(const std::vector<Item>& a, const std::vector<Item>& b) {
  const auto same = [](const Item& x, const Item& y) {
    return x.kind == y.kind && x.width == y.width && x.divider == y.divider && x.use == y.use && x.door == y.door &&
           x.door_at == y.door_at && x.door_from_end == y.door_from_end && x.mirrored == y.mirrored &&
           x.free_wall == y.free_wall;
  };
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    Item x = a[k];
    if (k + 1 == a.size()) x.divider = b[k].divider;  // the last item's is not drawn
    if (!same(x, b[k])) return false;
  }
  return true;
}

void noteFeatures(Floor& f, const CompositePlan& p, const std::vector<Row*>& rows) {
  std::pair<int, std::string> best{0, ""};
  for (const Row* row : rows) best = std::max(best, identicalRun(*row), [](const auto& a, const auto& b) { return a.first < b.first; });
  if (best.first >= 3) f.features.push_back("row of " + std::to_string(best.first) + " identical " + best.second);
  if (p.shape == Shape::L) f.features.push_back("L-shaped corridor");
  if (p.shape == Shape::T) {
    f.features.push_back(p.branches < 2 ? "T-shaped corridor" : "comb: " + std::to_string(p.branches) + " wings off the corridor");
  }
  if (p.symmetry == Symmetry::Rot180) f.features.push_back("rows turned 180 deg across the corridor");
  if (p.symmetry == Symmetry::MirrorY) f.features.push_back("rows mirrored across the corridor");
  if (p.symmetry == Symmetry::MirrorX) f.features.push_back(p.shape == Shape::T ? "mirrored wings" : "mirrored halves");
  for (const Row* row : rows)
    for (const Item& item : row->items)
      if (!item.note.empty()) {
        f.near_symmetric = true;
        f.features.push_back(std::string("near-symmetric (") + symmetryName(p.symmetry) + "): " +
                             Floor::roomName(item.label) + " " + item.note);
      }
}

}  // namespace

const char* symmetryName(Symmetry s) {
  switch (s) {
    case Symmetry::Rot180: return "180 deg turn";
    case Symmetry::MirrorX: return "mirror x";
    case Symmetry::MirrorY: return "mirror y";
    default: return "none";
  }
}

void drawComposite(Floor& f, CompositePlan p) {
  Random& rng = f.rng;
  const Mm ext = f.exterior, t = p.south.module.divider;
  // Which symmetries a shape allows: an L none, a T its mirror image across B's corridor (and
  // no hall at one end), a straight wing any, but with a hall at its east end only the mirror
  // across the corridor, and with a single row no symmetry across the corridor.
  const bool turned = p.symmetry == Symmetry::Rot180 || p.symmetry == Symmetry::MirrorY;
  if (p.shape == Shape::L) p.symmetry = Symmetry::None;
  if (p.shape == Shape::T && p.symmetry != Symmetry::None) p.symmetry = p.end_hall > 0 ? Symmetry::None : Symmetry::MirrorX;
  if (p.shape == Shape::I && p.north.depth == 0 && turned) p.symmetry = Symmetry::MirrorX;
  if (p.shape == Shape::I && p.end_hall > 0 && p.symmetry != Symmetry::None) {
    p.symmetry = p.north.depth > 0 ? Symmetry::MirrorY : Symmetry::None;
  }
  if (p.symmetry == Symmetry::Rot180 || p.symmetry == Symmetry::MirrorY) p.north = p.south;
  p.north.module.divider = t;
  if (p.shape == Shape::T && p.symmetry == Symmetry::MirrorX) p.east = p.west;
  if (p.symmetry == Symmetry::Rot180 || p.symmetry == Symmetry::MirrorX) p.entrance_east = p.entrance_west;

  // Wing A's rows, exactly LA long; a mirror image has modules on both sides of its axis.
  const Mm w = p.south.module.width, wn = p.north.module.width;
  const Mm cB = p.corridor_b, tcB = p.corridor_wall, dw = p.west.depth, de = p.east.depth;
  const auto extra = [&] { return rng.percent(50) ? rng.steps(2500, 6000, 50) + t : 0; };
  int m = std::max(1, p.modules);
  if (p.symmetry == Symmetry::MirrorX) m = std::max(p.south.module.kind == Item::Kind::Room ? 6 : 2, (m + 1) / 2 * 2);
  Mm LA = m * (w + t) - t + extra();
  if (p.symmetry == Symmetry::MirrorX) LA = 2 * (m / 2 * (w + t) - t + extra()) + t;  // two halves and the wall between
  if (p.shape == Shape::L) LA = std::max(LA, dw + cB + 2 * tcB + 2 * (wn + t));
  std::vector<Mm> segments;  // T: A's north row between the passages into the wings B
  const int k = p.shape == Shape::T ? std::max(1, p.branches) : 0;
  if (p.shape == Shape::T) {
    // Beyond the outer wings 3 m of A's north row at least, between two wings a 6 m courtyard.
    const Mm end_min = std::max(dw, de) + ext + 3000, gap_min = dw + de + 2 * ext + 6000;
    const int per = std::max(1, m / (k + 1));
    for (int i = 0; i <= k; ++i) {
      const Mm least = i == 0 || i == k ? end_min : gap_min;
      const int fit = static_cast<int>((least + t + wn - 1) / (wn + t));
      segments.push_back(std::max(least, std::max(per, fit) * (wn + t) - t + extra()));
    }
    if (p.symmetry == Symmetry::MirrorX) {
      for (int i = 0; i < k - i; ++i) segments[k - i] = segments[i];
      if (k % 2 == 0 && (segments[k / 2] - t) % 10 != 0) segments[k / 2] += 5;  // a palindrome around its middle wall
    }
    LA = k * (cB + 2 * tcB);
    for (Mm s : segments) LA += s;
    if (p.symmetry == Symmetry::MirrorX && (LA - t) % 10 != 0) throw LayoutConflict("random layout: a T off the 5 mm grid");
  }
  Wing A;
  A.south.depth = p.south.depth, A.north.depth = p.north.depth;
  const auto fill = [&](Mm length, const RowRecipe& r) {
    std::vector<Item> items = fillRow(rng, length, r.module, r.specials);
    bool mirrored = false;
    for (Item& item : items)
      if (r.alternate && item.kind == r.module.kind) item.mirrored = mirrored, mirrored = !mirrored;
    return items;
  };
  if (p.symmetry == Symmetry::MirrorX) {
    A.south.items = palindrome(fill((LA - t) / 2, p.south), Item{});
  } else {
    A.south.items = fill(LA, p.south);
  }
  if (p.north.depth > 0 && p.shape == Shape::I) {
    if (p.symmetry == Symmetry::Rot180) A.north.items = reversedItems(A.south.items);
    else if (p.symmetry == Symmetry::MirrorY) A.north.items = A.south.items;
    else if (p.symmetry == Symmetry::MirrorX) A.north.items = palindrome(fill((LA - t) / 2, p.north), Item{});
    else A.north.items = fill(LA, p.north);
  } else if (p.shape == Shape::L) {
    Item corner = rng.pick(p.north.specials);
    corner.width = dw, corner.divider = tcB, corner.door_at = dw / 2 / 5 * 5;
    A.north.items = {corner, passage(cB, tcB)};
    const std::vector<Item> rest = fill(LA - dw - cB - 2 * tcB, p.north);
    A.north.items.insert(A.north.items.end(), rest.begin(), rest.end());
  } else if (p.shape == Shape::T) {
    // Segments and passages; mirrored, the left half around the middle passage or segment.
    const int upto = p.symmetry == Symmetry::MirrorX ? (k + 1) / 2 : k + 1;
    for (int i = 0; i < upto; ++i) {
      std::vector<Item> seg = fill(segments[i], p.north);
      if (i < k) seg.back().divider = tcB;
      A.north.items.insert(A.north.items.end(), seg.begin(), seg.end());
      if (i < k && (p.symmetry != Symmetry::MirrorX || i + 1 < upto || k % 2 == 0)) A.north.items.push_back(passage(cB, tcB));
    }
    if (p.symmetry == Symmetry::MirrorX && k % 2 == 0) {
      const std::vector<Item> mid = fill((segments[k / 2] - t) / 2, p.north);
      A.north.items.insert(A.north.items.end(), mid.begin(), mid.end());
    }
    if (p.symmetry == Symmetry::MirrorX) A.north.items = palindrome(A.north.items, k % 2 == 1 ? passage(cB, tcB) : Item{});
  }
  // Rows that came out the same (or turned) are a symmetric floor too: treat them as one.
  if (p.symmetry == Symmetry::None && p.shape == Shape::I && A.north.depth == A.south.depth) {
    if (sameItems(A.north.items, A.south.items)) p.symmetry = Symmetry::MirrorY;
    else if (sameItems(A.north.items, reversedItems(A.south.items))) p.symmetry = Symmetry::Rot180;
  }
  // The wings B: mirrored, wing k-1-i is wing i with its rows swapped.
  std::vector<Wing> B(p.shape == Shape::I ? 0 : std::max(1, k));
  for (std::size_t i = 0; i < B.size(); ++i) {
    const std::size_t twin = B.size() - 1 - i;
    B[i].south.depth = dw, B[i].north.depth = de;
    if (p.symmetry == Symmetry::MirrorX && twin < i) {
      B[i].south.items = B[twin].north.items, B[i].north.items = B[twin].south.items;
      continue;
    }
    const Mm wb = p.west.module.width, tb = p.west.module.divider;
    const Mm LB = std::max(1, p.modules_b) * (wb + tb) - tb + (rng.percent(50) ? rng.steps(2500, 6000, 50) + tb : 0);
    B[i].south.items = fill(LB, p.west);
    B[i].north.items = p.symmetry == Symmetry::MirrorX && twin == i ? B[i].south.items : fill(LB, p.east);
  }
  std::vector<Row*> rows = {&A.south, &A.north};
  for (Wing& b : B) rows.push_back(&b.south), rows.push_back(&b.north);
  if (p.symmetry != Symmetry::None) perturb(rng, rows);

  // Draw A, then B on A's north side, then the end hall.
  A.corridor_label = f.room(p.corridor_use);
  A.a_start = kSiteMargin + ext / 2, A.t_start = ext, A.b_south = kSiteMargin + ext / 2, A.t_south = A.t_north = ext;
  A.corridor = p.corridor, A.corridor_wall = p.corridor_wall;
  A.t_end = p.end_hall > 0 ? p.corridor_wall : ext;
  A.a_end = A.faceStart() + LA + A.t_end / 2;
  drawWing(f, A);
  const auto corridorMid = [](const Wing& wing) { return (wing.b_corridor_south + wing.b_corridor_north) / 10 * 5; };
  if (p.corridor_free_walls > 0) {
    const Mm b0 = A.south.depth > 0 ? A.b_corridor_south + A.corridor_wall / 2 : A.b_south + ext / 2;
    const Mm b1 = A.north.depth > 0 ? A.b_corridor_north - A.corridor_wall / 2 : A.b_north - ext / 2;
    const int n = freeWalls(f, A.frame, A.faceStart(), b0, A.faceEnd(), b1, p.corridor_free_walls, p.symmetry);
    f.features.push_back(p.corridor_use + " with " + std::to_string(n) + " free-standing wall(s)");
  }
  const Mm corridor_clear = p.corridor;
  Mm passage_face = A.faceStart();
  auto next = A.north.items.begin();
  const Mm entrance_b = doubleDoor(rng, cB);  // the same doors at the end of every wing
  for (Wing& b : B) {  // each on its passage through A's north row, its corridor A's
    for (; next->kind != Item::Kind::Passage; ++next) passage_face += next->width + next->divider;
    b.frame = Frame::swapped();
    b.corridor_label = A.corridor_label;
    b.a_start = A.b_north, b.t_start = ext;
    b.b_south = passage_face - tcB - dw - ext / 2, b.t_south = b.t_north = ext;
    b.corridor = cB, b.corridor_wall = tcB;
    b.t_end = ext;
    b.a_end = b.faceStart() + b.south.length() + ext / 2;
    drawWing(f, b);
    if (p.entrance_b) b.frame.doorOnA(f.grid, b.a_end, corridorMid(b), entrance_b, f.door_height);
    passage_face += next->width + next->divider;
    ++next;
  }
  const Mm entrance = doubleDoor(rng, corridor_clear);  // both ends alike
  if (p.entrance_west) A.frame.doorOnA(f.grid, A.a_start, corridorMid(A), entrance, f.door_height);
  if (p.end_hall > 0) {
    const Mm hall_end = A.a_end + A.t_end / 2 + p.end_hall + ext / 2;
    A.frame.lineA(f.grid, hall_end, ext);
    const int hall = f.room(p.end_hall_use);
    A.frame.paint(f.grid, A.a_end, A.b_south, hall_end, A.b_north, hall);
    A.frame.doorOnA(f.grid, A.a_end, corridorMid(A), doubleDoor(rng, corridor_clear), f.door_height);
    if (p.entrance_east) A.frame.doorOnA(f.grid, hall_end, corridorMid(A), doubleDoor(rng, 2000), f.door_height);
    const int n = freeWalls(f, A.frame, A.a_end + A.t_end / 2, A.b_south + ext / 2, hall_end - ext / 2,
                            A.b_north - ext / 2, p.end_hall_free_walls, p.symmetry);
    f.features.push_back(p.end_hall_use + " " + std::to_string(p.end_hall / 1000) + " m long, " + std::to_string(n) +
                         " free-standing wall(s)");
  } else if (p.entrance_east) {
    A.frame.doorOnA(f.grid, A.a_end, corridorMid(A), entrance, f.door_height);
  }
  // Fire doors across a long straight corridor, 1 m clear of the rows' dividers and doors.
  if (p.shape == Shape::I && p.fire_wall_every > 0 && LA > p.fire_wall_every * 3 / 2) {
    std::vector<std::pair<Mm, Mm>> taken;
    for (const Row* row : {&A.south, &A.north}) {
      Mm face = A.faceStart();
      for (const Item& item : row->items) {
        if (item.door) {
          const Mm c = face + (item.door_from_end ? item.width - item.door_at : item.door_at);
          taken.emplace_back(c - item.door_width / 2, c + item.door_width / 2);
        }
        face += item.width;
        taken.emplace_back(face, face + item.divider);
        face += item.divider;
      }
    }
    const int parts = p.symmetry == Symmetry::None ? static_cast<int>(LA / p.fire_wall_every) + 1 : 2;
    std::vector<Mm> cuts;
    for (int part = 1; part < parts; ++part) {
      const Mm a = (A.faceStart() + LA * part / parts) / 5 * 5;
      bool clear = true;
      for (const auto& [lo, hi] : taken) clear = clear && (a + 1000 <= lo || a - 1000 >= hi);
      if (clear) cuts.push_back(a);
    }
    for (const Mm a : cuts) A.frame.lineA(f.grid, a, p.corridor_wall);
    for (std::size_t c = 0; c < cuts.size(); ++c) {
      const Mm a = cuts[c], until = c + 1 < cuts.size() ? cuts[c + 1] : A.a_end;
      A.frame.paint(f.grid, a, A.b_corridor_south, until, A.b_corridor_north, f.room(p.corridor_use));
      A.frame.doorOnA(f.grid, a, corridorMid(A), doubleDoor(rng, corridor_clear), f.door_height);
    }
    if (!cuts.empty()) f.features.push_back("corridor split by " + std::to_string(cuts.size()) + " fire door(s)");
  }
  noteFeatures(f, p, rows);
}

}  // namespace bimloc::worldgen::layout
