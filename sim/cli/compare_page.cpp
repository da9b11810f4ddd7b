#include "sim/cli/compare_page.hpp"

#include "sim/cli/compare_page_style.hpp"
#include "sim/cli/compare_verdict.hpp"
#include "sim/cli/html_writer.hpp"
#include "sim/cli/snapshots.hpp"
#include "sim/cli/table.hpp"
#include "sim/common/atomic_file.hpp"
#include "sim/render/compare_plots.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace bimloc::cli {
namespace {

using Json = nlohmann::json;

std::string what(const std::string& method) {
  if (method == "sgraph") return "the paper's method: the room-aware particle filter, then the S-Graph tracks";
  if (method == "pf") return "the room-aware particle filter alone";
  if (method == "pf-no-rooms") return "ablation: the particle filter without the room evidence";
  if (method == "amcl") return "peer: ROS-style AMCL on a 2D slice of the plan";
  if (method == "ndt") return "peer: HDL-style branch-and-bound, then NDT";
  return "";
}

// The method's colour in the figures (seriesRgb), as CSS.
std::string colourOf(std::size_t k) {
  char css[16];
  std::snprintf(css, sizeof css, "#%06x", static_cast<unsigned>(sim::seriesRgb(k)));
  return css;
}

void swatch(HtmlWriter& h, std::size_t k) {
  h.element("span", {{"class", "swatch"}, {"style", "background:" + colourOf(k)}}, "");
}

std::string planName(const Json& report) { return std::filesystem::path(report["plan"].get<std::string>()).filename().string(); }

std::size_t runCount(const Json& report) {
  std::size_t n = 0;
  for (const auto& room : report["rooms"]) n += room["runs"].size();
  return n;
}

// One run's value for a method as the tables show it, and its class.
std::pair<std::string, std::string> value(const Json& run, const std::string& method, const char* key, int decimals) {
  if (!run["methods"].contains(method)) return {"error", "false"};
  const Json& m = run["methods"][method];
  if (!m["converged"].get<bool>()) return {"N.L.", "nl"};
  std::string v = m[key].is_null() ? "-" : fixed(m[key].get<double>(), decimals);
  if (m["false_convergence"].get<bool>()) return {v + "!", "false"};
  return {v, ""};
}

void summaryTable(HtmlWriter& h, const Json& report) {
  const std::vector<MethodStanding> standings = methodStandings(report);
  const std::vector<std::size_t> leaders = leadersOf(standings);
  const std::vector<StandingHeader>& columns = standingHeaders();
  h.open("table", {{"id", "summary"}}).open("tr").element("th", {}, "method");
  for (const auto& c : columns) h.element("th", {}, c.name);
  h.close();
  std::vector<std::vector<bool>> best;
  for (const auto& c : columns) best.push_back(bestIn(standings, c.column));
  for (std::size_t k = 0; k < standings.size(); ++k) {
    const MethodStanding& s = standings[k];
    h.open("tr").open("td");
    swatch(h, k);
    h.element("b", {}, s.method);
    if (s.localized > 0 && std::find(leaders.begin(), leaders.end(), k) != leaders.end())
      h.element("span", {{"class", "badge"}}, leaders.size() == 1 ? "winner" : "shares the lead");
    h.close();
    for (std::size_t c = 0; c < columns.size(); ++c)
      h.element("td", best[c][k] ? HtmlWriter::Attributes{{"class", "best"}} : HtmlWriter::Attributes{},
                standingCell(s, columns[c].column));
    h.close();
  }
  h.close();
  // What each method is, under the table.
  h.open("ul", {{"class", "methods"}});
  for (std::size_t k = 0; k < standings.size(); ++k) {
    if (what(standings[k].method).empty()) continue;
    h.open("li");
    swatch(h, k);
    h.element("b", {}, standings[k].method).text(": " + what(standings[k].method)).close();
  }
  h.close();
}

// best[k]: method k did best from this start room: of the methods that localized the most of
// its runs (at least one), the smallest mean value over those runs. None when all are equal.
std::vector<bool> rowBest(const Json& room, const std::vector<std::string>& methods, const char* key) {
  std::vector<int> localized(methods.size(), 0);
  std::vector<double> sum(methods.size(), 0.0);
  for (std::size_t k = 0; k < methods.size(); ++k)
    for (const auto& run : room["runs"]) {
      if (!run["methods"].contains(methods[k])) continue;
      const Json& m = run["methods"][methods[k]];
      if (m["converged"].get<bool>() && !m["false_convergence"].get<bool>() && m[key].is_number())
        ++localized[k], sum[k] += m[key].get<double>();
    }
  const int most = *std::max_element(localized.begin(), localized.end());
  std::vector<bool> best(methods.size(), false);
  if (most == 0) return best;
  double lowest = INFINITY;
  for (std::size_t k = 0; k < methods.size(); ++k)
    if (localized[k] == most) lowest = std::min(lowest, sum[k] / most);
  bool all = true;
  for (std::size_t k = 0; k < methods.size(); ++k) {
    best[k] = localized[k] == most && sum[k] / most == lowest;
    all = all && best[k];
  }
  if (all && methods.size() > 1) std::fill(best.begin(), best.end(), false);
  return best;
}

// Rooms down, methods across, one value per seed, each linking to its run's pictures.
void roomTable(HtmlWriter& h, const Json& report, const std::string& id, const char* key, int decimals) {
  const auto methods = report["methods"].get<std::vector<std::string>>();
  h.open("table", {{"id", id}}).open("tr").element("th", {}, "start room");
  for (std::size_t k = 0; k < methods.size(); ++k) {
    h.open("th");
    swatch(h, k);
    h.text(methods[k]).close();
  }
  h.close();
  for (const auto& room : report["rooms"]) {
    h.open("tr").element("td", {}, room["room"].get<std::string>());
    const std::vector<bool> best = rowBest(room, methods, key);
    for (std::size_t k = 0; k < methods.size(); ++k) {
      const std::string& method = methods[k];
      h.open("td", best[k] ? HtmlWriter::Attributes{{"class", "best"}} : HtmlWriter::Attributes{});
      bool first = true;
      for (const auto& run : room["runs"]) {
        if (!first) h.text(" / ");
        first = false;
        const auto [text, css] = value(run, method, key, decimals);
        HtmlWriter::Attributes a{{"href", "#" + runAnchor(run["name"].get<std::string>(), method)},
                                 {"title", run["name"].get<std::string>() + ", " + method}};
        if (!css.empty()) a.push_back({"class", css});
        h.element("a", a, text);
      }
      h.close();
    }
    h.close();
  }
  h.close();
}

// "converged at 8.4 s, ATE 0.031 m" and the like, for a run's method.
std::string outcome(const Json& m, double duration_s) {
  if (!m["converged"].get<bool>())
    return "not localized in " + fixed(duration_s, 0) + " s; " + fixed(m["position_error_m"].get<double>(), 2) +
           " m off at the end";
  std::string out = (m["false_convergence"].get<bool>() ? "FALSE convergence at " : "converged at ") +
                    fixed(m["convergence_time_s"].get<double>(), 1) + " s";
  if (m["ate_m"].is_number()) out += ", ATE " + fixed(m["ate_m"].get<double>(), 3) + " m";
  return out + "; " + fixed(m["position_error_m"].get<double>(), 2) + " m off at the end";
}

// "3_convergence.png" -> "convergence"; "errors.png" -> "error over time".
std::string caption(const std::string& path) {
  const std::string file = std::filesystem::path(path).stem().string();
  if (file == "errors") return "error over time";
  const auto under = file.find('_');
  return under == std::string::npos ? file : file.substr(under + 1);
}

void runsSection(HtmlWriter& h, const Json& report) {
  const auto methods = report["methods"].get<std::vector<std::string>>();
  const double duration_s = report["duration_s"].get<double>();
  for (const auto& room : report["rooms"])
    for (const auto& run : room["runs"]) {
      const std::string name = run["name"].get<std::string>();
      h.open("details", {{"id", "run-" + fileSafe(name)}}).open("summary").text(name + " ");
      std::string brief;
      for (const auto& method : methods) {
        const auto [text, css] = value(run, method, "convergence_time_s", 1);
        brief += (brief.empty() ? "" : " · ") + method + " " + (css.empty() || css == "false" ? text + " s" : text);
      }
      h.element("span", {}, brief).close();
      if (!run["error"].is_null()) h.element("p", {{"class", "false"}}, "could not be made: " + run["error"].get<std::string>());
      for (std::size_t k = 0; k < methods.size(); ++k) {
        if (!run["methods"].contains(methods[k])) continue;
        const Json& m = run["methods"][methods[k]];
        h.open("div", {{"class", "method"}, {"id", runAnchor(name, methods[k])}}).open("h3");
        swatch(h, k);
        h.text(methods[k] + ": ").element("span", {{"class", "muted"}}, outcome(m, duration_s)).close();
        h.open("div", {{"class", "strip"}});
        for (const auto& picture : m["pictures"]) {
          const std::string path = picture.get<std::string>();
          h.open("a", {{"href", path}})
              .empty("img", {{"src", path}, {"loading", "lazy"}, {"alt", caption(path)}})
              .text(caption(path))
              .close();
        }
        if (m["pictures"].empty()) h.element("span", {{"class", "muted"}}, "no pictures");
        h.close().close();
      }
      h.close();
    }
}

}  // namespace

