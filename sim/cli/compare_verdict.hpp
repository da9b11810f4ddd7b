// Who wins a comparison (bimloc compare), from its report's numbers alone: each method's
// standing, the best method in each column, and a short verdict in words, for the terminal
// and for the page (compare_page).
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace bimloc::cli {

struct MethodStanding {
  std::string method;
  int runs = 0, localized = 0, false_convergences = 0, losses = 0;
  std::optional<double> median_convergence_s, median_ate_m;  // none when nothing to take a median of
  double localizer_seconds_per_run = 0;                      // wall seconds of its steps (timing)
  double localizedRate() const { return runs > 0 ? static_cast<double>(localized) / runs : 0.0; }
};

// One per method, in the report's order (compareReport's "summary" and "timing").
std::vector<MethodStanding> methodStandings(const nlohmann::json& report);

enum class StandingColumn { Localized, FalseConvergences, MedianTime, MedianAte, Losses, LocalizerSeconds };

// The table per method's columns, as the terminal and the page show them, and a cell's text.
struct StandingHeader {
  std::string name;
  StandingColumn column;
};
const std::vector<StandingHeader>& standingHeaders();
std::string standingCell(const MethodStanding& standing, StandingColumn column);

// best[k]: method k is the best in the column (ties are all best). More localized is better,
// less of everything else. In every column but Localized only the methods that localized a
// run compete: one that never converges has no false convergence and spends little, and wins
// nothing by it. No method is best when none localized a run.
std::vector<bool> bestIn(const std::vector<MethodStanding>& standings, StandingColumn column);

// The winner's index: the most runs localized, then the fewest false convergences, then the
// shortest median convergence time, then the smallest median ATE, then the first given.
std::size_t winnerOf(const std::vector<MethodStanding>& standings);

// The methods that share the lead: the winner first, then each method that localized as many
// runs with as few false convergences and beats the winner on median time or median ATE (the
// winner does not dominate it). One entry when the winner stands alone.
std::vector<std::size_t> leadersOf(const std::vector<MethodStanding>& standings);

// A few sentences: who wins and by how much, who is faster or more accurate at what cost,
// who falsely converged. Plain text, numbers from the report.
std::string compareVerdict(const nlohmann::json& report);

}  // namespace bimloc::cli
