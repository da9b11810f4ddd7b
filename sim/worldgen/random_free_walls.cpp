// Free-standing walls in a large room (random_styles.hpp): partitions of an open-plan office,
// display walls of an exhibition hall. They bound no room, so no room lists them.
#include "sim/worldgen/random_styles.hpp"

#include <vector>

namespace bimloc::worldgen::layout {

int freeWalls(Floor& f, const Frame& frame, Mm a0, Mm b0, Mm a1, Mm b1, int count, Symmetry symmetry) {
  constexpr Mm kClear = 900 + 50;  // PlanGrid wants 0.9 m to every other wall
  // One wall per cell of a grid over the room: walls in neighbouring cells stay 2 x kClear apart.
  const int na = symmetry == Symmetry::None ? 3 : 2, nb = 2;
  const Mm ca = (a1 - a0) / na, cb = (b1 - b0) / nb;
  const bool flip_a = symmetry == Symmetry::MirrorX || symmetry == Symmetry::Rot180;
  const bool flip_b = symmetry == Symmetry::MirrorY || symmetry == Symmetry::Rot180;
  std::vector<bool> used(static_cast<std::size_t>(na * nb), false);
  int placed = 0;
  for (int attempt = 0; attempt < 3 * na * nb && placed < count; ++attempt) {
    const int i = static_cast<int>(f.rng.between(0, na - 1)), j = static_cast<int>(f.rng.between(0, nb - 1));
    const int mi = flip_a ? na - 1 - i : i, mj = flip_b ? nb - 1 - j : j;
    const bool pair = symmetry != Symmetry::None;
    if (used[i + na * j] || (pair && (used[mi + na * mj] || (mi == i && mj == j)))) continue;
    const bool along_a = f.rng.percent(50);
    const Mm along = along_a ? ca : cb, across = along_a ? cb : ca;
    const Mm along0 = ((along_a ? a0 + i * ca : b0 + j * cb) + 4) / 5 * 5;
    const Mm across0 = ((along_a ? b0 + j * cb : a0 + i * ca) + 4) / 5 * 5;
    const Mm t = f.rng.steps(100, 200, 50);
    const Mm room_along = along - 2 * kClear - 10, room_across = across - 2 * kClear - t - 10;
    if (room_along < 1200 || room_across < 0) continue;
    const Mm length = f.rng.steps(1200, std::min<Mm>(4000, room_along), 100);
    const Mm from = along0 + kClear + 5 * f.rng.between(0, (room_along - length) / 5);
    const Mm axis = across0 + kClear + t / 2 + 5 * f.rng.between(0, room_across / 5);
    const auto emit = [&](bool mirror) {
      if (along_a) {
        const Mm lo = mirror && flip_a ? a0 + a1 - from - length : from;
        frame.freeWallAlongA(f.grid, mirror && flip_b ? b0 + b1 - axis : axis, lo, lo + length, t);
      } else {
        const Mm lo = mirror && flip_b ? b0 + b1 - from - length : from;
        frame.freeWallAlongB(f.grid, mirror && flip_a ? a0 + a1 - axis : axis, lo, lo + length, t);
      }
    };
    emit(false);
    used[i + na * j] = true, ++placed;
    if (pair) emit(true), used[mi + na * mj] = true, ++placed;
  }
  return placed;
}

}  // namespace bimloc::worldgen::layout
