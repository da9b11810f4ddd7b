#include "sim/cli/run_report.hpp"

#include "sim/cli/oracle_report.hpp"
#include "sim/cli/table.hpp"

#include <algorithm>
#include <limits>

namespace bimloc::cli {
namespace {

template <typename T>
nlohmann::json orNull(const std::optional<T>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

nlohmann::json placesJson(const std::vector<sim::ScenarioResult::Place>& places) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& p : places)
    out.push_back({{"x", p.x}, {"y", p.y}, {"yaw_deg", p.yaw_deg}, {"room", p.room}, {"storey", p.storey},
                   {"relative_weight", p.relative_weight}});
  return out;
}

nlohmann::json storeysJson(const std::vector<sim::ScenarioResult::StoreyOption>& storeys) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& s : storeys)
    out.push_back({{"storey", s.storey}, {"converged", s.converged}, {"path_log_likelihood", s.path_log_likelihood}});
  return out;
}

nlohmann::json wallsJson(const std::vector<sim::ScenarioResult::WallEstimate>& walls) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& [w, true_offset, true_angle] : walls)
    out.push_back({{"wall", w.wall_id}, {"offset_m", w.offset_m}, {"angle_deg", w.angle_deg},
                   {"thickness_change_m", w.thickness_change_m}, {"observations", w.observations},
                   {"true_offset_m", orNull(true_offset)}, {"true_angle_deg", orNull(true_angle)}});
  return out;
}

}  // namespace

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

nlohmann::json scenarioJson(const sim::ScenarioResult& r) {
  nlohmann::json entry{{"name", r.name}, {"plan", r.plan}, {"storey", r.storey}, {"start_room", r.start_room},
          {"method", r.method}, {"seed", r.seed}, {"converged", r.converged},
          {"convergence_time_s", orNull(r.convergence_time_s)}, {"found_room", orNull(r.found_room)},
          {"true_room", r.true_room}, {"position_error_m", r.position_error_m},
          {"yaw_error_deg", r.yaw_error_deg}, {"ate_m", orNull(r.ate_m)},
          {"rpe_m_per_m", orNull(r.rpe_m_per_m)}, {"map_rmse_m", orNull(r.map_rmse_m)}, {"losses", r.losses},
          {"path_length_m", r.path_length_m}, {"wall_deviations", wallsJson(r.wall_deviations)}, {"site", r.site},
          {"wall_offset_error_m", orNull(r.wall_offset_error_m)},
          {"false_convergence", r.false_convergence}, {"convergence_margin", orNull(r.convergence_margin)},
          {"hypotheses", placesJson(r.hypotheses)}, {"storey_auto", r.storey_auto},
          {"found_storey", orNull(r.found_storey)}, {"storey_margin", orNull(r.storey_margin)},
          {"storey_candidates", storeysJson(r.storey_candidates)}, {"passed", r.passed}, {"failures", r.failures},
          {"warnings", r.warnings}, {"sim_seconds", r.sim_seconds}};
  addOracleFields(entry, r);
  return entry;
}

nlohmann::json runSummary(const nlohmann::json& scenarios, double wall_seconds) {
  int localized = 0, false_convergences = 0, losses = 0;
  double sim_seconds = 0;
  std::vector<double> times, ates;
  for (const auto& s : scenarios) {
    const bool converged = s.at("converged").get<bool>(), false_convergence = s.at("false_convergence").get<bool>();
    localized += converged && !false_convergence;
    false_convergences += false_convergence;
    sim_seconds += s.at("sim_seconds").get<double>();
    losses += s.at("losses").get<int>();
    if (!s.at("convergence_time_s").is_null()) times.push_back(s["convergence_time_s"].get<double>());
    if (!s.at("ate_m").is_null() && !false_convergence) ates.push_back(s["ate_m"].get<double>());
  }
  const nlohmann::json median_time = times.empty() ? nlohmann::json(nullptr) : nlohmann::json(median(times));
  const nlohmann::json median_ate = ates.empty() ? nlohmann::json(nullptr) : nlohmann::json(median(ates));
  nlohmann::json summary{{"runs", scenarios.size()}, {"localized", localized}, {"false_convergences", false_convergences},
                         {"median_convergence_s", median_time}, {"median_ate_m", median_ate}, {"losses", losses},
                         {"sim_seconds", sim_seconds}, {"wall_seconds", wall_seconds}};
  if (hasOracle(scenarios)) summary.update(oracleSummary(scenarios));
  return summary;
}

nlohmann::json runReport(const std::vector<sim::ScenarioResult>& results, double wall_seconds) {
  nlohmann::json scenarios = nlohmann::json::array();
  for (const auto& r : results) scenarios.push_back(scenarioJson(r));
  nlohmann::json summary = runSummary(scenarios, wall_seconds);
  return {{"scenarios", std::move(scenarios)}, {"summary", std::move(summary)}};
}

