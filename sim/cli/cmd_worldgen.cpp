// bimloc worldgen NAME [--out PATH] | --all [--out DIR] | --list
//                 | --random SEED [--style S] [--rooms N] [--storeys N] [--random-count K] [--out PATH]
#include "sim/cli/commands.hpp"
#include "sim/common/atomic_file.hpp"
#include "sim/worldgen/ifc4_writer.hpp"
#include "sim/worldgen/random_world.hpp"
#include "sim/worldgen/worlds.hpp"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <iostream>
#include <stdexcept>

namespace {

namespace fs = std::filesystem;
using namespace bimloc::worldgen;

struct WorldgenArgs {
  std::string name;
  std::string out = ".";
  bool all = false;
  bool list = false;
  std::optional<std::uint64_t> random_seed;
  std::string style;  // empty: office, or cycling through the styles with --random-count
  int rooms = 0;
  int storeys = 1;
  int random_count = 0;
};

struct Generated {
  std::string path;
  WorldSpec spec;
  std::string note;  // appended to the summary line
};

std::string joinedNames() {
  std::string out;
  for (const std::string& n : worldNames()) out += (out.empty() ? "" : ", ") + n;
  return out;
}

std::string summary(const WorldSpec& spec) {
  std::size_t walls = 0, rooms = 0, doors = 0, stairs = 0, flights = 0;
  for (const StoreySpec& s : spec.storeys) {
    walls += s.walls.size();
    rooms += s.rooms.size();
    doors += s.doors.size();
    stairs += s.stairs.size();
    for (const StairSpec& stair : s.stairs) flights += stair.flights.size();
  }
  return std::to_string(spec.storeys.size()) + " storey(s), " + std::to_string(rooms) + " rooms, " +
         std::to_string(walls) + " walls, " + std::to_string(doors) + " doors" +
         (stairs > 0 ? ", " + std::to_string(stairs) + " stairs (" + std::to_string(flights) + " flights)" : "") +
         (spec.space_boundaries ? ", space boundaries" : ", no space boundaries");
}

// Every file is generated before the first is written: a bad spec writes nothing.
void writeAll(const std::vector<Generated>& worlds, const fs::path& directory) {
  std::vector<std::string> texts;
  for (const Generated& g : worlds) texts.push_back(writeIfc4(g.spec));
  if (!directory.empty()) {
    std::error_code ec;
    fs::create_directories(directory, ec);
    if (ec) throw std::runtime_error(directory.string() + ": cannot create directory: " + ec.message());
  }
  for (std::size_t i = 0; i < worlds.size(); ++i) {
    bimloc::sim::writeFileAtomically(worlds[i].path, texts[i]);
    std::cout << "wrote " << worlds[i].path << " (" << texts[i].size() << " bytes): " << summary(worlds[i].spec)
              << worlds[i].note << "\n";
  }
}

// --random SEED [--random-count K]: seeds SEED..SEED+K-1, with --style or cycling through the styles.
void runRandom(const WorldgenArgs& args) {
  if (args.all || !args.name.empty() || args.list) throw std::invalid_argument("--random takes no NAME, --all or --list");
  if (args.out.empty()) throw std::invalid_argument("--out is empty");
  const int count = std::max(1, args.random_count);
  const bool into_directory = args.random_count > 0 || fs::is_directory(args.out) || args.out.back() == '/';
  if (args.random_count > 0 && fs::exists(args.out) && !fs::is_directory(args.out)) {
    throw std::invalid_argument(args.out + ": not a directory");
  }
  const std::uint64_t first = *args.random_seed;
  const std::size_t first_style = args.style.empty() ? 0 : static_cast<std::size_t>(randomStyle(args.style));
  if (args.storeys > 1 && (args.style.empty() || !randomStyleStacks(static_cast<RandomStyle>(first_style))))
    throw std::invalid_argument("--storeys " + std::to_string(args.storeys) + " goes with --style office or apartment_block");
  std::vector<Generated> worlds;
  for (int k = 0; k < count; ++k) {
    RandomWorldOptions options;
    options.style = static_cast<RandomStyle>(args.style.empty() ? static_cast<std::size_t>(k) % kCycledRandomStyles
                                                                : first_style);
    options.rooms = args.rooms;
    options.storeys = args.storeys;
    RandomWorldInfo info;
    WorldSpec spec = randomWorld(first + static_cast<std::uint64_t>(k), options, &info);
    const std::string path = into_directory ? (fs::path(args.out) / (spec.name + ".ifc")).string() : args.out;
    std::string note;
    for (const std::string& f : info.features) note += "; " + f;
    note += "; closest symmetry: " + info.closest_symmetry + " (" + std::to_string(info.symmetry_mismatches) +
            " walls/doorways without a twin)";
    worlds.push_back({path, std::move(spec), note});
  }
  writeAll(worlds, into_directory ? fs::path(args.out) : fs::path(args.out).parent_path());
}

void run(const WorldgenArgs& args) {
  if (args.random_seed) return runRandom(args);
  if (!args.style.empty() || args.rooms > 0 || args.random_count > 0 || args.storeys > 1) {
    throw std::invalid_argument("--style, --rooms, --storeys and --random-count go with --random SEED");
  }
  if (args.list) {
    for (const std::string& n : worldNames()) {
      const WorldSpec spec = makeWorld(n);
      std::cout << n << (n == kDefaultWorld ? " (default)" : "") << ": " << spec.description << "; "
                << summary(spec) << "\n";
    }
    return;
  }
  if (args.all == !args.name.empty()) throw std::invalid_argument("give either a world NAME or --all (see --help)");
  if (args.out.empty()) throw std::invalid_argument("--out is empty");
  // With --all (or an existing directory, or a path ending in '/') --out is a directory that
  // receives NAME.ifc; otherwise it is the file itself.
  const bool into_directory = args.all || fs::is_directory(args.out) || args.out.back() == '/';
  if (args.all && fs::exists(args.out) && !fs::is_directory(args.out)) {
    throw std::invalid_argument(args.out + ": not a directory");
  }
  std::vector<Generated> worlds;
  for (const std::string& n : args.all ? worldNames() : std::vector<std::string>{args.name}) {
    worlds.push_back({into_directory ? (fs::path(args.out) / (n + ".ifc")).string() : args.out, makeWorld(n), ""});
  }
  writeAll(worlds, into_directory ? fs::path(args.out) : fs::path(args.out).parent_path());
}

}  // namespace

