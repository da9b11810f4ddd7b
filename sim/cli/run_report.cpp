#include "sim/cli/run_report.hpp"

#include "sim/cli/oracle_report.hpp"
#include "sim/cli/table.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

namespace bimloc::cli {
namespace {

template <typename T>
nlohmann::json valueOrNull(const std::optional<T>& v) {
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
  for (const auto& s : storeys) {
    nlohmann::json j = {{"storey", s.storey}, {"converged", s.converged}, {"path_log_likelihood", s.path_log_likelihood}};
    if (s.best) j["best"] = {{"x", s.best->x()}, {"y", s.best->y()}, {"yaw_deg", s.best->z() * 180.0 / M_PI}};
    out.push_back(std::move(j));
  }
  return out;
}

nlohmann::json wallsJson(const std::vector<sim::ScenarioResult::WallEstimate>& walls) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& [w, true_offset, true_angle] : walls)
    out.push_back({{"wall", w.wall_id}, {"offset_m", w.offset_m}, {"angle_deg", w.angle_deg},
                   {"thickness_change_m", w.thickness_change_m}, {"observations", w.observations},
                   {"true_offset_m", valueOrNull(true_offset)}, {"true_angle_deg", valueOrNull(true_angle)}});
  return out;
}

// What a recording's readers dropped (sim/dataset/recording_checks.hpp), by reason.
nlohmann::json recordingJson(const sim::RecordingChecks& c) {
  const auto poses = [](const sim::PoseSampleDrops& d) {
    return nlohmann::json{{"read", d.read}, {"dropped", d.dropped()}, {"non_finite", d.non_finite},
                          {"zero_quaternion", d.zero_quaternion}, {"not_unit_quaternion", d.not_unit_quaternion}};
  };
  const auto& p = c.points;
  return {{"scans", {{"read", c.scans}, {"skipped_no_usable_point", c.scans_skipped}}},
          {"points", {{"read", p.read}, {"dropped", p.dropped()}, {"non_finite", p.non_finite}, {"at_origin", p.at_origin},
                      {"below_min_range", p.below_min_range}, {"beyond_max_range", p.beyond_max_range}}},
          {"odometry", poses(c.odometry)},
          {"odometry_jumps", {{"count", c.odometry_jumps.count}, {"worst_m", c.odometry_jumps.worst_m},
                              {"worst_deg", c.odometry_jumps.worst_deg}, {"worst_stamp_s", c.odometry_jumps.worst_stamp_s}}},
          {"ground_truth", poses(c.ground_truth)}};
}

// The sum of the scenarios' "recording" blocks (the same keys), or null when none has one.
nlohmann::json recordingTotal(const nlohmann::json& scenarios) {
  nlohmann::json total;
  for (const auto& s : scenarios) {
    if (!s.contains("recording")) continue;
    if (total.is_null()) {
      total = s["recording"];
      total["odometry_jumps"] = s["recording"]["odometry_jumps"]["count"];  // the total: a count
      continue;
    }
    for (const char* part : {"scans", "points", "odometry", "ground_truth"})
      for (auto& [key, value] : total[part].items()) value = value.get<std::size_t>() + s["recording"][part][key].get<std::size_t>();
    total["odometry_jumps"] = total["odometry_jumps"].get<std::size_t>() + s["recording"]["odometry_jumps"]["count"].get<std::size_t>();
  }
  return total;
}

}  // namespace

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

nlohmann::json scenarioJson(const sim::ScenarioResult& r) {
  nlohmann::json j = {{"name", r.name}, {"plan", r.plan}, {"storey", r.storey}, {"start_room", r.start_room},
          {"method", r.method}, {"seed", r.seed}, {"converged", r.converged},
          {"convergence_time_s", valueOrNull(r.convergence_time_s)}, {"found_room", valueOrNull(r.found_room)},
          {"true_room", r.true_room}, {"position_error_m", r.position_error_m},
          {"yaw_error_deg", r.yaw_error_deg}, {"ate_m", valueOrNull(r.ate_m)},
          {"rpe_m_per_m", valueOrNull(r.rpe_m_per_m)}, {"map_rmse_m", valueOrNull(r.map_rmse_m)}, {"losses", r.losses},
          {"storey_changes", r.storey_changes}, {"storey_changes_followed", r.storey_changes_followed},
          {"storey_changes_searching", r.storey_changes_searching}, {"storey_follow_lags_s", r.storey_follow_lags_s}, {"path_length_m", r.path_length_m}, {"wall_deviations", wallsJson(r.wall_deviations)}, {"site", r.site},
          {"wall_offset_error_m", valueOrNull(r.wall_offset_error_m)},
          {"false_convergence", r.false_convergence}, {"convergence_margin", valueOrNull(r.convergence_margin)},
          {"verdicts_bound_held", r.verdicts_bound_held}, {"verdicts_fit_lowered", r.verdicts_fit_lowered},
          {"first_bound_held_s", valueOrNull(r.first_bound_held_s)}, {"first_fit_lowered_s", valueOrNull(r.first_fit_lowered_s)},
          {"hypotheses", placesJson(r.hypotheses)}, {"storey_auto", r.storey_auto},
          {"found_storey", valueOrNull(r.found_storey)}, {"storey_margin", valueOrNull(r.storey_margin)},
          {"storey_candidates", storeysJson(r.storey_candidates)}, {"passed", r.passed}, {"failures", r.failures},
          {"warnings", r.warnings}, {"sim_seconds", r.sim_seconds}};
  if (r.recording) j["recording"] = recordingJson(*r.recording);  // `localize` only: the schema of `run` is unchanged
  if (r.guide)  // motion disambiguate only: a tour's JSON is unchanged
    j["guide"] = {{"place_steps", r.guide->place_steps}, {"goal_steps", r.guide->goal_steps},
                  {"goals_taken", r.guide->goals_taken}, {"first_goal_s", valueOrNull(r.guide->first_goal_s)}};
  addOracleFields(j, r);
  return j;
}

