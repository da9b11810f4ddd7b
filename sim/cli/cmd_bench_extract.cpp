// bimloc bench extract [PLAN...] [--repeat N] [--json]
// Extraction time per plan, split into IFC parse, geometry conversion (both IFC++), the
// model (walls, rooms, topology, meshes: ours) and export, with the share of the total that
// is ours against the IFC++ floor measured in the same run.
#include "sim/cli/commands.hpp"
#include "sim/cli/progress.hpp"
#include "sim/cli/table.hpp"
#include "sim/world/plan_export.hpp"

#include <bimloc/bim/ifc_reader.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <unistd.h>
#include <nlohmann/json.hpp>

namespace {
namespace fs = std::filesystem;

struct BenchArgs {
  std::vector<std::string> plans;
  int repeat = 3;
  bool json = false;
};

struct Sample {
  double parse_s, geometry_s, model_s, export_s, total_s;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::vector<std::string> defaultPlans() {
  std::vector<std::string> plans;
  for (const char* dir : {"../shared/ifc", "worlds"}) {
    if (!fs::is_directory(dir)) continue;
    std::vector<std::string> found;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".ifc") found.push_back(e.path().string());
    std::sort(found.begin(), found.end());
    plans.insert(plans.end(), found.begin(), found.end());
  }
  return plans;
}

Sample measure(const std::string& plan) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const auto building = bimloc::bim::readIfc(plan);
  const auto t1 = Clock::now();
  const fs::path tmp = fs::temp_directory_path() / ("bimloc-bench-" + std::to_string(::getpid()));
  bimloc::sim::exportPlan(building, tmp.string());
  const auto t2 = Clock::now();
  fs::remove_all(tmp);
  const auto& t = building.times;
  return {t.parse_s, t.geometry_s, t.model_s, std::chrono::duration<double>(t2 - t1).count(),
          std::chrono::duration<double>(t2 - t0).count()};
}

void run(BenchArgs args) {
  if (args.plans.empty()) args.plans = defaultPlans();
  if (args.plans.empty()) throw std::runtime_error("no plans given and none found in ../shared/ifc or worlds/");
  nlohmann::json rows = nlohmann::json::array();
  bimloc::cli::Table table({"plan", "parse [s]", "geometry [s]", "model [s]", "export [s]", "total [s]", "IFC++"});
  {
    // A bar on a terminal only (a "measuring ...\r" line ran into the table in a log), its line
    // cleared when it goes, before the table.
    bimloc::cli::Progress progress("bench extract");
    for (const auto& plan : args.plans) {
      progress.update(rows.size(), args.plans.size());
      std::vector<double> parse, geometry, model, exp, total;
      for (int r = 0; r < std::max(1, args.repeat); ++r) {
        const Sample s = measure(plan);
        parse.push_back(s.parse_s), geometry.push_back(s.geometry_s), model.push_back(s.model_s);
        exp.push_back(s.export_s), total.push_back(s.total_s);
      }
      const double p = median(parse), g = median(geometry), m = median(model), e = median(exp), t = median(total);
      const double share = (p + g) / t;  // the IFC++ reference: what reading the file alone costs
      rows.push_back({{"plan", plan}, {"parse_s", p}, {"geometry_s", g}, {"model_s", m}, {"export_s", e},
                      {"total_s", t}, {"ifcpp_share", share}, {"under_2s", t < 2.0}});
      using bimloc::cli::fixed;
      table.add({fs::path(plan).filename().string(), fixed(p, 3), fixed(g, 3), fixed(m, 3), fixed(e, 3), fixed(t, 3),
                 fixed(100 * share, 0) + " %"});
    }
  }
  if (args.json) {
    std::cout << nlohmann::json{{"repeat", args.repeat}, {"plans", rows}}.dump() << "\n";
  } else {
    table.print(std::cout);
    std::cout << "(median of " << args.repeat << " runs, one thread; IFC++: its share, (parse + geometry) / total)\n";
  }
}

}  // namespace

void addBenchExtractCommand(CLI::App& bench) {
  auto args = std::make_shared<BenchArgs>();
  CLI::App* extract = bench.add_subcommand(
      "extract", "Extraction time per plan: IFC parse, geometry, model, export (default: ../shared/ifc/*.ifc and worlds/*.ifc).");
  extract->add_option("plans", args->plans, "IFC files to measure");
  extract->add_option("--repeat", args->repeat, "runs per plan (the median is reported)")->check(CLI::Range(1, 100));
  extract->add_flag("--json", args->json, "print one JSON object");
  extract->callback([args] { run(*args); });
}
