#include "sim/cli/compare_report.hpp"

#include "sim/cli/compare_verdict.hpp"
#include "sim/cli/run_report.hpp"
#include "sim/cli/table.hpp"

#include <filesystem>
#include <numeric>

namespace bimloc::cli {
namespace {

template <typename T>
nlohmann::json orNull(const std::optional<T>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

// What a method made of one run: its own convergence, judged by the one scorer (RunScore).
nlohmann::json methodJson(const sim::ScenarioResult& r, const std::vector<std::string>& pictures) {
  return {{"converged", r.converged},
          {"convergence_time_s", orNull(r.convergence_time_s)},
          {"false_convergence", r.false_convergence},
          {"ate_m", orNull(r.ate_m)},
          {"rpe_m_per_m", orNull(r.rpe_m_per_m)},
          {"map_rmse_m", orNull(r.map_rmse_m)},
          {"position_error_m", r.position_error_m},
          {"yaw_error_deg", r.yaw_error_deg},
          {"found_room", orNull(r.found_room)},
          {"true_room", r.true_room},
          {"losses", r.losses},
          {"warnings", r.warnings},
          {"pictures", pictures}};
}

double localizerSeconds(const sim::ScenarioResult& r) {
  return std::accumulate(r.localizer_seconds_by_minute.begin(), r.localizer_seconds_by_minute.end(), 0.0);
}

// A cell of a table: one value per seed, "N.L." where the method had not converged by the
// end (unless `always`: a value every run has), '!' after a value of a false convergence.
std::string cell(const nlohmann::json& room, const std::string& method, const char* key, int decimals, bool always = false) {
  std::string out;
  for (const auto& run : room["runs"]) {
    std::string v = "error";
    if (run["methods"].contains(method)) {
      const auto& m = run["methods"][method];
      v = !always && !m["converged"].get<bool>() ? "N.L." : m[key].is_null() ? "-" : fixed(m[key].get<double>(), decimals);
      if (m["false_convergence"].get<bool>()) v += "!";
    }
    out += (out.empty() ? "" : " / ") + v;
  }
  return out;
}

}  // namespace

nlohmann::json compareReport(const CompareSetup& setup, const std::vector<CompareRun>& runs, double wall_seconds) {
  nlohmann::json rooms = nlohmann::json::array();
  std::vector<std::vector<sim::ScenarioResult>> by_method(setup.methods.size());
  int errors = 0;
  double sim_seconds = 0;
  for (const CompareRun& run : runs) {
    if (rooms.empty() || rooms.back()["room"] != run.room) rooms.push_back({{"room", run.room}, {"runs", nlohmann::json::array()}});
    nlohmann::json methods = nlohmann::json::object();
    for (std::size_t k = 0; k < run.results.size() && k < setup.methods.size(); ++k) {
      methods[setup.methods[k]] = methodJson(run.results[k], k < run.pictures.size() ? run.pictures[k] : std::vector<std::string>{});
      by_method[k].push_back(run.results[k]);
    }
    if (!run.results.empty()) sim_seconds += run.results.front().sim_seconds;
    errors += !run.error.empty();
    rooms.back()["runs"].push_back({{"seed", run.seed}, {"name", run.name},
                                    {"error", run.error.empty() ? nlohmann::json(nullptr) : nlohmann::json(run.error)},
                                    {"methods", methods}});
  }
  // The summary of each method by `bimloc run`'s own rule (run_report), so the two agree.
  nlohmann::json summary = nlohmann::json::object(), seconds = nlohmann::json::object();
  for (std::size_t k = 0; k < setup.methods.size(); ++k) {
    nlohmann::json s = runReport(by_method[k], 0)["summary"];
    summary[setup.methods[k]] = {{"runs", s["runs"]}, {"localized", s["localized"]}, {"false_convergences", s["false_convergences"]},
                                 {"median_convergence_s", s["median_convergence_s"]}, {"median_ate_m", s["median_ate_m"]},
                                 {"losses", s["losses"]}};
    double total = 0;
    for (const auto& r : by_method[k]) total += localizerSeconds(r);
    seconds[setup.methods[k]] = total;
  }
  return {{"format", "bimloc.compare"}, {"version", 1}, {"plan", setup.plan}, {"storey", setup.storey}, {"site", setup.site},
          {"duration_s", setup.duration_s}, {"seeds", setup.seeds}, {"methods", setup.methods}, {"rooms", rooms},
          {"summary", summary}, {"errors", errors},
          {"timing", {{"wall_seconds", wall_seconds}, {"sim_seconds", sim_seconds}, {"localizer_seconds", seconds}}}};
}

void printCompareTables(const nlohmann::json& report, std::ostream& out, bool wide) {
  const auto methods = report["methods"].get<std::vector<std::string>>();
  std::vector<std::string> header{"start room"};
  header.insert(header.end(), methods.begin(), methods.end());
  const auto print = [&](const Table& table) { wide ? table.printWide(out) : table.print(out); };
  const auto say = [&](const std::string& text) { out << (wide ? text + "\n" : wrapText(text, kTableColumns)); };
  const std::string plan = report["plan"].get<std::string>();
  std::size_t runs = 0;
  for (const auto& room : report["rooms"]) runs += room["runs"].size();
  say((wide ? plan : std::filesystem::path(plan).filename().string()) + ", " + report["storey"].get<std::string>() + ": " +
      std::to_string(report["rooms"].size()) + " start rooms, " + std::to_string(runs) + " runs of " +
      fixed(report["duration_s"].get<double>(), 0) + " s, site " + report["site"].get<std::string>());
  const std::string per_cell = report["seeds"].get<int>() > 1 ? " (one value per seed)" : "";
  const auto roomTable = [&](const std::string& title, const char* key, int decimals, bool always = false) {
    out << "\n";
    say(title + per_cell);
    Table table(header);
    for (const auto& room : report["rooms"]) {
      std::vector<std::string> row{room["room"]};
      for (const auto& m : methods) row.push_back(cell(room, m, key, decimals, always));
      table.add(row);
    }
    print(table);
  };
  roomTable("Convergence time [s] per start room", "convergence_time_s", 1);
  roomTable("ATE [m] after convergence per start room", "ate_m", 3);
  if (wide) roomTable("Position error at the end of the run [m] per start room", "position_error_m", 2, true);

  // Per method, the best in each column marked.
  out << "\n";
  say("Per method (* the best in the column)");
  const std::vector<MethodStanding> standings = methodStandings(report);
  const std::vector<StandingHeader>& columns = standingHeaders();
  std::vector<std::string> names{"method"};
  for (const auto& c : columns) names.push_back(c.name);
  Table summary(names);
  std::vector<std::vector<bool>> best;
  for (const auto& c : columns) best.push_back(bestIn(standings, c.column));
  for (std::size_t k = 0; k < standings.size(); ++k) {
    std::vector<std::string> row{standings[k].method};
    for (std::size_t c = 0; c < columns.size(); ++c) row.push_back(standingCell(standings[k], columns[c].column) + (best[c][k] ? "*" : " "));
    summary.add(row);
  }
  print(summary);

  out << "\n";
  say(compareVerdict(report));
  out << "\n";
  const auto& timing = report["timing"];
  say("N.L.: not localized by the end of the run. !: a false convergence (declared converged while more than 0.5 m or "
      "10 deg off). localized: converged and never falsely; median time over every convergence, median ATE over the "
      "true ones; step s/run: the wall seconds of the method's steps per run.");
  std::string seconds = fixed(timing["sim_seconds"].get<double>(), 0) + " s simulated once for " + std::to_string(methods.size()) +
                        " methods in " + fixed(timing["wall_seconds"].get<double>(), 1) + " s; localizer seconds:";
  for (const auto& m : methods) seconds += " " + m + " " + fixed(timing["localizer_seconds"][m].get<double>(), 1);
  say(seconds);
}

}  // namespace bimloc::cli
