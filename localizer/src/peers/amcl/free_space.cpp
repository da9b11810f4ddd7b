#include "peers/amcl/free_space.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <cmath>

namespace bimloc::peers::amcl {
namespace {

// Cells reachable from the border through free cells (4-connected): the outside.
std::vector<std::uint8_t> outside(const Grid& grid) {
  std::vector<std::uint8_t> out(grid.size(), 0);
  std::vector<std::uint32_t> stack;
  const auto push = [&](int i, int j) {
    if (!grid.contains(i, j)) return;
    const std::size_t c = grid.index(i, j);
    if (out[c] || grid.occupied[c]) return;
    out[c] = 1;
    stack.push_back(static_cast<std::uint32_t>(c));
  };
  for (int i = 0; i < grid.width; ++i) push(i, 0), push(i, grid.height - 1);
  for (int j = 0; j < grid.height; ++j) push(0, j), push(grid.width - 1, j);
  while (!stack.empty()) {
    const std::uint32_t c = stack.back();
    stack.pop_back();
    const int i = static_cast<int>(c % grid.width), j = static_cast<int>(c / grid.width);
    push(i - 1, j), push(i + 1, j), push(i, j - 1), push(i, j + 1);
  }
  return out;
}

// Cells whose centre lies in some room's footprint.
std::vector<std::uint8_t> inRooms(const Grid& grid, const bim::Storey& storey) {
  std::vector<std::uint8_t> in(grid.size(), 0);
  for (const auto& room : storey.rooms) {
    if (room.footprint.size() < 3) continue;
    Eigen::Vector2d lo = room.footprint[0], hi = lo;
    for (const auto& p : room.footprint) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    if (!lo.allFinite() || !hi.allFinite()) continue;
    const Eigen::Vector2i a = grid.cellOf(lo.x(), lo.y()), b = grid.cellOf(hi.x(), hi.y());
    for (int j = std::max(0, a.y()); j <= std::min(grid.height - 1, b.y()); ++j)
      for (int i = std::max(0, a.x()); i <= std::min(grid.width - 1, b.x()); ++i)
        if (bim::pointInPolygon(room.footprint, grid.centre(i, j))) in[grid.index(i, j)] = 1;
  }
  return in;
}

}  // namespace

FreeSpace freeSpace(const LikelihoodField& field, const bim::Storey& storey, double clearance_m) {
  const Grid& grid = field.grid();
  // A clearance beyond the field's cap would exclude every cell: the cap is as far as it sees.
  const double clear = std::min(clearance_m, field.maxDistance());
  const auto& d = field.distances();
  const auto out = outside(grid), rooms = inRooms(grid, storey);
  FreeSpace fs;
  for (std::size_t c = 0; c < grid.size(); ++c)
    if (!grid.occupied[c] && d[c] >= clear && (rooms[c] || !out[c])) fs.cells.push_back(static_cast<std::uint32_t>(c));
  if (!fs.cells.empty()) return fs;
  for (std::size_t c = 0; c < grid.size(); ++c)
    if (!grid.occupied[c] && d[c] >= clear) fs.cells.push_back(static_cast<std::uint32_t>(c));
  if (!fs.cells.empty()) {
    fs.warnings.push_back("amcl: storey '" + storey.name +
                          "' has no room and its slice encloses no space: global localization spreads particles over the whole map");
    return fs;
  }
  for (std::size_t c = 0; c < grid.size(); ++c) fs.cells.push_back(static_cast<std::uint32_t>(c));
  fs.warnings.push_back("amcl: no cell of storey '" + storey.name + "' is clear of obstacles: particles spread over the whole map");
  return fs;
}

}  // namespace bimloc::peers::amcl
