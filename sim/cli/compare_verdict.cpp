#include "sim/cli/compare_verdict.hpp"

#include "sim/cli/table.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

namespace bimloc::cli {
namespace {

std::optional<double> optionalOf(const nlohmann::json& v) {
  return v.is_number() ? std::optional(v.get<double>()) : std::nullopt;
}

// The column's value of a standing, lower is better (Localized negated); none to not compete.
std::optional<double> score(const MethodStanding& s, StandingColumn column) {
  if (column == StandingColumn::Localized) return s.localized > 0 ? std::optional(-double(s.localized)) : std::nullopt;
  if (s.localized == 0) return std::nullopt;
  switch (column) {
    case StandingColumn::FalseConvergences: return s.false_convergences;
    case StandingColumn::MedianTime: return s.median_convergence_s;
    case StandingColumn::MedianAte: return s.median_ate_m;
    case StandingColumn::Losses: return s.losses;
    case StandingColumn::LocalizerSeconds: return s.localizer_seconds_per_run;
    case StandingColumn::Localized: break;
  }
  return std::nullopt;
}

std::string plural(int n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

std::string percent(double rate) { return fixed(100.0 * rate, 0) + " %"; }

// "a", "a and b", "a, b and c".
std::string listOf(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i)
    out += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
  return out;
}

}  // namespace

std::vector<MethodStanding> methodStandings(const nlohmann::json& report) {
  std::vector<MethodStanding> out;
  for (const auto& method : report["methods"]) {
    const std::string name = method.get<std::string>();
    const auto& s = report["summary"][name];
    MethodStanding m;
    m.method = name;
    m.runs = s["runs"].get<int>();
    m.localized = s["localized"].get<int>();
    m.false_convergences = s["false_convergences"].get<int>();
    m.losses = s["losses"].get<int>();
    m.median_convergence_s = optionalOf(s["median_convergence_s"]);
    m.median_ate_m = optionalOf(s["median_ate_m"]);
    const double seconds = report["timing"]["localizer_seconds"].value(name, 0.0);
    m.localizer_seconds_per_run = m.runs > 0 ? seconds / m.runs : 0.0;
    out.push_back(m);
  }
  return out;
}

const std::vector<StandingHeader>& standingHeaders() {
  using C = StandingColumn;
  static const std::vector<StandingHeader> headers{{"localized", C::Localized},     {"false", C::FalseConvergences},
                                                   {"median time [s]", C::MedianTime}, {"median ATE [m]", C::MedianAte},
                                                   {"losses", C::Losses},           {"step s/run", C::LocalizerSeconds}};
  return headers;
}

std::string standingCell(const MethodStanding& s, StandingColumn column) {
  const auto orDash = [](const std::optional<double>& v, int decimals) { return v ? fixed(*v, decimals) : std::string("-"); };
  switch (column) {
    case StandingColumn::Localized:
      return std::to_string(s.localized) + "/" + std::to_string(s.runs) + " " + percent(s.localizedRate());
    case StandingColumn::FalseConvergences: return std::to_string(s.false_convergences);
    case StandingColumn::MedianTime: return orDash(s.median_convergence_s, 1);
    case StandingColumn::MedianAte: return orDash(s.median_ate_m, 3);
    case StandingColumn::Losses: return std::to_string(s.losses);
    case StandingColumn::LocalizerSeconds: return fixed(s.localizer_seconds_per_run, 2);
  }
  return "";
}

std::vector<bool> bestIn(const std::vector<MethodStanding>& standings, StandingColumn column) {
  std::optional<double> best;
  for (const auto& s : standings)
    if (const auto v = score(s, column); v && (!best || *v < *best)) best = v;
  std::vector<bool> out;
  bool all_best = true;  // every competitor equal: nobody stands out
  for (const auto& s : standings) {
    const auto v = score(s, column);
    out.push_back(best && v && *v == *best);
    const bool competes = v.has_value() || column == StandingColumn::Localized;  // 0 localized loses, not abstains
    all_best = all_best && (!competes || out.back());
  }
  if (all_best && standings.size() > 1) std::fill(out.begin(), out.end(), false);
  return out;
}

std::size_t winnerOf(const std::vector<MethodStanding>& standings) {
  const auto key = [](const MethodStanding& s) {
    constexpr double kNone = 1e300;  // no median: behind every value
    return std::make_tuple(-s.localized, s.false_convergences, s.median_convergence_s.value_or(kNone),
                           s.median_ate_m.value_or(kNone));
  };
  std::size_t best = 0;
  for (std::size_t k = 1; k < standings.size(); ++k)
    if (key(standings[k]) < key(standings[best])) best = k;
  return best;
}

std::vector<std::size_t> leadersOf(const std::vector<MethodStanding>& standings) {
  if (standings.empty()) return {};
  const std::size_t w = winnerOf(standings);
  const MethodStanding& win = standings[w];
  std::vector<std::size_t> out{w};
  const auto below = [](const std::optional<double>& a, const std::optional<double>& b) { return a && (!b || *a < *b); };
  for (std::size_t k = 0; k < standings.size(); ++k) {
    const MethodStanding& s = standings[k];
    if (k == w || s.localized == 0 || s.localized != win.localized || s.false_convergences != win.false_convergences) continue;
    if (below(s.median_convergence_s, win.median_convergence_s) || below(s.median_ate_m, win.median_ate_m)) out.push_back(k);
  }
  return out;
}

namespace {

// "X and Y share the lead: ..., X converges sooner (...), Y tracks more closely (...)": the
// leaders' common count and, for each, where it beats the others.
std::string sharedLead(const std::vector<MethodStanding>& all, const std::vector<std::size_t>& leaders) {
  std::vector<std::string> names;
  for (const std::size_t k : leaders) names.push_back(all[k].method);
  const MethodStanding& first = all[leaders.front()];
  std::string out = listOf(names) + " share the lead: " + (leaders.size() == 2 ? "both" : "each") + " localize" +
                    (leaders.size() == 2 ? " " : "s ") + std::to_string(first.localized) + " of " +
                    plural(first.runs, "run", "runs") + " (" + percent(first.localizedRate()) + ") with " +
                    (first.false_convergences == 0 ? std::string("no false convergence")
                                                   : plural(first.false_convergences, "false convergence", "false convergences"));
  std::vector<MethodStanding> among;
  for (const std::size_t k : leaders) among.push_back(all[k]);
  // Method i's value first, then the others'.
  const auto values = [&](std::size_t i, const auto& value) {
    std::string v = value(among[i]);
    for (std::size_t j = 0; j < among.size(); ++j)
      if (j != i) v += " against " + value(among[j]);
    return v;
  };
  const std::vector<bool> fastest = bestIn(among, StandingColumn::MedianTime), closest = bestIn(among, StandingColumn::MedianAte);
  std::vector<std::string> edges;
  for (std::size_t i = 0; i < among.size(); ++i) {
    if (fastest[i])
      edges.push_back(among[i].method + " converges sooner (" +
                      values(i, [](const MethodStanding& s) { return fixed(s.median_convergence_s.value_or(NAN), 1) + " s"; }) +
                      " median)");
    if (closest[i])
      edges.push_back(among[i].method + " tracks more closely (" +
                      values(i, [](const MethodStanding& s) { return fixed(s.median_ate_m.value_or(NAN), 3) + " m"; }) +
                      " median ATE)");
  }
  return out + (edges.empty() ? "." : "; " + listOf(edges) + ".");
}

}  // namespace

std::string compareVerdict(const nlohmann::json& report) {
  const std::vector<MethodStanding> all = methodStandings(report);
  if (all.empty() || all.front().runs == 0) return "No run could be made: nothing to compare.";
  const std::size_t w = winnerOf(all);
  const MethodStanding& win = all[w];
  const std::string of_runs = " of " + plural(win.runs, "run", "runs");
  if (win.localized == 0)
    return "No method localized: none converged truly within the " + fixed(report["duration_s"].get<double>(), 0) +
           " s of a run.";

  const std::vector<std::size_t> leaders = leadersOf(all);
  const auto leads = [&](std::size_t k) { return std::find(leaders.begin(), leaders.end(), k) != leaders.end(); };
  // The others, best first, by how many runs each localized: those as good, then the rest.
  std::vector<std::size_t> order(all.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return all[a].localized > all[b].localized; });
  std::vector<std::string> tied, behind;
  for (const std::size_t k : order)
    if (!leads(k)) (all[k].localized == win.localized ? tied : behind).push_back(all[k].method + " " + std::to_string(all[k].localized));
  for (auto& t : tied) t = t.substr(0, t.rfind(' '));  // "as many as X": no count
  // " (the shortest)", " (the shortest, with X)" when the winner is the best in `column`.
  const auto superlative = [&](StandingColumn column, const std::string& word) {
    const std::vector<bool> best = bestIn(all, column);
    if (!best[w]) return std::string();
    std::vector<std::string> with;
    for (std::size_t k = 0; k < all.size(); ++k)
      if (k != w && best[k]) with.push_back(all[k].method);
    return " (the " + word + (with.empty() ? "" : ", with " + listOf(with)) + ")";
  };