nlohmann::json runSummary(const nlohmann::json& scenarios, double wall_seconds) {
  int localized = 0, false_convergences = 0, losses = 0, storey_changes = 0, storey_changes_followed = 0,
      storey_changes_searching = 0;
  double sim_seconds = 0;
  std::vector<double> times, ates, follow_lags;
  for (const auto& s : scenarios) {
    const bool converged = s.at("converged").get<bool>(), false_convergence = s.at("false_convergence").get<bool>();
    localized += converged && !false_convergence;
    false_convergences += false_convergence;
    sim_seconds += s.at("sim_seconds").get<double>();
    losses += s.at("losses").get<int>();
    storey_changes += s.value("storey_changes", 0);
    storey_changes_followed += s.value("storey_changes_followed", 0);
    storey_changes_searching += s.value("storey_changes_searching", 0);
    if (s.contains("storey_follow_lags_s"))
      for (const auto& lag : s["storey_follow_lags_s"]) follow_lags.push_back(lag.get<double>());
    if (!s.at("convergence_time_s").is_null()) times.push_back(s["convergence_time_s"].get<double>());
    if (!s.at("ate_m").is_null() && !false_convergence) ates.push_back(s["ate_m"].get<double>());
  }
  const nlohmann::json median_time = times.empty() ? nlohmann::json(nullptr) : nlohmann::json(median(times));
  const nlohmann::json median_ate = ates.empty() ? nlohmann::json(nullptr) : nlohmann::json(median(ates));
  nlohmann::json summary = {{"runs", scenarios.size()}, {"localized", localized}, {"false_convergences", false_convergences},
                            {"median_convergence_s", median_time}, {"median_ate_m", median_ate}, {"losses", losses},
                            {"storey_changes", storey_changes}, {"storey_changes_followed", storey_changes_followed},
                            {"storey_changes_searching", storey_changes_searching},
                            {"median_storey_follow_lag_s", follow_lags.empty() ? nlohmann::json(nullptr) : nlohmann::json(median(follow_lags))},
                            {"sim_seconds", sim_seconds}, {"wall_seconds", wall_seconds}};
  if (nlohmann::json dropped = recordingTotal(scenarios); !dropped.is_null()) summary["recording"] = std::move(dropped);
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
  std::ostringstream line;  // one sentence, broken to the table's width
  line << s["localized"].get<int>() << " of " << s["runs"].get<std::size_t>() << " localized, "
      << s["false_convergences"].get<int>() << " false convergences, median convergence "
      << (s["median_convergence_s"].is_null() ? std::string("-") : fixed(s["median_convergence_s"].get<double>(), 1) + " s")
      << ", median ATE " << (s["median_ate_m"].is_null() ? std::string("-") : fixed(s["median_ate_m"].get<double>(), 3) + " m")
      << ", " << s["losses"].get<int>() << " losses of track; "
      << (s.value("storey_changes", 0) > 0 ? std::to_string(s.value("storey_changes_followed", 0)) + " of " +
                                                  std::to_string(s.value("storey_changes", 0)) + " storey changes followed; "
                                            : std::string())
      << (s.value("storey_changes_searching", 0) > 0
              ? std::to_string(s.value("storey_changes_searching", 0)) + " storey changes while still searching; "
              : std::string()) << fixed(s["sim_seconds"].get<double>(), 0) << " s simulated in " << fixed(s["wall_seconds"].get<double>(), 1)
      << " s";
  out << "\n" << wrapText(line.str(), kTableColumns);
  if (oracle) printOracleSummary(s, out);
  for (const auto& r : results)
    for (const auto& f : r.at("failures")) out << "  " << r.at("name").get<std::string>() << ": " << f.get<std::string>() << "\n";
  // A recording's drops, whenever there were any (the details are in the warnings).
  for (const auto& r : results) {
    if (!r.contains("recording")) continue;
    const auto& c = r["recording"];
    const std::size_t scans = c["scans"]["skipped_no_usable_point"], points = c["points"]["dropped"],
                      odometry = c["odometry"]["dropped"], jumps = c["odometry_jumps"]["count"];
    if (scans + points + odometry + jumps == 0) continue;
    out << "  " << r.at("name").get<std::string>() << ": dropped " << scans << " of " << c["scans"]["read"].get<std::size_t>()
        << " scans (no usable point), " << points << " of " << c["points"]["read"].get<std::size_t>() << " points ("
        << c["points"]["non_finite"].get<std::size_t>() << " not finite, " << c["points"]["at_origin"].get<std::size_t>()
        << " at the origin, " << c["points"]["below_min_range"].get<std::size_t>() << " below min range, "
        << c["points"]["beyond_max_range"].get<std::size_t>() << " beyond max range), " << odometry << " of "
        << c["odometry"]["read"].get<std::size_t>() << " odometry samples; " << jumps << " odometry jumps\n";
  }
}

}  // namespace bimloc::cli
