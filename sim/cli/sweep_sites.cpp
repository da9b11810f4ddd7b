#include "sim/cli/sweep_sites.hpp"

#include "sim/cli/run_report.hpp"
#include "sim/cli/sweep_summary.hpp"
#include "sim/cli/table.hpp"
#include "sim/render/robustness_plot.hpp"

#include <chrono>
#include <cmath>
#include <iostream>

namespace bimloc::cli {
namespace {

// The deviation level of a preset: how far its walls may stand off their drawn place.
double deviationM(const std::string& site) { return sim::sitePreset(site).walls.max_offset_m; }

double number(const nlohmann::json& v) { return v.is_null() ? std::nan("") : v.get<double>(); }

}  // namespace

int runRobustness(const std::vector<sim::Scenario>& base, WorldCache& worlds, const RobustnessOptions& o) {
  std::vector<sim::Scenario> scenarios;
  for (const auto& site : o.sites)
    for (const auto& method : o.methods)
      for (sim::Scenario s : base) {
        s.site = sim::sitePreset(site);
        s.localizer["method"] = method;
        s.name += " [" + site + ", " + method + "]";
        scenarios.push_back(std::move(s));
      }
  const auto start = std::chrono::steady_clock::now();
  RunPoolOptions pool;
  pool.jobs = o.jobs, pool.progress_label = "sweeping " + std::to_string(scenarios.size()) + " runs";
  pool.oracle = o.oracle;
  const auto runs = runPool(scenarios, std::vector<bool>(scenarios.size(), true), worlds, pool);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  nlohmann::json rows = nlohmann::json::array();
  sim::RobustnessPlotData plot;
  plot.title = o.title;
  for (const auto& site : o.sites)
    plot.levels.push_back(site + " (" + fixed(100.0 * deviationM(site), 0) + " cm)");
  for (const auto& method : o.methods) plot.series.push_back({method, {}, {}});
  int false_total = 0;
  std::size_t at = 0;
  for (const auto& site : o.sites)
    for (std::size_t m = 0; m < o.methods.size(); ++m) {
      std::vector<const sim::ScenarioResult*> group;
      for (std::size_t k = 0; k < base.size(); ++k) group.push_back(&runs[at++].result);
      nlohmann::json row{{"site", site}, {"deviation_m", deviationM(site)}, {"method", o.methods[m]}};
      row.update(summariseRuns(group));
      const double n = runsThatRan(row);  // a start that could not be run is no run
      row["rate"] = n > 0 ? row["localized"].get<double>() / n : 0.0;
      false_total += row["false_convergences"].get<int>();
      plot.series[m].rate.push_back(n > 0 ? row["rate"].get<double>() : std::nan(""));
      plot.series[m].ate_m.push_back(number(row["median_ate_m"]));
      rows.push_back(row);
    }
  if (!o.plot.empty()) sim::renderRobustnessPlot(plot, o.plot);
  if (o.json) {
    std::vector<sim::ScenarioResult> results;
    for (const auto& r : runs) results.push_back(r.result);
    std::cout << nlohmann::json{{"sites", o.sites}, {"methods", o.methods}, {"rows", rows}, {"wall_seconds", wall},
                                {"plot", o.plot.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.plot)},
                                {"scenarios", runReport(results, wall)["scenarios"]}}
                     .dump()
              << "\n";
  } else {
    std::vector<std::string> header{"site", "deviation [m]", "method", "runs", "localized", "rate", "false", "median [s]",
                                    "p90 [s]", "median ATE [m]", "lost"};
    // With --oracle: the same columns as the plain sweep's (decidable starts, the lag and the ratio).
    if (o.oracle) header.insert(header.end(), {"decidable", "dec. localized", "lag [s]", "ratio", "oracle [s/run]"});
    Table table(header);
    for (const auto& r : rows) {
      std::vector<std::string> row{r["site"], fixed(r["deviation_m"].get<double>(), 2), r["method"],
                                   std::to_string(runsThatRan(r)), std::to_string(r["localized"].get<int>()),
                                   fixed(r["rate"].get<double>(), 2),
                                   r["false_convergences"].get<int>() ? "FALSE " + std::to_string(r["false_convergences"].get<int>()) : "0",
                                   cell(r["median_convergence_s"], 1), cell(r["p90_convergence_s"], 1), cell(r["median_ate_m"], 3),
                                   std::to_string(r["losses"].get<int>())};
      if (o.oracle) {
        const bool any = r.contains("decidable");  // no run of the row had an oracle (none ran)
        row.insert(row.end(), {any ? std::to_string(r["decidable"].get<int>()) : "-",
                               any ? std::to_string(r["decidable_localized"].get<int>()) : "-",
                               any ? cell(r["median_decision_lag_s"], 1) + " / " + cell(r["p90_decision_lag_s"], 1) : "-",
                               any ? cell(r["median_decision_ratio"], 2) + " / " + cell(r["p90_decision_ratio"], 2) : "-",
                               any ? cell(r["median_oracle_seconds"], 1) : "-"});
      }
      table.add(row);
    }
    table.print(std::cout);
    std::size_t not_run = 0;
    for (const auto& r : runs) not_run += !r.error.empty();
    std::cout << "\n" << scenarios.size() - not_run << " runs, " << false_total << " false convergences; " << fixed(wall, 0) << " s"
              << (not_run > 0 ? "; " + std::to_string(not_run) + (not_run == 1 ? " start" : " starts") + " could not be run (below)" : "")
              << (o.plot.empty() ? "" : "; plot: " + o.plot) << "\n";
  }
  for (const auto& r : runs)
    if (!r.error.empty()) std::cerr << "bimloc sweep: not run: " << r.result.name << ": " << r.error << "\n";
  return false_total;
}

}  // namespace bimloc::cli
