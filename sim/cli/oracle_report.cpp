#include "sim/cli/oracle_report.hpp"

#include "sim/cli/sweep_summary.hpp"
#include "sim/cli/table.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>

namespace bimloc::cli {

namespace {

// decidable_at_s, decision_lag_s and decision_ratio (or their `_robust` forms: `suffix`) from one
// of the oracle's answers.
void addLimit(nlohmann::json& entry, const sim::ScenarioResult& r, const std::optional<double>& decidable_at_s,
              const std::string& suffix) {
  entry["decidable" + suffix + "_at_s"] = decidable_at_s ? nlohmann::json(*decidable_at_s) : nlohmann::json(nullptr);
  // The localizer's time beyond the limit, for a run it localized (a false one has no lag).
  const bool localized = r.converged && !r.false_convergence && r.convergence_time_s;
  if (localized && decidable_at_s) {
    entry["decision_lag" + suffix + "_s"] = *r.convergence_time_s - *decidable_at_s;
    // A start decidable from its first scan must not make the ratio explode: at least 1 s.
    entry["decision_ratio" + suffix] = *r.convergence_time_s / std::max(*decidable_at_s, 1.0);
  } else {
    entry["decision_lag" + suffix + "_s"] = nullptr, entry["decision_ratio" + suffix] = nullptr;
  }
}

// Over the entries that carry the fields of one answer (`suffix`: "" or "_robust"): how many
// were decidable, how many of those localized, the lags' and ratios' median and p90.
nlohmann::json limitSummary(const nlohmann::json& scenarios, const std::string& suffix) {
  int decidable = 0, decidable_localized = 0;
  std::vector<double> lags, ratios;
  const std::string at = "decidable" + suffix + "_at_s", lag = "decision_lag" + suffix + "_s", ratio = "decision_ratio" + suffix;
  for (const auto& s : scenarios) {
    if (!s.contains("oracle") || !s.contains(at) || s[at].is_null()) continue;
    ++decidable;
    decidable_localized += s["converged"].get<bool>() && !s["false_convergence"].get<bool>();
    if (!s[lag].is_null()) lags.push_back(s[lag].get<double>());
    if (!s[ratio].is_null()) ratios.push_back(s[ratio].get<double>());
  }
  const auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"decidable" + suffix, decidable}, {"decidable" + suffix + "_localized", decidable_localized},
          {"median_" + lag, num(quantile(lags, 0.5))}, {"p90_" + lag, num(quantile(lags, 0.9))},
          {"median_" + ratio, num(quantile(ratios, 0.5))}, {"p90_" + ratio, num(quantile(ratios, 0.9))}};
}

}  // namespace

void addOracleFields(nlohmann::json& entry, const sim::ScenarioResult& r) {
  if (!r.oracle) return;
  const auto& o = *r.oracle;
  addLimit(entry, r, o.decidable_at_s, "");
  addLimit(entry, r, o.decidable_robust_at_s, "_robust");
  entry["oracle"] = {{"threshold", o.threshold}, {"rival_places", o.rival_places}, {"seconds", o.seconds},
                     {"keyframes", o.keyframes}, {"checks", o.checks}, {"points", o.points},
                     {"nodes", o.nodes}, {"cells", o.cells}, {"cpu_seconds", o.cpu_seconds},
                     {"truth_ruled_out", o.truth_ruled_out},
                     {"robust_seconds", o.robust_seconds}, {"robust_cpu_seconds", o.robust_cpu_seconds},
                     {"robust_checks", o.robust_checks}, {"robust_nodes", o.robust_nodes}, {"robust_cells", o.robust_cells}};
}

bool hasOracle(const nlohmann::json& scenarios) {
  return std::any_of(scenarios.begin(), scenarios.end(), [](const nlohmann::json& s) { return s.contains("oracle"); });
}

nlohmann::json oracleSummary(const nlohmann::json& scenarios) {
  int runs = 0, robust_runs = 0, truth_ruled_out = 0;
  std::vector<double> seconds;
  double cpu = 0, robust_cpu = 0;
  for (const auto& s : scenarios) {
    if (!s.contains("oracle")) continue;
    ++runs;
    seconds.push_back(s["oracle"]["seconds"].get<double>());
    truth_ruled_out += s["oracle"].value("truth_ruled_out", false);
    // Entries of a binary without the robust answer have neither its fields nor its cost.
    if (!s.contains("decidable_robust_at_s")) continue;
    ++robust_runs;
    cpu += s["oracle"].value("cpu_seconds", 0.0), robust_cpu += s["oracle"].value("robust_cpu_seconds", 0.0);
  }
  const auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  double total = 0;
  for (double v : seconds) total += v;
  nlohmann::json summary = {{"oracle_runs", runs}, {"oracle_seconds", total}, {"median_oracle_seconds", num(quantile(seconds, 0.5))},
                            {"max_oracle_seconds", num(quantile(seconds, 1.0))}, {"truth_ruled_out", truth_ruled_out}};
  summary.update(limitSummary(scenarios, ""));
  if (robust_runs == 0) return summary;
  summary.update(limitSummary(scenarios, "_robust"));
  // The robust answer's cost against the plain one's, CPU of the oracle's thread in the same runs.
  summary.update({{"robust_oracle_runs", robust_runs}, {"oracle_cpu_seconds", cpu}, {"robust_oracle_cpu_seconds", robust_cpu}});
  return summary;
}

void printOracleSummary(const nlohmann::json& s, std::ostream& out_stream) {
  // Each sentence on its lines, broken to the tables' width.
  std::ostringstream out;
  const auto flush = [&] {
    out_stream << wrapText(out.str(), kTableColumns);
    out.str(std::string());
  };
  out << "oracle: " << s["decidable"].get<int>() << " of " << s["oracle_runs"].get<int>() << " decidable, "
      << s["decidable_localized"].get<int>() << " of them localized; decision lag median " << cell(s["median_decision_lag_s"], 1)
      << " s, p90 " << cell(s["p90_decision_lag_s"], 1) << " s; ratio median " << cell(s["median_decision_ratio"], 2) << ", p90 "
      << cell(s["p90_decision_ratio"], 2) << "; oracle " << cell(s["median_oracle_seconds"], 1) << " s per run (median), "
      << fixed(s["oracle_seconds"].get<double>(), 0) << " s in all";
  flush();
  // The plain model's limit is no bar where it rules the true place out (docs/oracle.md).
  if (s.value("truth_ruled_out", 0) > 0) {
    out << "oracle: in " << s["truth_ruled_out"].get<int>() << " run(s) its scans rule the TRUE place out: the site is not its plan "
        << "within the plain model's noise";
    flush();
  }
  if (!s.contains("decidable_robust")) return;
  out << "oracle, one deviation allowed: " << s["decidable_robust"].get<int>() << " decidable, "
      << s["decidable_robust_localized"].get<int>() << " of them localized; decision lag median "
      << cell(s["median_decision_lag_robust_s"], 1) << " s, p90 " << cell(s["p90_decision_lag_robust_s"], 1) << " s; ratio median "
      << cell(s["median_decision_ratio_robust"], 2) << ", p90 " << cell(s["p90_decision_ratio_robust"], 2) << "; CPU "
      << fixed(s["robust_oracle_cpu_seconds"].get<double>(), 1) << " s beside the plain answer's "
      << fixed(s["oracle_cpu_seconds"].get<double>(), 1) << " s";
  flush();
}

}  // namespace bimloc::cli
