#include "sim/cli/oracle_report.hpp"

#include "sim/cli/sweep_summary.hpp"
#include "sim/cli/table.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::cli {

void addOracleFields(nlohmann::json& entry, const sim::ScenarioResult& r) {
  if (!r.oracle) return;
  const auto& o = *r.oracle;
  entry["decidable_at_s"] = o.decidable_at_s ? nlohmann::json(*o.decidable_at_s) : nlohmann::json(nullptr);
  // The localizer's time beyond the limit, for a run it localized (a false one has no lag).
  const bool localized = r.converged && !r.false_convergence && r.convergence_time_s;
  if (localized && o.decidable_at_s) {
    entry["decision_lag_s"] = *r.convergence_time_s - *o.decidable_at_s;
    // A start decidable from its first scan must not make the ratio explode: at least 1 s.
    entry["decision_ratio"] = *r.convergence_time_s / std::max(*o.decidable_at_s, 1.0);
  } else {
    entry["decision_lag_s"] = nullptr, entry["decision_ratio"] = nullptr;
  }
  entry["oracle"] = {{"threshold", o.threshold}, {"rival_places", o.rival_places}, {"seconds", o.seconds},
                     {"keyframes", o.keyframes}, {"checks", o.checks}, {"points", o.points},
                     {"nodes", o.nodes}, {"cells", o.cells}};
}

bool hasOracle(const nlohmann::json& scenarios) {
  return std::any_of(scenarios.begin(), scenarios.end(), [](const nlohmann::json& s) { return s.contains("oracle"); });
}

nlohmann::json oracleSummary(const nlohmann::json& scenarios) {
  int runs = 0, decidable = 0, decidable_localized = 0;
  std::vector<double> lags, ratios, seconds;
  for (const auto& s : scenarios) {
    if (!s.contains("oracle")) continue;
    ++runs;
    seconds.push_back(s["oracle"]["seconds"].get<double>());
    if (s["decidable_at_s"].is_null()) continue;
    ++decidable;
    decidable_localized += s["converged"].get<bool>() && !s["false_convergence"].get<bool>();
    if (!s["decision_lag_s"].is_null()) lags.push_back(s["decision_lag_s"].get<double>());
    if (!s["decision_ratio"].is_null()) ratios.push_back(s["decision_ratio"].get<double>());
  }
  const auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  double total = 0;
  for (double v : seconds) total += v;
  return {{"oracle_runs", runs}, {"decidable", decidable}, {"decidable_localized", decidable_localized},
          {"median_decision_lag_s", num(quantile(lags, 0.5))}, {"p90_decision_lag_s", num(quantile(lags, 0.9))},
          {"median_decision_ratio", num(quantile(ratios, 0.5))}, {"p90_decision_ratio", num(quantile(ratios, 0.9))},
          {"oracle_seconds", total}, {"median_oracle_seconds", num(quantile(seconds, 0.5))},
          {"max_oracle_seconds", num(quantile(seconds, 1.0))}};
}

void printOracleSummary(const nlohmann::json& s, std::ostream& out) {
  out << "oracle: " << s["decidable"].get<int>() << " of " << s["oracle_runs"].get<int>() << " decidable, "
      << s["decidable_localized"].get<int>() << " of them localized; decision lag median " << cell(s["median_decision_lag_s"], 1)
      << " s, p90 " << cell(s["p90_decision_lag_s"], 1) << " s; ratio median " << cell(s["median_decision_ratio"], 2) << ", p90 "
      << cell(s["p90_decision_ratio"], 2) << "; oracle " << cell(s["median_oracle_seconds"], 1) << " s per run (median), "
      << fixed(s["oracle_seconds"].get<double>(), 0) << " s in all\n";
}

}  // namespace bimloc::cli