  std::string out;
  if (leaders.size() > 1) {
    out = sharedLead(all, leaders);
    if (!tied.empty()) out += " " + listOf(tied) + " localize" + (tied.size() == 1 ? "s" : "") + " as many.";
    if (!behind.empty()) out += " Then " + listOf(behind) + " of " + std::to_string(win.runs) + ".";
  } else {
  out = win.method + (all.size() > 1 ? " wins: it" : "") + " localizes " + std::to_string(win.localized) +
                    of_runs + " (" + percent(win.localizedRate()) + ")";
  if (!tied.empty()) out += ", as many as " + listOf(tied);
  out += behind.empty() ? "." : (tied.empty() ? "; then " : "; ") + listOf(behind) + ".";
  out += " Its median convergence time is " + fixed(win.median_convergence_s.value_or(NAN), 1) + " s" +
         superlative(StandingColumn::MedianTime, "shortest") + " and its median ATE " +
         (win.median_ate_m ? fixed(*win.median_ate_m, 3) + " m" + superlative(StandingColumn::MedianAte, "smallest")
                           : std::string("not measured")) +
         ", with " +
         (win.false_convergences == 0 ? std::string("no false convergence")
                                      : plural(win.false_convergences, "false convergence", "false convergences")) +
         ".";
  }

