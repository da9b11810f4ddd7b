// A damaged dataset is refused as a whole before `localize` uses any of it (issue 10, items 9
// and 10). The truth is the damage each test does to a dataset `bimloc simulate` wrote: the
// error names the damaged file (and line) and what is wrong with it, in words of our own.
#include "plan_mutation.hpp"
#include "test_support.hpp"

#include "sim/dataset/dataset_reader.hpp"
#include "sim/common/json_errors.hpp"
#include "sim/world/world.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>

namespace fs = std::filesystem;
using namespace bimloc;
using namespace bimloc::test;

namespace {

// One short dataset for every test of the file: 1 s, 10 scans.
const std::string& cleanDataset() {
  static const std::string dir = [] {
    const std::string root = tempDir("validation");
    const std::string scenario = root + "/s.yaml";
    std::ofstream(scenario) << "name: short\nworld: " << BIMLOC_WORLDS_DIR << "/site_office.ifc\n"
                            << "start: {room: R101, yaw_deg: 90}\nmotion: {type: tour, rooms: [C100]}\n"
                            << "duration_s: 1\nodometry: {preset: legged}\nseed: 5\n";
    const auto r = runBimloc("simulate '" + scenario + "' --out '" + root + "/data' --quiet");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return root + "/data";
  }();
  return dir;
}

// A copy of the clean dataset with one file edited; returns its folder.
std::string damaged(const std::string& file, const std::function<std::string(const std::string&)>& edit) {
  const std::string dir = tempDir("damaged") + "/data";
  fs::copy(cleanDataset(), dir, fs::copy_options::recursive);
  const std::string path = dir + "/" + file;
  const std::string text = edit(slurp(path));
  fs::remove(path);
  if (!text.empty()) writeFile(dir, file, text);
  return dir;
}

std::string replaceRegex(const std::string& text, const std::string& pattern, const std::string& by) {
  const std::string out = std::regex_replace(text, std::regex(pattern), by, std::regex_constants::format_first_only);
  EXPECT_NE(out, text) << pattern;
  return out;
}

// readDataset must throw, naming `where` and saying `problem`.
void expectRefused(const std::string& dir, const std::string& where, const std::string& problem) {
  try {
    sim::readDataset(dir);
    ADD_FAILURE() << "accepted: " << where << " " << problem;
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(dir + "/" + where + ": "), std::string::npos) << what;
    EXPECT_NE(what.find(problem), std::string::npos) << what;
    EXPECT_EQ(what.find("json.exception"), std::string::npos) << what;
  }
}

}  // namespace

TEST(DatasetValidation, TheCleanDatasetReadsWhole) {
  const auto d = sim::readDataset(cleanDataset());
  ASSERT_EQ(d.scans.size(), 10u);
  for (const auto& scan : d.scans) EXPECT_EQ(sim::readPcdPoints(scan.file).size(), scan.points);
  EXPECT_GT(d.odometry.size(), 10u);
}

TEST(DatasetValidation, IndexRowsMustPointAtSoundPcdFiles) {
  expectRefused(damaged("clouds/000003.pcd", [](auto) { return std::string(); }), "clouds/index.csv:5",
                "clouds/000003.pcd is missing");
  expectRefused(damaged("clouds/000004.pcd", [](const std::string& t) { return t.substr(0, t.size() - 22); }),
                "clouds/000004.pcd", "bytes of data, the file has");
  expectRefused(damaged("clouds/000004.pcd", [](const std::string& t) { return replaceRegex(t, "POINTS ", "POINTS 1"); }),
                "clouds/000004.pcd", "is not WIDTH x HEIGHT");
  // A garbled VERSION (found by the fuzz test, seed 17004: "0.7" -> "nan") says the header is damaged.
  expectRefused(damaged("clouds/000004.pcd", [](const std::string& t) { return replaceRegex(t, "VERSION 0.7", "VERSION nan"); }),
                "clouds/000004.pcd", "VERSION 'nan' is none of the PCD format's 0.5, 0.6, 0.7");
  expectRefused(damaged("clouds/index.csv", [](const std::string& t) { return replaceRegex(t, "\n000001.pcd,", "\n../x,"); }),
                "clouds/index.csv:3", "'../x' is not a file name in clouds/");
}

