// bimloc report merge A.json B.json ... [--json]: the shards of `bimloc run --shard K/N --json`
// put back together into exactly the unsharded run's report (sim/cli/shards.hpp).
#include "sim/cli/commands.hpp"
#include "sim/cli/run_report.hpp"
#include "sim/cli/shards.hpp"
#include "sim/common/json_errors.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

namespace {

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open: " + std::strerror(errno));
  std::stringstream text;
  text << in.rdbuf();
  try {
    return nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::exception& e) {  // a parse error, or a number out of range (1e99999)
    throw std::runtime_error(path + ": " + bimloc::sim::jsonProblem(e));
  }
}

struct MergeArgs {
  std::vector<std::string> files;
  bool json = false;
};

void merge(const MergeArgs& args) {
  std::vector<std::pair<std::string, nlohmann::json>> shards;
  for (const auto& file : args.files) shards.emplace_back(file, readJson(file));
  const nlohmann::json report = bimloc::cli::mergeShards(shards);
  if (args.json)
    std::cout << report.dump() << "\n";
  else
    bimloc::cli::printRunTable(report, std::cout);
  for (const auto& s : report["scenarios"])  // as `bimloc run`: status 1 when a scenario failed
    if (!s["passed"].get<bool>()) throw bimloc::cli::ExitCode{bimloc::cli::kExitNotLocalized};
}

}  // namespace

void addReportCommand(CLI::App& app) {
  CLI::App* report = app.add_subcommand("report", "Work on the JSON reports of `bimloc run`.");
  report->require_subcommand(1);
  auto args = std::make_shared<MergeArgs>();
  CLI::App* cmd = report->add_subcommand(
      "merge",
      "Merge the shards of a sweep (`bimloc run ... --shard K/N --json`, K = 1..N) into exactly the report of the\n"
      "unsharded run: its scenarios in the unsharded order, its summary, table or --json (wall_seconds: the shards'\n"
      "sum). Errors on a file that is no shard report, shards of different sweeps, a shard given twice or missing.\n"
      "Exit status as `bimloc run`: 0 every scenario passed, 1 one failed, 2 the shards cannot be used.");
  cmd->add_option("files", args->files, "the shards' JSON files")->required();
  cmd->add_flag("--json", args->json, "print one JSON object instead of the table");
  cmd->callback([args] { merge(*args); });
}
