// The inconsistencies the text of a STEP file shows by itself, before IFC++ reads it.
#include "step_references.hpp"

#include <algorithm>
#include <unordered_map>

namespace bimloc::bim::detail {
namespace {

std::string name(const StepInstance& instance) {
  return "#" + std::to_string(instance.id) + " " + instance.type + " (line " + std::to_string(instance.line) + ")";
}

// The strongly connected components of the reference graph that are cycles (more than one
// instance, or one that names itself): Tarjan's algorithm, iterative, as a broken file may
// chain placements deeper than any stack allows.
std::vector<std::vector<int>> referenceCycles(const std::vector<StepInstance>& instances,
                                              const std::unordered_map<int, int>& index_of) {
  const int n = static_cast<int>(instances.size());
  std::vector<int> index(n, -1), low(n, 0);
  std::vector<bool> on_stack(n, false);
  std::vector<int> stack;
  std::vector<std::pair<int, std::size_t>> work;  // (node, next reference to follow)
  std::vector<std::vector<int>> cycles;
  int counter = 0;
  const auto target = [&](int node, std::size_t r) {
    const auto it = index_of.find(instances[node].refs[r]);
    return it == index_of.end() ? -1 : it->second;
  };
  for (int root = 0; root < n; ++root) {
    if (index[root] >= 0) continue;
    work.emplace_back(root, 0);
    while (!work.empty()) {
      auto& [node, next] = work.back();
      if (next == 0 && index[node] < 0) {
        index[node] = low[node] = counter++;
        stack.push_back(node);
        on_stack[node] = true;
      }
      if (next < instances[node].refs.size()) {
        const int to = target(node, next++);
        if (to < 0) continue;
        if (index[to] < 0) work.emplace_back(to, 0);
        else if (on_stack[to]) low[node] = std::min(low[node], index[to]);
        continue;
      }
      const int done = node;
      work.pop_back();
      if (!work.empty()) low[work.back().first] = std::min(low[work.back().first], low[done]);
      if (low[done] != index[done]) continue;
      std::vector<int> component;
      int member = -1;
      do {
        member = stack.back();
        stack.pop_back();
        on_stack[member] = false;
        component.push_back(member);
      } while (member != done);
      const auto& refs = instances[done].refs;
      const bool self = std::find(refs.begin(), refs.end(), instances[done].id) != refs.end();
      if (component.size() > 1 || self) cycles.push_back(std::move(component));
    }
  }
  return cycles;
}

}  // namespace

std::map<int, std::string> stepProblems(const StepScan& scan) {
  std::map<int, std::string> problems;
  const auto& instances = scan.instances;
  // Duplicate ids: which of the two IFC++ keeps is its own choice, so neither can be trusted.
  for (std::size_t i = 0; i + 1 < instances.size(); ++i) {
    if (instances[i].id != instances[i + 1].id) continue;
    std::size_t j = i;
    std::string lines;
    while (j < instances.size() && instances[j].id == instances[i].id)
      lines += (lines.empty() ? "" : ", ") + std::to_string(instances[j++].line);
    problems.emplace(instances[i].id, "#" + std::to_string(instances[i].id) + " is defined " + std::to_string(j - i) +
                                          " times (lines " + lines + ")");
    i = j - 1;
  }
  for (const auto& instance : instances)
    if (!instance.problem.empty()) problems.emplace(instance.id, name(instance) + " " + instance.problem);
  std::unordered_map<int, int> index_of;
  for (int i = 0; i < static_cast<int>(instances.size()); ++i) index_of.emplace(instances[i].id, i);
  for (auto& cycle : referenceCycles(instances, index_of)) {
    std::sort(cycle.begin(), cycle.end());
    std::string members;
    for (std::size_t k = 0; k < cycle.size() && k < 6; ++k)
      members += (k ? ", #" : "#") + std::to_string(instances[cycle[k]].id);
    if (cycle.size() > 6) members += ", ... (" + std::to_string(cycle.size()) + " instances)";
    for (const int member : cycle)
      problems.emplace(instances[member].id, name(instances[member]) + " is on a cycle of references (" + members + ")");
  }
  return problems;
}

}  // namespace bimloc::bim::detail
