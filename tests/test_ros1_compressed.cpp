// ROS 1 bags with compressed chunks, as `rosbag record --lz4 / --bz2` write them (issue 29's
// cost item: what real ROS 1 robots record). One simulated recording written three ways by
// rosbag's own writer (`simulate --compression none|lz4|bz2`). The truths: python rosbag (its
// own lz4 binding and python's bz2) reads the same messages, byte for byte, from all three;
// BagInput decodes the same points and poses; `localize` gives the same trajectory, bit for
// bit. And `simulate` refuses a compression the format has not, with exit 2.
#include "bag_fixtures.hpp"
#include "test_support.hpp"

#include "sim/dataset/bag_reader.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>

namespace fs = std::filesystem;
using namespace bimloc;

namespace {

const std::vector<std::string> kCompressions = {"none", "lz4", "bz2"};

// The corridor run of the bag tests, cut to 1.2 s (it converges at its first turn): 12 turns, a
// bz2 bag of 7 MB that writes and reads in under a second of CPU.
const std::string& recorded() {
  std::vector<std::pair<std::string, std::string>> variants;
  for (const auto& c : kCompressions) variants.emplace_back(c, "--compression " + c);
  return test::simulatedVariants("ros1-compressed",
                                 "name: ros1-compressed\nworld: " + test::officePlan() +
                                     "\nstart: {room: C100, yaw_deg: 0}\nmotion: {type: tour, rooms: [R101]}\n"
                                     "duration_s: 1.2\nodometry: {preset: legged}\nseed: 3\n",
                                 variants);
}

std::string bag(const std::string& compression) { return recorded() + "/" + compression + "/dataset.bag"; }

struct Read {
  std::vector<sim::StampedPose> odometry, truth;
  Eigen::Isometry3d T_base_lidar;
  std::vector<double> stamps;
  std::vector<std::vector<Eigen::Vector3f>> points;
  std::vector<std::string> warnings;
};

Read readAll(const std::string& path) {
  Read r;
  const sim::BagInput input(path, sim::BagInputOptions{});
  r.odometry = input.odometry(), r.truth = input.groundTruth(), r.T_base_lidar = input.T_base_lidar();
  input.forEachTurn([&](const sim::BagTurn& t) {
    r.stamps.push_back(t.stamp_s);
    r.points.push_back(t.points());
  });
  r.warnings = input.warnings();
  return r;
}

bool samePoses(const std::vector<sim::StampedPose>& a, const std::vector<sim::StampedPose>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].stamp_s != b[i].stamp_s || a[i].pose.matrix() != b[i].pose.matrix()) return false;
  return true;
}

}  // namespace

TEST(Ros1Compressed, PythonRosbagReadsTheSameMessagesFromEveryCompression) {
  const auto none = nlohmann::json::parse(test::runPython("bag_digest.py", "'" + bag("none") + "'"));
  EXPECT_EQ(none["chunk_compressions"], nlohmann::json::array({"none"}));
  EXPECT_EQ(none["topics"]["/velodyne_points"]["messages"], 12);  // 1.2 s at 10 Hz
  for (const std::string c : {"lz4", "bz2"}) {
    const auto digest = nlohmann::json::parse(test::runPython("bag_digest.py", "'" + bag(c) + "'"));
    EXPECT_EQ(digest["chunk_compressions"], nlohmann::json::array({c})) << "every chunk compressed, with " << c;
    EXPECT_EQ(digest["topics"], none["topics"]) << c;
    EXPECT_LT(fs::file_size(bag(c)), fs::file_size(bag("none"))) << c;
  }
}

TEST(Ros1Compressed, BagInputDecodesTheSamePointsAndPoses) {
  const Read none = readAll(bag("none"));
  ASSERT_EQ(none.points.size(), 12u);
  EXPECT_TRUE(none.warnings.empty());
  for (const std::string c : {"lz4", "bz2"}) {
    const Read r = readAll(bag(c));
    EXPECT_TRUE(samePoses(r.odometry, none.odometry)) << c;
    EXPECT_TRUE(samePoses(r.truth, none.truth)) << c;
    EXPECT_EQ(r.T_base_lidar.matrix(), none.T_base_lidar.matrix()) << c;
    EXPECT_EQ(r.stamps, none.stamps) << c;
    ASSERT_EQ(r.points.size(), none.points.size()) << c;
    for (std::size_t i = 0; i < r.points.size(); ++i) {
      ASSERT_EQ(r.points[i].size(), none.points[i].size()) << c << " turn " << i;
      EXPECT_EQ(std::memcmp(r.points[i].data(), none.points[i].data(), r.points[i].size() * sizeof(Eigen::Vector3f)), 0)
          << c << " turn " << i << ": other bits";
    }
    EXPECT_EQ(r.warnings, none.warnings) << c;
  }
}

TEST(Ros1Compressed, LocalizeGivesTheSameTrajectoryBitForBit) {
  std::string reference;
  nlohmann::json reference_json;
  for (const auto& c : kCompressions) {
    const std::string out = recorded() + "/out-" + c;
    const auto r = test::runBimloc("localize '" + bag(c) + "' --plan '" + test::officePlan() + "' --out '" + out + "' --json");
    ASSERT_EQ(r.exit_code, 0) << c << ": " << r.err;
    const std::string trajectory = test::readFile(out + "/trajectory.tum");
    nlohmann::json json = nlohmann::json::parse(r.out)["scenarios"][0];
    json.erase("wall_seconds"), json.erase("name");  // the input's path and the machine's speed
    for (auto& w : json["warnings"]) {  // "INPUT: message N: ...": the same without the path
      std::string text = w.get<std::string>();
      if (text.rfind(bag(c), 0) == 0) text.erase(0, bag(c).size());
      w = text;
    }
    if (c == "none") {
      reference = trajectory, reference_json = json;
      EXPECT_EQ(std::count(trajectory.begin(), trajectory.end(), '\n'), 13);  // a comment, then every turn
      EXPECT_TRUE(json.value("converged", false));
      continue;
    }
    EXPECT_EQ(trajectory, reference) << c;
    EXPECT_EQ(json, reference_json) << c;
  }
}

// As `rosbag record` offers for ROS 1 and rosbag2's MCAP storage for ROS 2; anything else,
// or a compression of another format, is a bad option: exit 2, said, nothing written.
TEST(Ros1Compressed, SimulateRefusesACompressionTheFormatHasNot) {
  const std::string d = recorded();
  for (const auto& [format, compression] : std::vector<std::pair<std::string, std::string>>{
           {"ros1", "zstd"}, {"mcap", "bz2"}, {"sqlite3", "lz4"}, {"sqlite3", "zstd"}, {"ros1", "gzip"}}) {
    const std::string out = d + "/refused-" + format + "-" + compression;
    const auto r = test::runBimloc("simulate '" + d + "/s.yaml' --out '" + out + "' --format " + format + " --compression " + compression);
    EXPECT_EQ(r.exit_code, 2) << format << " " << compression << ": " << r.err;
    EXPECT_NE(r.err.find("--compression " + compression + ": a " + format + " bag has no such compression"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << out;
  }
}
