// The results of `bimloc run`: one JSON object (the documented schema) and a terminal table.
// The summary and the table are computed from the JSON's scenario entries alone, so that
// `bimloc report merge` rebuilds exactly the unsharded run's output from the shards' JSON.
#pragma once

#include "sim/runner/run_scenario.hpp"

#include <nlohmann/json.hpp>

#include <ostream>
#include <vector>

namespace bimloc::cli {

// The middle value (the mean of the middle two for an even count); NaN for none.
double median(std::vector<double> values);

// One entry of the report's "scenarios" array.
nlohmann::json scenarioJson(const sim::ScenarioResult& result);
// The report's "summary" from its "scenarios" entries (in their order).
nlohmann::json runSummary(const nlohmann::json& scenarios, double wall_seconds);
// {"scenarios": [...], "summary": {...}}.
nlohmann::json runReport(const std::vector<sim::ScenarioResult>& results, double wall_seconds);

// The table and the summary lines, from a report made by runReport (or merged shards).
void printRunTable(const nlohmann::json& report, std::ostream& out);
// The same table (the results are in the report; kept for callers that have them at hand).
void printRunTable(const std::vector<sim::ScenarioResult>& results, const nlohmann::json& report, std::ostream& out);

}  // namespace bimloc::cli
