#include "sim/cli/shards.hpp"

#include "sim/cli/run_report.hpp"

#include <cstdint>
#include <cstdio>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>

namespace bimloc::cli {

ShardSpec parseShard(const std::string& text) {
  static const std::regex form(R"(\s*([0-9]{1,6})\s*/\s*([0-9]{1,6})\s*)");
  std::smatch m;
  const std::string expected = "--shard '" + text + "': expected K/N with 1 <= K <= N (e.g. 2/8)";
  if (!std::regex_match(text, m, form)) throw std::invalid_argument(expected);
  ShardSpec s{std::stoi(m[1]), std::stoi(m[2])};
  if (s.count < 1 || s.index < 1 || s.index > s.count) throw std::invalid_argument(expected);
  return s;
}

std::string sweepFingerprint(const std::vector<sim::Scenario>& scenarios) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a offset basis
  const auto add = [&h](const std::string& s) {
    for (const unsigned char c : s + '\x1f') h = (h ^ c) * 1099511628211ull;  // FNV prime
  };
  const auto num = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.17g", v);
    return std::string(b);
  };
  add(std::to_string(scenarios.size()));
  for (const auto& s : scenarios) {
    add(s.name), add(s.world), add(s.storey), add(std::to_string(s.seed)), add(num(s.duration_s));
    add(std::to_string(static_cast<int>(s.start.kind))), add(s.start.room);
    for (int i = 0; i < 3; ++i) add(num(s.start.pose[i]));
    add(s.start.yaw_rad ? num(*s.start.yaw_rad) : "-");
    add(s.localizer.dump()), add(s.site.preset);
    add(num(s.expect.max_convergence_time_s) + num(s.expect.max_position_error_m) + num(s.expect.max_yaw_error_deg) +
        num(s.expect.max_ate_m) + (s.expect.converge ? "1" : "0"));
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

nlohmann::json shardJson(const ShardSpec& shard, std::size_t total, const std::string& fingerprint,
                         const std::vector<std::size_t>& positions) {
  return {{"index", shard.index}, {"count", shard.count}, {"sweep_scenarios", total}, {"sweep", fingerprint},
          {"positions", positions}};
}

namespace {

struct Shard {
  std::string file;
  ShardSpec spec;
  std::size_t total = 0;
  std::string sweep;
  std::vector<std::size_t> positions;
  const nlohmann::json* scenarios = nullptr;
};

Shard readShard(const std::string& file, const nlohmann::json& report) {
  const auto bad = [&file](const std::string& why) { return std::runtime_error(file + ": " + why); };
  if (!report.is_object() || !report.contains("shard"))
    throw bad("not the JSON of a sharded run (no \"shard\" object: made by `bimloc run ... --shard K/N --json`?)");
  try {
    Shard s;
    s.file = file;
    const auto& m = report.at("shard");
    s.spec = {m.at("index").get<int>(), m.at("count").get<int>()};
    s.total = m.at("sweep_scenarios").get<std::size_t>();
    s.sweep = m.at("sweep").get<std::string>();
    s.positions = m.at("positions").get<std::vector<std::size_t>>();
    s.scenarios = &report.at("scenarios");
    if (s.spec.count < 1 || s.spec.index < 1 || s.spec.index > s.spec.count) throw bad("shard index out of range");
    if (!s.scenarios->is_array() || s.scenarios->size() != s.positions.size())
      throw bad("has " + std::to_string(s.scenarios->size()) + " scenarios but " + std::to_string(s.positions.size()) +
                " positions");
    for (const std::size_t p : s.positions)
      if (p >= s.total || !s.spec.contains(p))
        throw bad("position " + std::to_string(p) + " is not in shard " + std::to_string(s.spec.index) + "/" +
                  std::to_string(s.spec.count) + " of a sweep of " + std::to_string(s.total));
    report.at("summary").at("wall_seconds").get<double>();
    // Every entry has what the summary and the table read: both made here, where the file is
    // known, rather than failing on the merged report with the library's words only.
    std::ostringstream table;
    printRunTable({{"scenarios", *s.scenarios}, {"summary", runSummary(*s.scenarios, 0)}}, table);
    return s;
  } catch (const nlohmann::json::exception& e) {
    throw bad(std::string("malformed shard report: ") + e.what());
  }
}

}  // namespace

nlohmann::json mergeShards(const std::vector<std::pair<std::string, nlohmann::json>>& inputs) {
  if (inputs.empty()) throw std::runtime_error("no shard files given");
  std::vector<Shard> shards;
  for (const auto& [file, report] : inputs) shards.push_back(readShard(file, report));
  const Shard& first = shards.front();
  std::map<int, std::string> seen;  // shard index -> file
  for (const Shard& s : shards) {
    if (s.sweep != first.sweep || s.total != first.total || s.spec.count != first.spec.count)
      throw std::runtime_error("mixed sweeps: " + first.file + " is shard " + std::to_string(first.spec.index) + "/" +
                               std::to_string(first.spec.count) + " of sweep " + first.sweep + " (" +
                               std::to_string(first.total) + " scenarios), " + s.file + " is shard " +
                               std::to_string(s.spec.index) + "/" + std::to_string(s.spec.count) + " of sweep " + s.sweep +
                               " (" + std::to_string(s.total) + " scenarios)");
    const auto [at, fresh] = seen.emplace(s.spec.index, s.file);
    if (!fresh)
      throw std::runtime_error("overlapping shards: " + at->second + " and " + s.file + " are both shard " +
                               std::to_string(s.spec.index) + "/" + std::to_string(s.spec.count));
  }
  std::string missing;
  for (int k = 1; k <= first.spec.count; ++k)
    if (!seen.count(k)) missing += (missing.empty() ? "" : ", ") + std::to_string(k) + "/" + std::to_string(first.spec.count);
  if (!missing.empty()) throw std::runtime_error("missing shards: " + missing + " (of sweep " + first.sweep + ")");

  std::vector<const nlohmann::json*> ordered(first.total, nullptr);
  double wall_seconds = 0;
  for (std::size_t i = 0; i < shards.size(); ++i) {
    const Shard& s = shards[i];
    for (std::size_t j = 0; j < s.positions.size(); ++j) {
      if (ordered[s.positions[j]])
        throw std::runtime_error(s.file + ": scenario " + std::to_string(s.positions[j]) + " is in another shard too");
      ordered[s.positions[j]] = &(*s.scenarios)[j];
    }
    wall_seconds += inputs[i].second.at("summary").at("wall_seconds").get<double>();
  }
  nlohmann::json scenarios = nlohmann::json::array();
  for (std::size_t p = 0; p < ordered.size(); ++p) {
    if (!ordered[p]) throw std::runtime_error("scenario " + std::to_string(p) + " of sweep " + first.sweep + " is in no shard");
    scenarios.push_back(*ordered[p]);
  }
  nlohmann::json summary;
  try {
    summary = runSummary(scenarios, wall_seconds);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(std::string("a shard's scenario entries are malformed: ") + e.what());
  }
  return {{"scenarios", std::move(scenarios)}, {"summary", std::move(summary)}};
}

}  // namespace bimloc::cli
