// `bimloc simulate` end to end: the dataset read back by independent readers, the same
// bytes whatever the thread count, and a bad scenario refused with nothing written.
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using bimloc::test::runBimloc;
using bimloc::test::tempDir;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A short version of the default tour, written next to the worlds so its relative path works.
std::string shortScenario(const std::string& dir, double duration_s) {
  const std::string path = dir + "/short.yaml";
  std::ofstream(path) << "name: short tour\n"
                      << "world: " << BIMLOC_WORLDS_DIR << "/site_office.ifc\n"
                      << "start: {room: R101, yaw_deg: 90}\n"
                      << "motion: {type: tour, rooms: [C100]}\n"
                      << "duration_s: " << duration_s << "\n"
                      << "odometry: {preset: legged}\n"
                      << "seed: 5\n";
  return path;
}

}  // namespace

TEST(Simulate, DatasetIsCompleteAndIdenticalWhateverTheThreadCount) {
  const std::string dir = tempDir("simulate");
  const std::string scenario = shortScenario(dir, 2.0);
  const auto one = runBimloc("simulate '" + scenario + "' --out '" + dir + "/t1' --threads 1");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const auto two = runBimloc("simulate '" + scenario + "' --out '" + dir + "/t2' --threads 2");
  ASSERT_EQ(two.exit_code, 0) << two.err;
  std::size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir + "/t1")) {
    if (!e.is_regular_file()) continue;
    ++files;
    const fs::path rel = fs::relative(e.path(), dir + "/t1");
    EXPECT_EQ(slurp(e.path()), slurp(fs::path(dir + "/t2") / rel)) << rel << " differs between 1 and 2 threads";
  }
  EXPECT_GE(files, 20u + 4u);  // 20 turns in 2 s at 10 Hz, bag, TUM files, metadata

  // The bag through Debian's python3-rosbag: topics, types and counts.
  const std::string cmd = "/usr/bin/python3 '" + std::string(BIMLOC_TESTS_DIR) + "/read_bag.py' '" + dir + "/t1/dataset.bag'";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) out += buffer;
  ASSERT_EQ(::pclose(pipe), 0) << out;
  const auto bag = nlohmann::json::parse(out);
  EXPECT_EQ(bag.dump().find("velodyne_points") != std::string::npos, true) << out;
  const auto meta = nlohmann::json::parse(slurp(dir + "/t1/metadata.json"));
  EXPECT_EQ(meta["seed"], 5);
  EXPECT_EQ(meta["format"], "bimloc.dataset");
}

TEST(Simulate, ScenarioWithATypoIsRefusedWithItsLineAndNothingWritten) {
  const std::string dir = tempDir("simulate");
  const std::string path = dir + "/typo.yaml";
  std::ofstream(path) << "world: " << BIMLOC_WORLDS_DIR << "/site_office.ifc\n"
                      << "start: {room: R101}\n"
                      << "duraton: 10\n";
  const auto r = runBimloc("simulate '" + path + "' --out '" + dir + "/out'");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find(path + ":3"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("duration_s"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out"));
}

TEST(Simulate, UnknownRoomListsTheRoomsOfTheStorey) {
  const std::string dir = tempDir("simulate");
  const std::string path = dir + "/room.yaml";
  std::ofstream(path) << "world: " << BIMLOC_WORLDS_DIR << "/site_office.ifc\n"
                      << "start: {room: R999}\n";
  const auto r = runBimloc("simulate '" + path + "' --out '" + dir + "/out'");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("R999"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("R101"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out"));
}