  // Where another method does better than the winner, and at what cost.
  const auto better = [&](StandingColumn column, const std::string& what, const auto& value) {
    const std::vector<bool> best = bestIn(all, column);
    if (best[w]) return;
    for (std::size_t k = 0; k < all.size(); ++k)
      if (best[k] && !leads(k))
        out += " " + all[k].method + " " + what + " (" + value(all[k]) + ") but localizes " +
               (all[k].localized < win.localized ? "fewer: " : "") + std::to_string(all[k].localized) + of_runs +
               (all[k].false_convergences > win.false_convergences ? ", with false convergences" : "") + ".";
  };
  better(StandingColumn::MedianTime, "converges sooner", [](const MethodStanding& s) { return fixed(*s.median_convergence_s, 1) + " s median"; });
  better(StandingColumn::MedianAte, "tracks more closely", [](const MethodStanding& s) { return fixed(*s.median_ate_m, 3) + " m median ATE"; });

  std::vector<std::string> none, falsely;
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (all[k].localized == 0) none.push_back(all[k].method);
    if (!leads(k) && all[k].false_convergences > 0)
      falsely.push_back(all[k].method + " " + std::to_string(all[k].false_convergences));
  }
  if (!none.empty())
    out += " " + listOf(none) + (none.size() == 1 ? " localizes" : " localize") + " no run within the " +
           fixed(report["duration_s"].get<double>(), 0) + " s.";
  if (!falsely.empty()) out += " False convergences: " + listOf(falsely) + ".";
  return out;
}

}  // namespace bimloc::cli
