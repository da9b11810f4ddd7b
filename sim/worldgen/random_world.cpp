#include "sim/worldgen/random_world.hpp"

#include "sim/worldgen/random_storeys.hpp"
#include "sim/worldgen/random_styles.hpp"
#include "sim/worldgen/spec_check.hpp"
#include "sim/worldgen/spec_symmetry.hpp"

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <optional>
#include <stdexcept>

namespace bimloc::worldgen {
namespace {

using namespace layout;

constexpr int kMaxDraws = 24;

// Rooms that share a door are connected; every room with a door must be connected to every
// other without going outside (the simulated base walks indoors).
void checkReachable(const PlanGrid::Result& r) {
  std::vector<int> parent(r.room_doors.size());
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](int k) {
    while (parent[k] != k) k = parent[k] = parent[parent[k]];
    return k;
  };
  for (const auto& [a, b] : r.door_rooms)
    if (a >= 0 && b >= 0) parent[root(a)] = root(b);
  int first = -1;
  for (int k = 0; k < static_cast<int>(parent.size()); ++k) {
    if (r.room_doors[k] == 0) continue;
    if (first < 0) first = k;
    if (root(k) != root(first)) {
      throw std::logic_error("room " + r.storey.rooms[k].name + " cannot be reached from room " +
                             r.storey.rooms[first].name + " through doors");
    }
  }
}

void drawStyle(RandomStyle style, Floor& floor, int rooms) {
  switch (style) {
    case RandomStyle::Office: return drawOffice(floor, rooms);
    case RandomStyle::Residential: return drawResidential(floor, rooms);
    case RandomStyle::School: return drawSchool(floor, rooms);
    case RandomStyle::Hall: return drawHall(floor, rooms);
    case RandomStyle::ApartmentBlock: return drawApartmentBlock(floor, rooms);
  }
}

struct Drawn {
  PlanGrid::Result result;
  std::vector<std::string> features;
  bool near_symmetric = false;
  int attempts = 0;
  int stair_room = -1;  // index into result.storey.rooms; -1: no stair
  StairWell well;
};

// The floor's stairwell: the style's own (apartment_block), else, for a building of several
// storeys, the first office a stair fits in. A floor without one is drawn again.
void findStair(const Floor& floor, RandomStyle style, int storeys, double storey_height_m, Drawn& d) {
  if (storeys <= 1 && floor.stair_room < 0) return;
  int room = floor.stair_room;
  if (room < 0) {
    room = roomForStair(d.result, style == RandomStyle::Office ? "Office" : "", storey_height_m);
    if (room < 0) throw LayoutConflict("no room for the stair");
    d.result.storey.rooms[static_cast<std::size_t>(room)].long_name = "Stair";
  }
  if (d.result.storey.rooms.at(static_cast<std::size_t>(room)).name != Floor::roomName(room))
    throw std::logic_error("the stairwell's label is not its room's index");
  const auto well = stairWellOf(d.result, room);
  if (!well || !fitHalfTurnStair(*well, storey_height_m, true, "probe")) throw LayoutConflict("the stair does not fit its well");
  d.stair_room = room;
  d.well = *well;
}

}  // namespace

const std::vector<std::string>& randomStyleNames() {
  static const std::vector<std::string> names = {"office", "residential", "school", "hall", "apartment_block"};
  return names;
}

bool randomStyleStacks(RandomStyle style) { return style == RandomStyle::Office || style == RandomStyle::ApartmentBlock; }

RandomStyle randomStyle(const std::string& name) {
  const auto& names = randomStyleNames();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) {
    throw std::invalid_argument("unknown style '" + name + "' (valid: office, residential, school, hall, apartment_block)");
  }
  return static_cast<RandomStyle>(it - names.begin());
}

std::string randomStyleName(RandomStyle style) { return randomStyleNames().at(static_cast<std::size_t>(style)); }

