// bimloc extract PLAN.ifc [--out DIR] [--json]
#include "sim/cli/commands.hpp"
#include "sim/cli/table.hpp"
#include "sim/world/plan_export.hpp"

#include <bimloc/bim/building_json.hpp>
#include <bimloc/bim/ifc_reader.hpp>

#include <chrono>
#include <iostream>

namespace {

struct ExtractArgs {
  std::string plan;
  std::string out;
  bool json = false;
  bool infer_rooms = false;
};

// A storey's name for the stairs table, cut to keep the table within 100 columns; "landing"
// for a flight's end between storeys.
std::string storeyLabel(const bimloc::bim::Building& b, int s) {
  if (s < 0 || s >= static_cast<int>(b.storeys.size())) return "landing";
  const std::string name = b.storeyLabel(static_cast<std::size_t>(s));
  return name.size() <= 16 ? name : name.substr(0, 15) + "~";
}

// One row per flight: where it goes, its steps and where the numbers came from.
void printStairs(const bimloc::bim::Building& b) {
  using bimloc::cli::fixed;
  if (b.stairs.empty()) {
    std::cout << "\nno stairs or ramps read\n";
    return;
  }
  std::cout << "\n" << b.stairs.size() << " stair flight(s):\n";
  bimloc::cli::Table table({"#", "class", "from", "to", "risers", "riser [m]", "going [m]", "width [m]", "source"});
  for (std::size_t i = 0; i < b.stairs.size(); ++i) {
    const auto& f = b.stairs[i];
    table.add({std::to_string(i + 1), f.ifc_type, storeyLabel(b, f.bottom_storey), storeyLabel(b, f.top_storey),
               std::to_string(f.risers), fixed(f.riser_height_m, 3), fixed(f.going_m, 3), fixed(f.width_m, 2),
               f.source});
  }
  table.print(std::cout);
}

void printReport(const bimloc::bim::Building& b, double seconds, const std::vector<std::string>& files,
                 const std::string& out) {
  using bimloc::cli::fixed;
  std::cout << b.file << " (" << b.schema << "), extracted in " << fixed(seconds, 2) << " s\n\n";
  bimloc::cli::Table table({"storey", "elevation [m]", "rooms", "walls", "wall planes", "mesh triangles"});
  for (std::size_t i = 0; i < b.storeys.size(); ++i) {
    const auto& s = b.storeys[i];
    table.add({b.storeyLabel(i), fixed(s.elevation_m, 2), std::to_string(s.rooms.size()), std::to_string(s.walls.size()),
               std::to_string(s.wallPlaneCount()), std::to_string(s.mesh.triangles.size())});
  }
  table.print(std::cout);
  printStairs(b);
  if (!b.warnings.empty()) {
    std::cout << "\n" << b.warnings.size() << " warning(s):\n";
    for (const auto& w : b.warnings) std::cout << "  - " << w << "\n";
  }
  if (!files.empty()) {
    std::cout << "\nwrote to " << out << ":";
    for (const auto& f : files) std::cout << " " << f;
    std::cout << "\n";
  }
}

void run(const ExtractArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  bimloc::bim::ExtractOptions options;
  options.infer_rooms = args.infer_rooms;
  const bimloc::bim::Building building = bimloc::bim::readIfc(args.plan, options);
  std::vector<std::string> files;
  if (!args.out.empty()) files = bimloc::sim::exportPlan(building, args.out);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (args.json)
    std::cout << bimloc::bim::extractionSummary(building, seconds).dump() << "\n";
  else
    printReport(building, seconds, files, args.out);
}

}  // namespace

void addExtractCommand(CLI::App& app) {
  auto args = std::make_shared<ExtractArgs>();
  CLI::App* cmd = app.add_subcommand(
      "extract",
      "Read an IFC plan (IFC2X3, IFC4 or IFC4X3) and extract its storeys, rooms (IfcSpace) and walls as double-sided\n"
      "planes with the room<->wall topology: the top two layers of a Situational Graph.\n"
      "With --out DIR it writes building.json (the whole model), walls.csv (one row per wall face:\n"
      "id, start point, normal, length, thickness, d) and one binary PLY mesh per storey for the simulator\n"
      "(every physical element, floor and ceiling included, world frame, metres). Files appear all or none.");
  cmd->add_option("plan", args->plan, "IFC file (STEP physical file, .ifc)")->required();
  cmd->add_option("--out", args->out, "directory to write building.json, walls.csv and the storey meshes into");
  cmd->add_flag("--json", args->json, "print one JSON summary object on stdout instead of the table");
  cmd->add_flag("--infer-rooms", args->infer_rooms,
                "infer every storey's rooms from its walls, dropping its IfcSpace rooms (to compare the two;\n"
                "a storey with walls and no IfcSpace always gets inferred rooms)");
  cmd->callback([args] { run(*args); });
}
