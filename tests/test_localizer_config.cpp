// The `localizer:` block and `--config FILE.yaml`: every documented key reaches its field of
// LocalizerConfig, and every mistake is an error at FILE:LINE.
#include "sim/scenario/localizer_config.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <fstream>

namespace {

using namespace bimloc;
using namespace bimloc::sim;

std::string write(const std::string& text) {
  const std::string path = test::tempDir("localizer-config") + "/config.yaml";
  std::ofstream(path) << text;
  return path;
}

std::string errorOf(const std::string& text) {
  try {
    loadLocalizerConfig(write(text));
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(LocalizerConfig, EveryListedKeyIsReadIntoItsFieldAndNoOther) {
  // Each key set to a value off its default through a config file: that key, and only that
  // key, reads back with the new value (the flat keys of old scenarios alias a sectioned one).
  const auto defaults = localizerKeys();
  int checked = 0;
  for (const auto& [key, value] : defaults) {
    if (key == "method" || key == "storey" || key == "prior_rooms" || key == "prior_pose") continue;
    const auto dot = key.find('.');
    std::string v = value == "true" ? "false" : value == "false" ? "true" : value;
    if (v != "true" && v != "false") {
      const double d = std::stod(v);
      v = std::to_string(d >= 2 ? std::floor(d * 0.8) : d > 0 && d < 1 ? d * 0.5 : d + 1);  // inside every range
    }
    const std::string yaml = dot == std::string::npos ? key + ": " + v + "\n"
                                                      : key.substr(0, dot) + ": {" + key.substr(dot + 1) + ": " + v + "}\n";
    LocalizerSettings s;
    ASSERT_NO_THROW(s = loadLocalizerConfig(write(yaml))) << yaml;
    const auto now = localizerKeys(s.config);
    ASSERT_EQ(now.size(), defaults.size());
    const auto leaf = [](const std::string& k) { return k.substr(k.rfind('.') + 1); };
    int differ = 0;
    for (std::size_t i = 0; i < now.size(); ++i) {
      if (now[i].second == defaults[i].second) continue;
      ++differ;
      EXPECT_EQ(leaf(now[i].first), leaf(key)) << yaml << " changed " << now[i].first;
      EXPECT_DOUBLE_EQ(v == "true" || v == "false" ? (v == "true") : std::stod(v), now[i].second == "true" ? 1.0 : now[i].second == "false" ? 0.0 : std::stod(now[i].second)) << yaml;
    }
    EXPECT_GE(differ, 1) << yaml;
    ++checked;
  }
  EXPECT_GT(checked, 90);
  const auto s = loadLocalizerConfig(write("method: pf-no-rooms\nprior_rooms: [R101, R102]\nprior_pose: [1, 2, 90]\nstorey: auto\n"));
  EXPECT_EQ(s.config.method, LocalizerMethod::PfNoRooms);
  EXPECT_EQ(s.config.pf.prior_rooms, (std::vector<std::string>{"R101", "R102"}));
  ASSERT_TRUE(s.config.pf.prior_pose);
  EXPECT_NEAR(s.config.pf.prior_pose->z(), M_PI / 2, 1e-12);
  EXPECT_TRUE(s.storey_auto);
}

TEST(LocalizerConfig, MistakesAreErrorsAtTheirLine) {
  const auto has = [](const std::string& error, const std::string& part) { return error.find(part) != std::string::npos; };
  std::string e = errorOf("method: sgraph\nsgraph:\n  window_keyframe: 5\n");
  EXPECT_TRUE(has(e, "config.yaml:3: localizer.sgraph.window_keyframe: unknown key (did you mean 'window_keyframes'?)")) << e;
  e = errorOf("pf: {particles: many}\n");
  EXPECT_TRUE(has(e, ":1: localizer.pf.particles: expected a number")) << e;
  e = errorOf("\npf: {particles: 250.5}\n");
  EXPECT_TRUE(has(e, ":2: localizer.pf.particles: expected a whole number")) << e;
  e = errorOf("planes:\n  voxel_size_m: 7\n");
  EXPECT_TRUE(has(e, ":2: localizer.planes.voxel_size_m: 7 is outside")) << e;
  e = errorOf("method: hdl\n");
  EXPECT_TRUE(has(e, ":1: localizer.method: expected sgraph, pf, pf-no-rooms, amcl or ndt")) << e;
  e = errorOf("pf: {use_hypotheses: 1}\n");
  EXPECT_TRUE(has(e, "expected true or false")) << e;
  e = errorOf("sgraph: 3\n");
  EXPECT_TRUE(has(e, ":1: localizer.sgraph: expected a mapping")) << e;
  e = errorOf("[1, 2]\n");
  EXPECT_TRUE(has(e, "expected a mapping of localizer keys")) << e;
  e = errorOf("pf: {zzzz: 1}\n");
  EXPECT_TRUE(has(e, "keys of localizer.pf: particles, ")) << e;
}
