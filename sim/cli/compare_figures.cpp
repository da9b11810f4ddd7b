// The figures of `bimloc compare`: the convergence-time table as bars, and each method's
// position error over time (the median over the runs, turn by turn: every run of a comparison
// has the same duration and lidar, so turn k is at the same time in each).
#include "sim/cli/compare_report.hpp"
#include "sim/cli/run_report.hpp"
#include "sim/render/compare_plots.hpp"
#include "sim/render/png_write.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace bimloc::cli {
namespace {

std::string planName(const CompareSetup& setup) { return std::filesystem::path(setup.plan).filename().string(); }

sim::BarChartData convergenceBars(const CompareSetup& setup, const std::vector<CompareRun>& runs) {
  sim::BarChartData data;
  char duration[32];
  std::snprintf(duration, sizeof duration, "%.0f s", setup.duration_s);
  data.title = "Convergence time: " + planName(setup) + ", " + setup.storey;
  data.value_label = "convergence time [s] (bars: each seed, by method)";
  data.series = setup.methods;
  data.value_max = setup.duration_s;
  data.missing_label = "N.L. (not localized in " + std::string(duration) + ")";
  // Group by start room; within a group, method by method, each seed's run.
  for (std::size_t i = 0; i < runs.size();) {
    std::size_t j = i;
    while (j < runs.size() && runs[j].room == runs[i].room) ++j;
    sim::BarChartData::Group group{runs[i].room, {}};
    for (std::size_t k = 0; k < setup.methods.size(); ++k)
      for (std::size_t r = i; r < j; ++r) {
        if (k >= runs[r].results.size()) continue;  // the run could not be made
        const sim::ScenarioResult& result = runs[r].results[k];
        group.bars.push_back({k, result.converged ? result.convergence_time_s : std::nullopt, result.false_convergence});
      }
    data.groups.push_back(std::move(group));
    i = j;
  }
  return data;
}

sim::CurvesData errorCurves(const CompareSetup& setup, const std::vector<CompareRun>& runs) {
  sim::CurvesData data;
  data.title = "Median position error: " + planName(setup) + ", " + setup.storey + " (" + std::to_string(runs.size()) +
               (runs.size() == 1 ? " run)" : " runs)");
  data.value_label = "position error [m]";
  for (std::size_t k = 0; k < setup.methods.size(); ++k) {
    sim::CurvesData::Curve curve{setup.methods[k], {}};
    for (std::size_t turn = 0;; ++turn) {
      std::vector<double> errors;
      double time_s = 0;
      bool any = false;
      for (const auto& run : runs)
        if (k < run.results.size() && turn < run.results[k].error_series.size()) {
          const auto& e = run.results[k].error_series[turn];
          time_s = e.time_s, any = true;
          if (std::isfinite(e.position_m)) errors.push_back(e.position_m);
        }
      if (!any) break;  // past every run's last turn
      curve.samples.emplace_back(time_s, errors.empty() ? std::nan("") : median(errors));
    }
    data.curves.push_back(std::move(curve));
  }
  return data;
}

}  // namespace

void writeCompareFigures(const CompareSetup& setup, const std::vector<CompareRun>& runs, const std::string& dir) {
  const auto bars = convergenceBars(setup, runs);
  sim::render::writePng(dir + "/convergence_times.png", [&] { return sim::renderBarChartImage(bars); });
  const auto curves = errorCurves(setup, runs);
  sim::render::writePng(dir + "/errors_over_time.png", [&] { return sim::renderCurvesImage(curves); });
}

}  // namespace bimloc::cli
