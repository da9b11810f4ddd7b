// `bimloc run` end to end: the documented JSON, the same results whatever --jobs, snapshots,
// and a failing scenario turning into a non-zero exit.
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using bimloc::test::runBimloc;
using bimloc::test::tempDir;

namespace {

std::string scenario(const std::string& dir, const std::string& name, const std::string& room, int seed, int duration_s = 20) {
  const std::string path = dir + "/" + name + ".yaml";
  std::ofstream(path) << "name: " << name << "\n"
                      << "world: " << BIMLOC_WORLDS_DIR << "/site_office.ifc\n"
                      << "start: {random_in_room: " << room << "}\n"
                      << "motion: {type: tour, rooms: [C100]}\n"
                      << "duration_s: " << duration_s << "\n"
                      << "seed: " << seed << "\n"
                      << "expect: {converge: true, max_convergence_time_s: " << duration_s << "}\n";
  return path;
}

}  // namespace

TEST(Run, JsonIsTheDocumentedObjectAndJobsDoNotChangeIt) {
  const std::string dir = tempDir("run");
  const std::string args = "'" + scenario(dir, "a", "R105", 1, 30) + "' '" + scenario(dir, "b", "S100", 2, 30) + "' --json";
  const auto one = runBimloc("run " + args + " --jobs 1 --out '" + dir + "/snaps'");
  const auto two = runBimloc("run " + args + " --jobs 2");
  auto j1 = nlohmann::json::parse(one.out), j2 = nlohmann::json::parse(two.out);
  ASSERT_EQ(j1["scenarios"].size(), 2u);
  for (const char* key : {"name", "plan", "storey", "start_room", "method", "seed", "converged", "convergence_time_s",
                          "found_room", "position_error_m", "yaw_error_deg", "ate_m", "false_convergence", "passed"})
    EXPECT_TRUE(j1["scenarios"][0].contains(key)) << key;
  for (const char* key : {"runs", "localized", "false_convergences", "median_convergence_s", "sim_seconds", "wall_seconds"})
    EXPECT_TRUE(j1["summary"].contains(key)) << key;
  for (const char* key : {"rpe_m_per_m", "losses", "path_length_m", "wall_deviations"}) EXPECT_TRUE(j1["scenarios"][0].contains(key)) << key;
  for (const char* key : {"median_ate_m", "losses"}) EXPECT_TRUE(j1["summary"].contains(key)) << key;
  EXPECT_EQ(j1["summary"]["false_convergences"], 0);
  // The default method (the paper's: the filter, then the S-Graph) localizes both and tracks.
  for (const auto& s : j1["scenarios"]) {
    EXPECT_EQ(s["method"], "sgraph");
    EXPECT_TRUE(s["converged"]) << s["name"];
    EXPECT_LT(s["ate_m"].get<double>(), 0.1) << s["name"];
    EXPECT_EQ(s["losses"], 0) << s["name"];
    EXPECT_FALSE(s["wall_deviations"].empty()) << s["name"];
  }
  // Everything but the wall-clock figures is the same with 1 or 2 jobs.
  j1["summary"].erase("wall_seconds"), j2["summary"].erase("wall_seconds");
  EXPECT_EQ(j1.dump(), j2.dump());
  EXPECT_EQ(one.exit_code, j1["scenarios"][0]["passed"] && j1["scenarios"][1]["passed"] ? 0 : 1);
  // Snapshots: initialization, clustering and (if converged) convergence, per scenario.
  std::size_t pngs = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir + "/snaps")) pngs += e.path().extension() == ".png";
  EXPECT_GE(pngs, 4u);
  // The S-Graph tracked: each run also has its last picture (the graph) and its error plot.
  for (const char* name : {"a", "b"}) {
    const fs::path run = fs::path(dir) / "snaps" / name;
    EXPECT_TRUE(fs::is_regular_file(run / "errors.png")) << run;
    bool end = false;
    for (const auto& e : fs::directory_iterator(run)) end |= e.path().filename().string().find("_end.png") != std::string::npos;
    EXPECT_TRUE(end) << run << ": no end snapshot";
  }
}

TEST(Run, FailingExpectationsGiveANonZeroExit) {
  const std::string dir = tempDir("run");
  const std::string path = dir + "/stand.yaml";
  // Standing still in one of eight identical offices: it must not converge, so this fails.
  std::ofstream(path) << "world: " << BIMLOC_WORLDS_DIR << "/site_office.ifc\n"
                      << "start: {room: R102}\n"
                      << "duration_s: 3\n"
                      << "expect: {converge: true}\n";
  const auto r = runBimloc("run '" + path + "' --json");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_FALSE(j["scenarios"][0]["converged"]);
  EXPECT_FALSE(j["scenarios"][0]["false_convergence"]);
}