std::string runAnchor(const std::string& run_name, const std::string& method) { return fileSafe(run_name) + "-" + fileSafe(method); }

std::string comparePage(const Json& report) {
  HtmlWriter h;
  const std::string plan = planName(report);
  const std::size_t runs = runCount(report);
  h.open("html", {{"lang", "en"}}).open("head");
  h.empty("meta", {{"charset", "utf-8"}}).empty("meta", {{"name", "viewport"}, {"content", "width=device-width, initial-scale=1"}});
  h.element("title", {}, "bimloc compare: " + plan);
  h.open("style").raw(kComparePageStyle).close().close();
  h.open("body").open("main");
  h.element("h1", {}, "Global localization on " + plan);
  h.element("p", {{"class", "sub"}},
            report["storey"].get<std::string>() + " · " + std::to_string(report["rooms"].size()) + " start rooms × " +
                std::to_string(report["seeds"].get<int>()) + (report["seeds"].get<int>() == 1 ? " seed" : " seeds") +
                " = " + std::to_string(runs) + " runs of " + fixed(report["duration_s"].get<double>(), 0) + " s · site " +
                report["site"].get<std::string>() +
                " · every method on the same simulated scans and odometry, judged by one scorer");
  h.open("p", {{"class", "verdict"}}).element("b", {}, "Verdict. ").text(compareVerdict(report)).close();

  h.element("h2", {}, "Per method");
  summaryTable(h, report);
  h.element("p", {{"class", "note"}},
            "Green: the best in the column, among the methods that localized a run (none where all are equal). "
            "Localized: converged within 0.5 m and 10° of the truth, never falsely; a false convergence: declared "
            "converged while farther off (false). Median time: to convergence. Losses: tracking lost after convergence. "
            "Step time: the wall seconds of the method's steps, on this machine.");

  h.element("h2", {}, "Convergence time per run");
  h.open("figure").empty("img", {{"src", "convergence_times.png"}, {"alt", "convergence times, a bar per run and method"}});
  h.element("figcaption", {}, "A bar per run (seed) and method, grouped by start room; pale with a cross: not localized.").close();
  h.element("h2", {}, "Position error over time");
  h.open("figure").empty("img", {{"src", "errors_over_time.png"}, {"alt", "median position error over time per method"}});
  h.element("figcaption", {}, "Each method's median position error over the runs, turn by turn (log scale).").close();

  const std::string per_seed = report["seeds"].get<int>() > 1 ? " (one value per seed; click one for its run)" : " (click a value for its run)";
  h.element("h2", {}, "Convergence time [s] per start room");
  h.element("p", {{"class", "note"}}, "Green: the method that did best from that room (the most runs localized, then "
                                      "the smallest mean). N.L.: not localized by the end of the run; !: a false "
                                      "convergence" + per_seed + ".");
  roomTable(h, report, "times", "convergence_time_s", 1);
  h.element("h2", {}, "ATE [m] after convergence per start room");
  roomTable(h, report, "ate", "ate_m", 3);

  h.element("h2", {{"id", "runs"}}, "Every run");
  h.element("p", {{"class", "note"}},
            "Top views of the plan at initialization, while the particles cluster, at convergence and at the end (green: "
            "the truth, red: the estimate), and the error over the run. Click a picture for it in full.");
  runsSection(h, report);

  const Json& timing = report["timing"];
  h.element("footer", {},
            "Written by bimloc compare from " + report["plan"].get<std::string>() + ": " +
                fixed(timing["sim_seconds"].get<double>(), 0) + " s simulated once for " +
                std::to_string(report["methods"].size()) + " methods in " + fixed(timing["wall_seconds"].get<double>(), 1) +
                " s. The numbers are in compare.json beside this page.");
  h.close().open("script").raw(kComparePageScript).close().close().close();
  return h.document();
}

void writeComparePage(const Json& report, const std::string& dir) {
  sim::writeFileAtomically(dir + "/index.html", comparePage(report));
}

}  // namespace bimloc::cli
