// ROS 2 bags in and out through the real binary (issue 29 §1, §2, acceptance "same result
// whatever the format"): one scenario simulated as a ROS 1 bag, a rosbag2 MCAP bag and a
// rosbag2 SQLite3 bag; `localize` gives the same trajectory.tum on all of them. The truths: the
// ROS 1 path (rosbag, Debian's), python3's sqlite3 module for the .db3, yaml-cpp for the
// metadata; the npm oracle (tests/npm) checks the MCAP bytes against Foxglove's reader.
#include "bag_fixtures.hpp"
#include "test_support.hpp"

#include "sim/ros2/messages.hpp"
#include "sim/ros2/rosbag2_reader.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

namespace fs = std::filesystem;
using namespace bimloc;
using test::runBimloc;

namespace {

const std::string kPlan = std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc";

std::string slurp(const std::string& path) { return test::readFile(path); }

// The scenario of test_bag_input (the corridor, converging within 2 s), in three formats.
const std::string& simulated() {
  return test::simulatedVariants("ros2-bags",
                                 "name: ros2 bags\nworld: " + kPlan +
                                     "\nstart: {room: C100, yaw_deg: 0}\nmotion: {type: tour, rooms: [R101]}\n"
                                     "duration_s: 8\nodometry: {preset: legged}\nseed: 3\n",
                                 {{"ros1", "--format ros1"}, {"mcap", "--format mcap"}, {"sqlite3", "--format sqlite3"}});
}

std::string python(const std::string& code, const std::string& arg) {
  return test::commandOutput("/usr/bin/python3 -c \"" + code + "\" '" + arg + "'");
}

}  // namespace

// metadata.yaml as `ros2 bag record` writes it, the counts of the ROS 1 bag (metadata.json),
// the ROS 2 types, and the .db3's rows as python3's sqlite3 module counts them.
TEST(Ros2Bags, SimulateWritesRosbag2FoldersAsRosbag2Does) {
  const std::string d = simulated();
  const nlohmann::json ros1 = nlohmann::json::parse(slurp(d + "/ros1/metadata.json"))["topics"];
  const std::map<std::string, std::string> types = {{"/velodyne_points", "sensor_msgs/msg/PointCloud2"},
                                                    {"/odom", "nav_msgs/msg/Odometry"},
                                                    {"/tf", "tf2_msgs/msg/TFMessage"},
                                                    {"/ground_truth", "nav_msgs/msg/Odometry"}};
  for (const std::string format : {"mcap", "sqlite3"}) {
    const std::string bag = d + "/" + format + "/rosbag2";
    EXPECT_FALSE(fs::exists(d + "/" + format + "/dataset.bag"));
    const YAML::Node info = YAML::LoadFile(bag + "/metadata.yaml")["rosbag2_bagfile_information"];
    EXPECT_GE(info["version"].as<int>(), 5);
    EXPECT_EQ(info["storage_identifier"].as<std::string>(), format);
    const std::string file = format == "mcap" ? "rosbag2_0.mcap" : "rosbag2_0.db3";
    EXPECT_EQ(info["relative_file_paths"][0].as<std::string>(), file);
    std::size_t total = 0;
    for (const auto& t : info["topics_with_message_count"]) {
      const std::string name = t["topic_metadata"]["name"].as<std::string>();
      EXPECT_EQ(t["topic_metadata"]["type"].as<std::string>(), types.at(name));
      EXPECT_EQ(t["topic_metadata"]["serialization_format"].as<std::string>(), "cdr");
      EXPECT_NE(t["topic_metadata"]["offered_qos_profiles"].as<std::string>().find("reliability: 1"), std::string::npos);
      EXPECT_EQ(t["message_count"].as<std::size_t>(), ros1[name]["messages"].get<std::size_t>()) << format << " " << name;
      total += t["message_count"].as<std::size_t>();
    }
    EXPECT_EQ(info["message_count"].as<std::size_t>(), total);
    EXPECT_GT(info["duration"]["nanoseconds"].as<std::uint64_t>(), 7000000000u);
    EXPECT_GT(info["starting_time"]["nanoseconds_since_epoch"].as<std::uint64_t>(), 999000000000u);  // time + 1000 s
    // Our reader agrees with the metadata.
    const sim::ros2::Rosbag2Reader reader(bag);
    EXPECT_EQ(reader.storageIdentifier(), format);
    for (const auto& t : reader.topics()) EXPECT_EQ(t.messages, ros1[t.name]["messages"].get<std::size_t>()) << t.name;
    EXPECT_TRUE(reader.warnings().empty());
  }
  // The SQLite3 file, as Python reads it: the rows per topic and the first odometry's stamp.
  const std::string rows = python(
      "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); "
      "print(*c.execute('select t.name, t.type, count(*) from messages m join topics t on t.id=m.topic_id group by t.name order by t.name').fetchall(), sep=chr(10))",
      d + "/sqlite3/rosbag2/rosbag2_0.db3");
  for (const auto& [topic, type] : types)
    EXPECT_NE(rows.find("('" + topic + "', '" + type + "', " + std::to_string(ros1[topic]["messages"].get<std::size_t>()) + ")"),
              std::string::npos)
        << rows;
}

