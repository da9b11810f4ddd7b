// The results of `bimloc compare`: the paper's two tables (convergence time, and ATE after
// convergence, per start room and method) as one JSON object, as terminal tables, and as
// figures (a bar chart of the convergence times, the position error over time per method).
#pragma once

#include "sim/runner/run_scenario.hpp"

#include <nlohmann/json.hpp>

#include <ostream>
#include <string>
#include <vector>

namespace bimloc::cli {

struct CompareSetup {
  std::string plan, storey, site = "exact";
  double duration_s = 0;
  int seeds = 1;
  std::vector<std::string> methods;
};

// One simulated run (a start room and a seed) and what each method made of it.
struct CompareRun {
  std::string room, name;
  std::uint64_t seed = 0;
  std::vector<sim::ScenarioResult> results;  // one per method, in CompareSetup::methods' order; empty on error
  std::string error;                         // the run could not be made at all
  // Per method, as results: its pictures (snapshots, then errors.png), paths relative to the
  // output folder; none without --out.
  std::vector<std::vector<std::string>> pictures;
};

// {"format": "bimloc.compare", "version": 1, plan, storey, site, duration_s, seeds, methods,
//  "rooms": [{"room", "runs": [{"seed", "name", "error", "methods": {METHOD: {converged,
//  convergence_time_s, false_convergence, ate_m, ..., pictures}}}]}], "summary": {METHOD: {runs,
//  localized, false_convergences, median_convergence_s, median_ate_m, losses}}, "errors",
//  "timing": {wall_seconds, sim_seconds, localizer_seconds: {METHOD: s}}}. Everything but
//  "timing" is the same for the same input, whatever the number of jobs.
nlohmann::json compareReport(const CompareSetup& setup, const std::vector<CompareRun>& runs, double wall_seconds);

// The convergence-time and ATE tables per start room, the table per method (the best in each
// column marked), the verdict and what the marks mean: within kTableColumns (table.hpp) columns (the
// tables split into blocks of methods, the plan by its file name); `wide`: each table whole,
// the plan's path, and the position error at the end of each run too.
void printCompareTables(const nlohmann::json& report, std::ostream& out, bool wide = false);

// DIR/convergence_times.png and DIR/errors_over_time.png (the median over the runs of each
// method's position error at each turn), each written atomically.
void writeCompareFigures(const CompareSetup& setup, const std::vector<CompareRun>& runs, const std::string& dir);

}  // namespace bimloc::cli