void addWorldgenCommand(CLI::App& app) {
  auto args = std::make_shared<WorldgenArgs>();
  CLI::App* cmd = app.add_subcommand(
      "worldgen",
      "Generate the project's synthetic buildings as IFC4 plans (STEP physical file): storeys,\n"
      "walls (axis + swept-solid body), floor and roof slabs, doors in openings, spaces and, for\n"
      "some worlds, IfcRelSpaceBoundary room<->wall relations. The same world always gives a\n"
      "byte-identical file; each file is written under a temporary name and renamed into place.\n"
      "  bimloc worldgen NAME [--out FILE|DIR]   one world (default: ./NAME.ifc)\n"
      "  bimloc worldgen --all --out DIR         every world, as DIR/NAME.ifc\n"
      "  bimloc worldgen --list                  the worlds, one line each\n"
      "Worlds: " +
          joinedNames() + "; the default world is " + kDefaultWorld +
          ".\n"
          "The committed plans in worlds/ are regenerated with: bimloc worldgen --all --out worlds\n"
          "Random floors, for sweeps of the localizer (sim/worldgen/random_world.hpp):\n"
          "  bimloc worldgen --random SEED [--style S] [--rooms N] [--storeys N] [--out FILE|DIR]\n"
          "      one floor (or building), DIR/random_STYLE_SEED.ifc in a directory (default: ./);\n"
          "      with --storeys N > 1, random_STYLE_SEED_Nstoreys.ifc\n"
          "  bimloc worldgen --random SEED --random-count K [--style S] [--rooms N] --out DIR\n"
          "      K floors, seeds SEED..SEED+K-1, cycling office, residential, school, hall unless --style\n"
          "  Styles: office (rows of identical offices on a straight, L or T corridor), residential\n"
          "  (identical apartments, every other mirrored), school (classrooms, assembly hall), hall (open\n"
          "  hall with free-standing walls, rooms opening into it), apartment_block (a stair core - lobby\n"
          "  and stairwell - with a flat on either side, the two flats mirror images: hall, living room,\n"
          "  kitchen, bathroom, one or two bedrooms; 12-14 rooms, --rooms is ignored). About half the\n"
          "  floors are drawn symmetric (rows turned 180 deg or mirrored, mirrored wings, mirrored flats)\n"
          "  and then changed in one small place (a door moved or missing, a wall moved, a short\n"
          "  free-standing wall): the case where a filter converges in the twin room; the other\n"
          "  apartment blocks keep twin flats and differ only in the core's doors. Some rooms have no\n"
          "  door (shafts, stores). Each line printed names the floor's rooms, walls, doors and hard\n"
          "  features. Same SEED, same bytes.\n"
          "  --storeys N (office, apartment_block): N identical floors 'storey height' apart (the same\n"
          "  walls, rooms and doors; the doors in the facade on the ground floor only; rooms and walls of\n"
          "  floor k named Sk-...), slabs between them, and a half-turn stair in the stair core from each\n"
          "  floor to the next: IfcStair decomposed into two IfcStairFlights (NumberOfRisers,\n"
          "  NumberOfTreads, RiserHeight, TreadLength, walking line, swept body of the steps) and an\n"
          "  IfcSlab .LANDING., the floor slab above voided (IfcOpeningElement) where the flights rise\n"
          "  through it. An office's stair takes the first office room deep enough for it.");
  cmd->add_option("name", args->name, "world to generate: " + joinedNames());
  cmd->add_flag("--all", args->all, "generate every world, as NAME.ifc in the --out directory");
  cmd->add_option("--out", args->out,
                  "output: with NAME, the .ifc file to write, or a directory (existing, or ending in '/') to\n"
                  "write NAME.ifc into; with --all or --random-count, the directory (created if missing).\n"
                  "Default: '.'");
  cmd->add_flag("--list", args->list, "list the worlds with a one-line description and exit");
  cmd->add_option("--random", args->random_seed, "generate a random floor from this seed (see above)");
  cmd->add_option("--style", args->style, "with --random: office, residential, school, hall or apartment_block\n"
                                          "(default: office; with --random-count, cycling through the first four)")
      ->check(CLI::IsMember(randomStyleNames()));
  cmd->add_option("--rooms", args->rooms, "with --random: about this many rooms (default: the style's usual size)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--storeys", args->storeys,
                  "with --random and --style office or apartment_block: this many storeys joined by stairs\n"
                  "(default: 1, no stairs)")
      ->check(CLI::Range(1, kMaxRandomStoreys));
  cmd->add_option("--random-count", args->random_count, "with --random: this many floors, seeds SEED, SEED+1, ...")
      ->check(CLI::Range(1, 100000));
  cmd->callback([args] { run(*args); });
}
