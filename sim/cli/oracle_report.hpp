// The oracle's part of `bimloc run --oracle` and `bimloc sweep --oracle` (docs/oracle.md): per
// run when the scans first allowed a decision and how long the localizer took beyond it, and
// per group of runs how many were decidable and the lags' and ratios' quantiles.
#pragma once

#include "sim/runner/run_scenario.hpp"

#include <nlohmann/json.hpp>

#include <ostream>

namespace bimloc::cli {

// decidable_at_s, decision_lag_s, decision_ratio and "oracle" (threshold, cost, search size)
// into a run's JSON entry; nothing when the run had no oracle.
void addOracleFields(nlohmann::json& entry, const sim::ScenarioResult& result);

// Whether any entry carries the oracle's fields.
bool hasOracle(const nlohmann::json& scenarios);

// decidable, decidable_localized, median/p90 decision_lag_s and decision_ratio, and the
// oracle's cost, over the entries that carry the oracle's fields.
nlohmann::json oracleSummary(const nlohmann::json& scenarios);

// One line for the terminal from an oracleSummary.
void printOracleSummary(const nlohmann::json& summary, std::ostream& out);

}  // namespace bimloc::cli
