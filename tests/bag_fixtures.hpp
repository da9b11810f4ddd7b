// The short simulated recording the bag tests share: the office plan from the corridor (it
// converges within 2 s), the bag rewritten by python rosbag as other robots record theirs
// (tests/rewrite_bag.py), and `bimloc localize --json` on it.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace bimloc::test {

// worlds/site_office.ifc.
const std::string& officePlan();
// A folder holding s.yaml (the scenario text `scenario_yaml`) and, per variant (NAME, OPTIONS),
// DIR/NAME: the output of `bimloc simulate s.yaml --quiet OPTIONS`. Made once per tag in this
// process (a failed simulate is a test failure naming the variant).
const std::string& simulatedVariants(const std::string& tag, const std::string& scenario_yaml,
                                     const std::vector<std::pair<std::string, std::string>>& variants);
// A folder holding s.yaml and data/ (the dataset of `bimloc simulate ... SIMULATE_OPTIONS`),
// made once per tag in this process.
const std::string& simulatedCorridor(const std::string& tag, const std::string& simulate_options = "");
// DIR/MODE.bag: DIR/data/dataset.bag rewritten in that mode, made once.
std::string rewrittenBag(const std::string& dir, const std::string& mode);
// The run's entry of `bimloc localize INPUT --plan office --json OPTIONS`, without what depends
// on the input's path or the machine (name, wall_seconds, the path in warnings).
nlohmann::json localizeJson(const std::string& input, const std::string& options = "");
// What the input layer of `localize` makes of a bag (BagInput: topics, odometry, tf, every cloud
// decoded): refused with the error, or read with the turns and the warnings, asked after the
// read (some are found only as the messages are read).
struct BagReadOutcome {
  bool refused = false;
  std::string error;
  std::vector<std::string> warnings;
  std::size_t turns = 0;
};
BagReadOutcome readWholeBag(const std::string& path);
// Standard output of /usr/bin/python3 tests/SCRIPT ARGS (ARGS shell-quoted by the caller).
std::string runPython(const std::string& script, const std::string& args);

}  // namespace bimloc::test
