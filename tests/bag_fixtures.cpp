#include "bag_fixtures.hpp"

#include "test_support.hpp"

#include "sim/dataset/bag_reader.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

namespace bimloc::test {

const std::string& officePlan() {
  static const std::string plan = std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc";
  return plan;
}

const std::string& simulatedVariants(const std::string& tag, const std::string& scenario_yaml,
                                     const std::vector<std::pair<std::string, std::string>>& variants) {
  static std::map<std::string, std::string> made;
  auto& dir = made[tag];
  if (dir.empty()) {
    dir = tempDir(tag);
    std::ofstream(dir + "/s.yaml") << scenario_yaml;
    for (const auto& [name, options] : variants) {
      const auto r = runBimloc("simulate '" + dir + "/s.yaml' --out '" + dir + "/" + name + "' --quiet " + options);
      if (r.exit_code != 0) ADD_FAILURE() << name << ": " << r.err;
    }
  }
  return dir;
}

const std::string& simulatedCorridor(const std::string& tag, const std::string& simulate_options) {
  return simulatedVariants(tag,
                           "name: " + tag + "\nworld: " + officePlan() +
                               "\nstart: {room: C100, yaw_deg: 0}\nmotion: {type: tour, rooms: [R101]}\n"
                               "duration_s: 8\nodometry: {preset: legged}\nseed: 3\n",
                           {{"data", simulate_options}});
}

std::string rewrittenBag(const std::string& dir, const std::string& mode) {
  const std::string out = dir + "/" + mode + ".bag";
  if (!std::filesystem::exists(out)) {
    const std::string cmd = "/usr/bin/python3 '" + std::string(BIMLOC_TESTS_DIR) + "/rewrite_bag.py' '" + dir +
                            "/data/dataset.bag' '" + out + "' " + mode;
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
  return out;
}

nlohmann::json localizeJson(const std::string& input, const std::string& options) {
  const auto r = runBimloc("localize '" + input + "' --plan '" + officePlan() + "' --json " + options);
  EXPECT_EQ(r.exit_code, 0) << r.err << r.out;
  try {
    auto j = nlohmann::json::parse(r.out)["scenarios"][0];
    j.erase("wall_seconds"), j.erase("name");  // the input's path and the machine's speed
    for (auto& w : j["warnings"]) {  // "INPUT: message N: ...": the same without the path
      std::string text = w.get<std::string>();
      if (text.rfind(input, 0) == 0) text.erase(0, input.size());
      w = text;
    }
    return j;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not JSON: " << r.out << r.err;
    return {};
  }
}

BagReadOutcome readWholeBag(const std::string& path) {
  BagReadOutcome o;
  try {
    sim::BagInput bag(path, sim::BagInputOptions{});
    bag.forEachTurn([&](const sim::BagTurn& t) {
      t.points();
      ++o.turns;
    });
    o.warnings = bag.warnings();
  } catch (const std::runtime_error& e) {
    o.refused = true;
    o.error = e.what();
  }
  return o;
}

std::string runPython(const std::string& script, const std::string& args) {
  return commandOutput("/usr/bin/python3 '" + std::string(BIMLOC_TESTS_DIR) + "/" + script + "' " + args);
}

}  // namespace bimloc::test