TEST(Run, TraceWritesARowPerWeighingEndingConverged) {
  const std::string dir = tempDir("run");
  const auto r = runBimloc("run '" + scenario(dir, "traced", "S100", 1) + "' --json --trace '" + dir + "/trace'");
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j["scenarios"][0]["converged"]) << r.err;
  std::ifstream csv(dir + "/trace/traced.csv");
  ASSERT_TRUE(csv.good());
  std::string header, line, last;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("time_s,truth_x_m,truth_y_m,truth_yaw_deg,estimate_x_m", 0), 0u) << header;
  int rows = 0;
  while (std::getline(csv, line)) ++rows, last = line;
  // A row per weighing up to the one that converged (with the free-space evidence S100 takes
  // about 7): the last row is at the convergence time.
  EXPECT_GE(rows, 2);
  // converged by the end: the `converged` column (the guide's columns follow it)
  const auto fields = [](const std::string& row) {
    std::vector<std::string> out(1);
    for (char c : row) {
      if (c == ',') out.emplace_back();
      else out.back().push_back(c);
    }
    return out;
  };
  const auto names = fields(header), values = fields(last);
  const auto column = std::find(names.begin(), names.end(), "converged");
  ASSERT_NE(column, names.end()) << header;
  ASSERT_EQ(values.size(), names.size()) << last;
  EXPECT_EQ(values[static_cast<std::size_t>(column - names.begin())], "1") << last;
  EXPECT_NEAR(std::stod(last.substr(0, last.find(','))), j["scenarios"][0]["convergence_time_s"].get<double>(), 1e-6) << last;
  // Nothing but the CSV: no temporary left behind.
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir + "/trace")) ++files;
  EXPECT_EQ(files, 1u);
}

TEST(Run, TheSGraphEstimatesAWallBuiltOffItsPlan) {
  // The default world with one corridor wall built 10 cm and another 20 cm off the plan, one
  // wall missing and a partition: the S-Graph tracks within 0.1 m and estimates both walls
  // within 4 cm of how they were built (site truth). A regression bound for this run; the
  // issue's 3 cm for every wall is not met in general (README, "A site that is not its plan").
  const std::string dir = tempDir("run");
  const std::string path = dir + "/site.yaml";
  std::ofstream(path) << "world: " << BIMLOC_WORLDS_DIR << "/site_office.ifc\n"
                      << "start: {random_in_room: S100}\n"
                      << "motion: {type: tour, rooms: [C100, R105, C100, R102, C100, R108]}\n"
                      << "odometry: {preset: legged}\nduration_s: 120\nseed: 3\n"
                      << "site:\n  walls:\n    partitions: {count: 1}\n    edit:\n"
                      << "      - {id: \"10NJeiAkbO1Jh_iurmjac0\", offset_m: 0.10}\n"
                      << "      - {id: \"1UodGUbwlAzlED$Ch6Qvl7\", offset_m: 0.20}\n"
                      << "      - {id: \"0EmB8zWLG5W42W5JgZy2Sj\", missing: true}\n"
                      << "expect: {converge: true, max_convergence_time_s: 120, max_ate_m: 0.1}\n";
  const auto r = runBimloc("run '" + path + "' --json");
  const auto j = nlohmann::json::parse(r.out);
  const auto& s = j["scenarios"][0];
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(s["site"], "exact");  // the preset the site started from; the edits are its own
  ASSERT_TRUE(s["converged"]) << r.err;
  EXPECT_LT(s["ate_m"].get<double>(), 0.1);
  int checked = 0;
  for (const auto& w : s["wall_deviations"]) {
    if (w["true_offset_m"].is_null() || w["true_offset_m"].get<double>() == 0.0) continue;
    EXPECT_NEAR(w["offset_m"].get<double>(), w["true_offset_m"].get<double>(), 0.04) << w["wall"];
    ++checked;
  }
  EXPECT_EQ(checked, 2);
  ASSERT_FALSE(s["wall_offset_error_m"].is_null());
  EXPECT_LT(s["wall_offset_error_m"].get<double>(), 0.04);
}

// A storey with walls and no room (Jesse.1's 'T.O. level 1 floor': 7 walls, no IfcSpace, none closed
// enough to infer one) has nowhere to start: the error names the plan, the storey and why, not
// "give --plan --all-rooms", which the user did. Exit 2, nothing run.
TEST(Run, AStoreyWithoutRoomsIsNamedNotReportedAsNothingGiven) {
  BIMLOC_REQUIRE_SHARED(plan, "Jesse.1.ifc");
  const auto r = runBimloc("run --plan '" + plan + "' --all-rooms --storey 3 --duration 5");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("Jesse.1.ifc: storey 3 'T.O. level 1 floor' has no rooms"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("nothing to run"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}