TEST(DatasetValidation, StampsMustBeFiniteAndIncreasing) {
  expectRefused(damaged("clouds/index.csv", [](const std::string& t) { return replaceRegex(t, ",1000\\.1[0-9]*,", ",nan,"); }),
                "clouds/index.csv:3", "stamp is not a finite number");
  expectRefused(damaged("clouds/index.csv", [](const std::string& t) { return replaceRegex(t, ",1000\\.2[0-9]*,", ",999,"); }),
                "clouds/index.csv:4", "does not follow the previous one");
  expectRefused(damaged("odometry.tum", [](const std::string& t) { return replaceRegex(t, "\n1000\\.0[0-9]* ", "\nabc "); }),
                "odometry.tum:2", "expected 'timestamp tx ty tz qx qy qz qw'");
  expectRefused(damaged("odometry.tum", [](const std::string& t) { return replaceRegex(t, "\n1000\\.0[0-9]* ", "\n1000.9 "); }),
                "odometry.tum:3", "does not follow the previous one");
}

TEST(DatasetValidation, CloudsAndOdometryMustOverlapInTime) {
  // Every odometry stamp 100 s later: still increasing, never beside a cloud.
  const std::string dir = damaged("odometry.tum", [](const std::string& t) {
    std::string out;
    std::istringstream in(t);
    for (std::string line; std::getline(in, line);) {
      if (line.empty() || line[0] == '#') {
        out += line + "\n";
        continue;
      }
      const auto blank = line.find(' ');
      out += std::to_string(std::stod(line.substr(0, blank)) + 100.0) + line.substr(blank) + "\n";
    }
    return out;
  });
  try {
    sim::readDataset(dir);
    ADD_FAILURE() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the clouds (1000 to 1000.9 s) and odometry.tum (1100"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("never overlap in time"), std::string::npos) << e.what();
  }
}

// A sample of odometry.tum (or ground_truth.tum) that is no pose is dropped and counted, as
// the bag readers do (issue 29 §5): a value "nan" or "inf" (stamp or pose), a zero quaternion,
// one off unit norm. The truth: the lines this test damaged. A file of nothing else is refused.
TEST(DatasetValidation, OdometrySamplesThatAreNoPoseAreDroppedAndCounted) {
  const auto clean = sim::readDataset(cleanDataset());
  const std::string dir = damaged("odometry.tum", [](const std::string& t) {
    std::string out = replaceRegex(t, "\n(1000\\.0[0-9]* \\S+) \\S+ ", "\n$1 nan ");      // line 2: y
    out = replaceRegex(out, "\n1000\\.06[0-9]* ", "\nnan ");                                // a stamp
    out = replaceRegex(out, "\n(1000\\.1[0-9]* \\S+ \\S+ \\S+) \\S+ \\S+ \\S+ \\S+\n", "\n$1 0 0 0 0\n");
    out = replaceRegex(out, "\n(1000\\.2[0-9]* \\S+ \\S+ \\S+) \\S+ \\S+ \\S+ \\S+\n", "\n$1 0 0 0 2\n");
    return replaceRegex(out, "\n(1000\\.3[0-9]* \\S+ \\S+) \\S+ ", "\n$1 -inf ");        // z
  });
  const auto d = sim::readDataset(dir);
  EXPECT_EQ(d.odometry_drops.read, clean.odometry.size());
  EXPECT_EQ(d.odometry_drops.non_finite, 3u);
  EXPECT_EQ(d.odometry_drops.zero_quaternion, 1u);
  EXPECT_EQ(d.odometry_drops.not_unit_quaternion, 1u);
  EXPECT_EQ(d.odometry.size(), clean.odometry.size() - 5);
  for (const auto& p : d.odometry) EXPECT_TRUE(p.pose.matrix().allFinite());
  EXPECT_EQ(clean.odometry_drops.dropped(), 0u);
  EXPECT_EQ(clean.odometry_drops.read, clean.odometry.size());

  // `bimloc localize` runs, and says what it dropped.
  const auto r = runBimloc("localize '" + dir + "' --plan '" + std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc' --json");
  EXPECT_NE(r.exit_code, 2) << r.err;
  const auto s = nlohmann::json::parse(r.out).at("scenarios").at(0).at("recording").at("odometry");
  EXPECT_EQ(s.at("read"), clean.odometry.size());
  EXPECT_EQ(s.at("non_finite"), 3);
  EXPECT_EQ(s.at("dropped"), 5);
  EXPECT_NE(r.err.find("odometry: 5 of " + std::to_string(clean.odometry.size()) + " samples dropped (3 not finite"),
            std::string::npos) << r.err;

  // Nothing but such samples: no odometry at all, refused.
  expectRefused(damaged("odometry.tum", [](const std::string& t) {
                  return std::regex_replace(t, std::regex("\n(\\S+) \\S+ "), "\n$1 nan ");
                }),
                "odometry.tum", "no poses: all " + std::to_string(clean.odometry.size()) + " samples are no pose (" +
                                    std::to_string(clean.odometry.size()) + " not finite");
}

TEST(DatasetValidation, QuaternionsMustHaveUnitNorm) {
  expectRefused(damaged("metadata.json", [](const std::string& t) {
                  auto doc = nlohmann::json::parse(t);
                  doc["T_base_lidar"]["quaternion_xyzw"] = {0, 0, 0, 0};
                  return doc.dump();
                }),
                "metadata.json", "does not have unit norm");
}

TEST(DatasetValidation, MetadataMustBeOfASupportedVersionAndSaySoInOurWords) {
  const auto edit = [](const std::function<void(nlohmann::json&)>& f) {
    return [f](const std::string& t) {
      auto doc = nlohmann::json::parse(t);
      f(doc);
      return doc.dump();
    };
  };
  expectRefused(damaged("metadata.json", edit([](auto& d) { d["version"] = 99; })), "metadata.json",
                "version 99 is not supported (this bimloc reads version 1)");
  expectRefused(damaged("metadata.json", edit([](auto& d) { d.erase("T_base_lidar"); })), "metadata.json",
                "missing key 'T_base_lidar'");
  expectRefused(damaged("metadata.json", edit([](auto& d) { d["T_base_lidar"].erase("xyz"); })), "metadata.json",
                "missing key 'T_base_lidar.xyz'");
  expectRefused(damaged("metadata.json", [](auto) { return std::string("{\"version\": 1,"); }), "metadata.json",
                "not valid JSON: parse error at line 1");
}

// Through the binary: one line naming the file, exit 2 (the input cannot be used).
TEST(DatasetValidation, LocalizeRefusesADamagedDatasetWithExitTwo) {
  const std::string dir = damaged("clouds/000007.pcd", [](auto) { return std::string(); });
  const auto r = runBimloc("localize '" + dir + "' --plan '" + BIMLOC_WORLDS_DIR + "/site_office.ifc'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(dir + "/clouds/index.csv:9: " + dir + "/clouds/000007.pcd is missing"), std::string::npos) << r.err;
}

// nlohmann's own words never reach the user (issue 10, item 10), wherever JSON is read.
TEST(JsonErrors, LibraryTextBecomesOurs) {
  try {
    (void)nlohmann::json::object().at("T_base_lidar");
  } catch (const std::exception& e) {
    EXPECT_EQ(sim::jsonProblem(e), "missing key 'T_base_lidar'");
  }
  const std::string dir = tempDir("json");
  writeFile(dir, "building.json", R"({"format": "bimloc.building", "version": 1})");
  try {
    (void)sim::World::fromExtractDir(dir);
    ADD_FAILURE() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).find("json.exception"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(dir + "/building.json: "), std::string::npos) << e.what();
  }
}
