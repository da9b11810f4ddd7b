// bimloc worldgen NAME [--out PATH] | --all [--out DIR] | --list
#include "sim/cli/commands.hpp"
#include "sim/world/atomic_file.hpp"
#include "sim/worldgen/ifc4_writer.hpp"
#include "sim/worldgen/worlds.hpp"

#include <filesystem>
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
};

std::string joinedNames() {
  std::string out;
  for (const std::string& n : worldNames()) out += (out.empty() ? "" : ", ") + n;
  return out;
}

std::string summary(const WorldSpec& spec) {
  std::size_t walls = 0, rooms = 0, doors = 0;
  for (const StoreySpec& s : spec.storeys) {
    walls += s.walls.size();
    rooms += s.rooms.size();
    doors += s.doors.size();
  }
  return std::to_string(spec.storeys.size()) + " storey(s), " + std::to_string(rooms) + " rooms, " +
         std::to_string(walls) + " walls, " + std::to_string(doors) + " doors" +
         (spec.space_boundaries ? ", space boundaries" : ", no space boundaries");
}

void run(const WorldgenArgs& args) {
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
  // Every file is generated before the first is written: a bad spec writes nothing.
  std::vector<std::pair<std::string, WorldSpec>> worlds;
  for (const std::string& n : args.all ? worldNames() : std::vector<std::string>{args.name}) {
    worlds.emplace_back(into_directory ? (fs::path(args.out) / (n + ".ifc")).string() : args.out, makeWorld(n));
  }
  std::vector<std::string> texts;
  for (const auto& [path, spec] : worlds) texts.push_back(writeIfc4(spec));
  const fs::path directory = into_directory ? fs::path(args.out) : fs::path(args.out).parent_path();
  if (!directory.empty()) {
    std::error_code ec;
    fs::create_directories(directory, ec);
    if (ec) throw std::runtime_error(directory.string() + ": cannot create directory: " + ec.message());
  }
  for (std::size_t i = 0; i < worlds.size(); ++i) {
    bimloc::sim::writeFileAtomically(worlds[i].first, texts[i]);
    std::cout << "wrote " << worlds[i].first << " (" << texts[i].size() << " bytes): " << summary(worlds[i].second)
              << "\n";
  }
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
          "The committed plans in worlds/ are regenerated with: bimloc worldgen --all --out worlds");
  cmd->add_option("name", args->name, "world to generate: " + joinedNames());
  cmd->add_flag("--all", args->all, "generate every world, as NAME.ifc in the --out directory");
  cmd->add_option("--out", args->out,
                  "output: with NAME, the .ifc file to write, or a directory (existing, or ending in '/') to\n"
                  "write NAME.ifc into; with --all, the directory (created if missing). Default: '.'");
  cmd->add_flag("--list", args->list, "list the worlds with a one-line description and exit");
  cmd->callback([args] { run(*args); });
}