// Acceptance: the same trajectory.tum from the ROS 1 bag, the rosbag2 MCAP folder, its .mcap
// file alone, and the rosbag2 SQLite3 folder; localized.mcap for the ROS 2 inputs.
TEST(Ros2Bags, LocalizeGivesTheSameTrajectoryWhateverTheFormat) {
  const std::string d = simulated();
  const std::vector<std::pair<std::string, std::string>> inputs = {
      {"ros1", d + "/ros1/dataset.bag"},
      {"mcap", d + "/mcap/rosbag2"},
      {"mcap_file", d + "/mcap/rosbag2/rosbag2_0.mcap"},
      {"sqlite3", d + "/sqlite3/rosbag2"}};
  std::string reference;
  for (const auto& [name, input] : inputs) {
    const std::string out = d + "/out_" + name;
    const auto r = runBimloc("localize '" + input + "' --plan '" + kPlan + "' --out '" + out + "'");
    EXPECT_EQ(r.exit_code, 0) << name << ": " << r.err << r.out;
    const std::string trajectory = slurp(out + "/trajectory.tum");
    EXPECT_GT(std::count(trajectory.begin(), trajectory.end(), '\n'), 20) << name;
    if (reference.empty()) reference = trajectory;
    EXPECT_EQ(trajectory, reference) << name << ": a different trajectory.tum than from the ROS 1 bag";
    const bool ros2 = name != "ros1";
    EXPECT_EQ(fs::exists(out + "/localized.mcap"), ros2) << name;
    EXPECT_EQ(fs::exists(out + "/localized.bag"), !ros2) << name;
    if (!ros2) continue;
    EXPECT_NE(r.out.find("localized.mcap"), std::string::npos) << r.out;
    // localized.mcap: the input's messages, /tf map -> odom and /localization at each
    // localized turn, the plan once (latched).
    const sim::ros2::Rosbag2Reader in(input), loc(out + "/localized.mcap");
    for (const auto& t : in.topics()) {
      const auto* copy = loc.topic(t.name);
      ASSERT_NE(copy, nullptr) << t.name;
      if (t.name != "/tf") {
        EXPECT_EQ(copy->messages, t.messages) << t.name;
      }
    }
    const std::size_t localized = static_cast<std::size_t>(std::count(trajectory.begin(), trajectory.end(), '\n')) -
                                  static_cast<std::size_t>(trajectory.rfind("#", 0) == 0 ? 1 : 0);
    ASSERT_NE(loc.topic("/localization"), nullptr);
    EXPECT_EQ(loc.topic("/localization")->type, "geometry_msgs/msg/PoseWithCovarianceStamped");
    EXPECT_EQ(loc.topic("/tf")->messages, in.topic("/tf")->messages + loc.topic("/localization")->messages);
    EXPECT_GE(loc.topic("/localization")->messages + 2, localized);
    const auto* plan = loc.topic("/bimloc/plan");
    ASSERT_NE(plan, nullptr);
    EXPECT_EQ(plan->type, "visualization_msgs/msg/MarkerArray");
    EXPECT_EQ(plan->messages, 1u);
    EXPECT_NE(plan->offered_qos_profiles.find("durability: 1"), std::string::npos);  // transient_local: latched
    std::size_t wall_lines = 0, rooms = 0;
    loc.forEachMessage({"/bimloc/plan"}, [&](const sim::ros2::BagMessage& m) {
      sim::ros2::CdrReader cdr(m.data, m.size, m.where);
      for (const auto& marker : sim::ros2::readMarkerArray(cdr).markers) {
        EXPECT_EQ(marker.header.frame_id, "map");
        if (marker.ns == "walls") wall_lines = marker.points.size() / 2;
        if (marker.ns == "room_names") ++rooms;
      }
    });
    EXPECT_GT(wall_lines, 20u);
    EXPECT_GE(rooms, 3u);
  }
}

// A recording cut off by a crash (no summary, the last chunk cut): read as far as it goes, with
// a warning naming the byte offset.
TEST(Ros2Bags, ACutRecordingIsReadAsFarAsItGoesWithAWarning) {
  const std::string d = simulated();
  const std::string cut = d + "/cut.mcap";
  const std::string whole = slurp(d + "/mcap/rosbag2/rosbag2_0.mcap");
  std::ofstream(cut, std::ios::binary) << whole.substr(0, whole.size() * 2 / 3);
  const sim::ros2::Rosbag2Reader reader(cut);
  ASSERT_FALSE(reader.warnings().empty());
  bool names_offset = false;
  for (const auto& w : reader.warnings()) names_offset = names_offset || (w.find(cut + ": cut short at byte ") == 0);
  EXPECT_TRUE(names_offset) << reader.warnings().front();
  const sim::ros2::Rosbag2Reader full(d + "/mcap/rosbag2/rosbag2_0.mcap");
  const auto* clouds = reader.topic("/velodyne_points");
  ASSERT_NE(clouds, nullptr);
  EXPECT_GT(clouds->messages, 0u);
  EXPECT_LT(clouds->messages, full.topic("/velodyne_points")->messages);
  const auto r = runBimloc("localize '" + cut + "' --plan '" + kPlan + "' --json");
  EXPECT_NE(r.err.find("cut short at byte"), std::string::npos) << r.err;
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.err;  // ran: localized or not
}

// A bag without the clouds' topic (the real nebula packets) is refused with the bag's topics listed.
TEST(Ros2Bags, APacketBagIsRefusedWithItsTopicsListed) {
  const fs::path dir = fs::path(BIMLOC_SHARED_REALDATA_DIR) / "nebula" / "40p";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) GTEST_SKIP() << dir << " not found: skipping";
  std::string bag;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_directory()) bag = e.path().string();
  const auto r = runBimloc("localize '" + bag + "' --plan '" + kPlan + "'");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find(bag + ": no topic /velodyne_points"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("/pandar_packets (pandar_msgs/msg/PandarScan, 4 messages)"), std::string::npos) << r.err;
}