namespace {

std::string text(const nlohmann::json& v) { return v.is_null() ? std::string("-") : v.get<std::string>(); }
std::string number(const nlohmann::json& v, int decimals) { return v.is_null() ? std::string("-") : fixed(v.get<double>(), decimals); }

}  // namespace

void printRunTable(const std::vector<sim::ScenarioResult>&, const nlohmann::json& report, std::ostream& out) {
  printRunTable(report, out);
}

void printRunTable(const nlohmann::json& report, std::ostream& out) {
  const nlohmann::json& results = report.at("scenarios");
  // With storey auto the storey found is part of the answer: a column of its own.
  bool any_auto = false;
  for (const auto& r : results) any_auto = any_auto || r.at("storey_auto").get<bool>();
  std::vector<std::string> header{"scenario", "method", "converged", "time [s]", "room found / true", "pos err [m]",
                                  "yaw err [deg]", "ATE [m]", "RPE [m/m]", "map RMSE [m]", "lost", "false", "result"};
  if (any_auto) header.insert(header.begin() + 4, "storey found / true");
  // On a site that is not its plan, which one, and how well the S-Graph estimated its walls.
  bool any_site = false;
  for (const auto& r : results) any_site = any_site || r.at("site").get<std::string>() != "exact";
  if (any_site) header.insert(header.begin() + 2, "site"), header.insert(header.end() - 2, "wall err [m]");
  // With --oracle: when the scans first allowed a decision, and the localizer's lag beyond it.
  const bool oracle = hasOracle(results);
  if (oracle) header.insert(header.end() - 2, {"decidable [s]", "lag [s]", "ratio"});
  Table table(header);
  for (const auto& r : results) {
    const int losses = r.at("losses").get<int>();
    std::vector<std::string> row{r.at("name").get<std::string>(), r.at("method").get<std::string>(),
                                 r.at("converged").get<bool>() ? "yes" : "no", number(r.at("convergence_time_s"), 1),
                                 text(r.at("found_room")) + " / " + r.at("true_room").get<std::string>(),
                                 fixed(r.at("position_error_m").get<double>(), 3), fixed(r.at("yaw_error_deg").get<double>(), 2),
                                 number(r.at("ate_m"), 3), number(r.at("rpe_m_per_m"), 3), number(r.at("map_rmse_m"), 3),
                                 losses ? std::to_string(losses) : "", r.at("false_convergence").get<bool>() ? "FALSE" : "",
                                 r.at("passed").get<bool>() ? "pass" : "FAIL"};
    if (any_auto) {
      std::string found = text(r.at("found_storey"));
      const auto& candidates = r.at("storey_candidates");
      if (r.at("found_storey").is_null() && !candidates.empty()) {
        found = "{";  // undecided: the storeys still considered, leader first
        for (std::size_t i = 0; i < candidates.size(); ++i) found += (i ? ", " : "") + candidates[i].at("storey").get<std::string>();
        found += "}";
      }
      row.insert(row.begin() + 4, found + " / " + r.at("storey").get<std::string>());
    }
    if (any_site)
      row.insert(row.begin() + 2, r.at("site").get<std::string>()), row.insert(row.end() - 2, number(r.at("wall_offset_error_m"), 3));
    if (oracle) {
      const auto value = [&](const char* key, int decimals) { return r.contains(key) ? number(r.at(key), decimals) : std::string("-"); };
      row.insert(row.end() - 2, {value("decidable_at_s", 1), value("decision_lag_s", 1), value("decision_ratio", 2)});
    }
    table.add(row);
  }
  table.print(out);
  const auto& s = report.at("summary");
  out << "\n" << s["localized"].get<int>() << " of " << s["runs"].get<std::size_t>() << " localized, "
      << s["false_convergences"].get<int>() << " false convergences, median convergence "
      << (s["median_convergence_s"].is_null() ? std::string("-") : fixed(s["median_convergence_s"].get<double>(), 1) + " s")
      << ", median ATE " << (s["median_ate_m"].is_null() ? std::string("-") : fixed(s["median_ate_m"].get<double>(), 3) + " m")
      << ", " << s["losses"].get<int>() << " losses of track; " << fixed(s["sim_seconds"].get<double>(), 0) << " s simulated in " << fixed(s["wall_seconds"].get<double>(), 1)
      << " s\n";
  if (oracle) printOracleSummary(s, out);
  for (const auto& r : results)
    for (const auto& f : r.at("failures")) out << "  " << r.at("name").get<std::string>() << ": " << f.get<std::string>() << "\n";
}

}  // namespace bimloc::cli
