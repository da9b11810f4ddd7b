#include "sim/cli/sweep_summary.hpp"

#include "sim/cli/oracle_report.hpp"
#include "sim/cli/run_report.hpp"
#include "sim/cli/table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bimloc::cli {

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const double at = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(at);
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (at - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

nlohmann::json summariseRuns(const std::vector<const sim::ScenarioResult*>& runs) {
  int localized = 0, false_conv = 0, errors = 0, losses = 0;
  std::vector<double> times, ates, margins, rpes, map_rmses, paths;
  for (const sim::ScenarioResult* r : runs) {
    localized += r->converged && !r->false_convergence;
    false_conv += r->false_convergence;
    errors += !r->failures.empty() && r->sim_seconds == 0;
    if (r->converged && r->convergence_time_s) times.push_back(*r->convergence_time_s);
    if (r->ate_m) ates.push_back(*r->ate_m);
    if (r->rpe_m_per_m) rpes.push_back(*r->rpe_m_per_m);
    if (r->map_rmse_m) map_rmses.push_back(*r->map_rmse_m);
    paths.push_back(r->path_length_m);
    losses += r->losses;
    if (r->convergence_margin) margins.push_back(*r->convergence_margin);
  }
  const auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  nlohmann::json summary{{"runs", runs.size()}, {"localized", localized}, {"false_convergences", false_conv},
          {"errors", errors}, {"median_convergence_s", num(quantile(times, 0.5))}, {"p90_convergence_s", num(quantile(times, 0.9))},
          {"max_convergence_s", num(quantile(times, 1.0))}, {"median_ate_m", num(quantile(ates, 0.5))},
          {"max_ate_m", num(quantile(ates, 1.0))}, {"median_rpe_m_per_m", num(quantile(rpes, 0.5))},
          {"median_map_rmse_m", num(quantile(map_rmses, 0.5))}, {"losses", losses},
          {"median_path_length_m", num(quantile(paths, 0.5))},
          {"min_accepted_margin", num(margins.empty() ? std::nan("") : *std::min_element(margins.begin(), margins.end()))}};
  // With --oracle: the information limit's figures, from the runs' entries as `run` reports them.
  nlohmann::json entries = nlohmann::json::array();
  for (const sim::ScenarioResult* r : runs)
    if (r->oracle) entries.push_back(scenarioJson(*r));
  if (!entries.empty()) summary.update(oracleSummary(entries));
  return summary;
}

std::string cell(const nlohmann::json& v, int decimals) { return v.is_null() ? "-" : fixed(v.get<double>(), decimals); }

}  // namespace bimloc::cli