WorldSpec randomWorld(std::uint64_t seed, const RandomWorldOptions& options, RandomWorldInfo* info) {
  const std::string style = randomStyleName(options.style);
  const std::string where = "random world (seed " + std::to_string(seed) + ", style " + style + ")";
  if (options.storeys < 1 || options.storeys > kMaxRandomStoreys)
    throw std::invalid_argument(where + ": storeys must be 1 to " + std::to_string(kMaxRandomStoreys) + ", not " +
                                std::to_string(options.storeys));
  if (options.storeys > 1 && !randomStyleStacks(options.style))
    throw std::invalid_argument(where + ": only office and apartment_block stack into several storeys");
  try {
    // The building's constants come from their own stream, so redrawing the layout keeps them.
    Random constants(seed ^ 0x5bd1e9955bd1e995ULL);
    static const int kUsual[5][2] = {{12, 40}, {6, 30}, {10, 30}, {6, 20}, {12, 14}};
    const auto& usual = kUsual[static_cast<int>(options.style)];
    const int target = options.rooms > 0 ? options.rooms : static_cast<int>(constants.between(usual[0], usual[1]));
    const Mm exterior = constants.pick<Mm>({300, 340, 350, 400, 420, 450});
    const Mm storey_height = constants.steps(2800, 3500, 50), slab = constants.steps(200, 300, 10);
    const Mm roof = constants.steps(200, 300, 10), door_height = constants.steps(2000, 2100, 50);
    const bool space_boundaries = constants.percent(50);
    const double height_m = storey_height / 1000.0, roof_m = roof / 1000.0;

    // Draw until the layout fits together and, when asked for a size, has about that many rooms.
    std::optional<Drawn> best;
    int hint = target, draws = 0;
    const auto off = [&](const Drawn& d) { return std::abs(static_cast<int>(d.result.storey.rooms.size()) - target); };
    for (; draws < kMaxDraws; ++draws) {
      Random rng(seed ^ (0x9e3779b97f4a7c15ULL * static_cast<std::uint64_t>(draws)));
      Floor floor(rng, exterior);
      floor.door_height = door_height;
      floor.storey_height = storey_height;
      Drawn d;
      try {
        drawStyle(options.style, floor, hint);
        d.result = floor.grid.build("Ground floor", height_m, slab / 1000.0, height_m - roof_m);
        findStair(floor, options.style, options.storeys, height_m, d);
        // A floor exactly symmetric in its walls and doorways cannot be localized at all: not
        // the hard case we want. Draw again.
        for (const SymmetryMismatch& m : symmetryMismatches(d.result.storey))
          if (m.total() == 0) throw LayoutConflict("symmetric under " + m.symmetry);
      } catch (const LayoutConflict&) {
        continue;
      }
      d.features = floor.features;
      d.near_symmetric = floor.near_symmetric;
      d.attempts = draws + 1;
      const int rooms = static_cast<int>(d.result.storey.rooms.size());
      if (!best || off(d) < off(*best)) best = d;
      if (options.rooms == 0 || off(*best) <= std::max(1, target / 10)) break;
      hint = std::max(1, hint + (target - rooms) * hint / std::max(1, rooms));
    }
    if (!best) throw std::logic_error("no layout fitted together in " + std::to_string(kMaxDraws) + " draws");

    WorldSpec spec;
    spec.name = "random_" + style + "_" + std::to_string(seed) +
                (options.storeys > 1 ? "_" + std::to_string(options.storeys) + "storeys" : "");
    spec.roof_thickness_m = roof_m;
    spec.space_boundaries = space_boundaries;
    StoreySpec& storey = spec.storeys.emplace_back(best->result.storey);
    RandomWorldInfo out;
    out.features = best->features;
    out.near_symmetric = best->near_symmetric;
    out.attempts = best->attempts;
    for (std::size_t k = 0; k < storey.rooms.size(); ++k) {
      if (best->result.room_doors[k] > 0) continue;
      ++out.closed_rooms;
      std::string& use = storey.rooms[k].long_name;
      if (use.find("no door") == std::string::npos && use != "Shaft") use += " (no door)";
    }
    for (const WallSpec& w : storey.walls) out.free_walls += w.name.rfind("FREE-", 0) == 0 ? 1 : 0;
    if (out.closed_rooms > 0) out.features.push_back("closed rooms (no door): " + std::to_string(out.closed_rooms));
    spec.description = "Random " + style + " floor, seed " + std::to_string(seed);
    for (const std::string& feature : out.features) spec.description += "; " + feature;
    const auto mismatches = symmetryMismatches(storey);
    const auto closest = std::min_element(mismatches.begin(), mismatches.end(),
                                          [](const auto& a, const auto& b) { return a.total() < b.total(); });
    out.closest_symmetry = closest->symmetry;
    out.symmetry_mismatches = closest->total();
    checkReachable(best->result);
    if (best->stair_room >= 0) {
      out.stair_room = storey.rooms[static_cast<std::size_t>(best->stair_room)].name;
      const bool low = firstFlightOnLowSide(best->result, best->stair_room, best->well);
      stackStoreys(spec, options.storeys, best->well, low);
      if (options.storeys > 1) {
        const StairFlightSpec& f = spec.storeys[0].stairs.at(0).flights.at(0);
        const std::string feature = std::to_string(options.storeys) + " storeys; stair core " + out.stair_room +
                                    ": two flights of " + std::to_string(f.risers) + " risers a storey";
        out.features.push_back(feature);
        spec.description += "; " + feature;
      }
    }
    checkWorldSpec(spec);
    if (info) *info = out;
    return spec;
  } catch (const std::exception& e) {
    throw std::logic_error(where + ": generator bug: " + e.what());
  }
}

}  // namespace bimloc::worldgen
