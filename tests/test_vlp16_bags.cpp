// The VLP-16's packets and the other drivers' point layouts through the command line (issue
// 29, parts 3 and 4): `bimloc simulate --packets` writes /velodyne_packets and velodyne.pcap,
// python rosbag reads the packets back (its message class rebuilt from the definition the bag
// stores), and `bimloc localize` runs on the packets and on the clouds rewritten into Ouster's,
// Hesai's and a time-less layout by python rosbag. The truth of the runs: the same bag's
// /velodyne_points, which the decoder of the packets must match.
#include "bag_fixtures.hpp"
#include "test_support.hpp"

#include "sim/lidar/vlp16_packet.hpp"
#include "sim/lidar/vlp16_turns.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace bimloc;
using test::runBimloc;

namespace {

const std::string& kPlan = test::officePlan();

// One short simulation with packets for the whole file (the corridor start of test_bag_input).
const std::string& simulated() { return test::simulatedCorridor("vlp16-bags", "--packets"); }

std::string rewritten(const std::string& mode) { return test::rewrittenBag(simulated(), mode); }

using test::localizeJson;
using test::runPython;

}  // namespace

TEST(Vlp16Bags, SimulateWritesThePacketsInTheBagAndThePcap) {
  const std::string data = simulated() + "/data";
  const auto meta = nlohmann::json::parse(std::ifstream(data + "/metadata.json"));
  EXPECT_EQ(meta["topics"]["/velodyne_packets"]["type"], "velodyne_msgs/VelodyneScan") << meta["topics"].dump();
  EXPECT_EQ(meta["topics"]["/velodyne_packets"]["messages"], 80);
  ASSERT_TRUE(fs::exists(data + "/velodyne.pcap"));
  // ROS's own reader: genmsg's MD5 sum, one message a turn of 76 packets, stamped as the clouds.
  const std::string json = runPython("read_velodyne_scan.py", "'" + data + "/dataset.bag' /velodyne_packets");
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(json)) << json;
  EXPECT_EQ(j["type"], "velodyne_msgs/VelodyneScan");
  EXPECT_EQ(j["md5sum"], "50804fc9533a0e579e6322c04ae70566");
  EXPECT_EQ(j["messages"], 80);
  for (const auto& n : j["packets"]) EXPECT_EQ(n, 76);
  EXPECT_EQ(j["frames"][0], "velodyne");
  EXPECT_NEAR(j["stamps"][0].get<double>(), 1000.0, 1e-9);
  EXPECT_NEAR(j["first_packet_stamp"].get<double>(), 1000.0, 1e-9);
  // The first packet as python read it decodes to the start of a turn.
  const std::string hex = j["first_packet_hex"];
  ASSERT_EQ(hex.size(), 2 * sim::kVlp16PacketBytes);
  std::vector<std::uint8_t> bytes(sim::kVlp16PacketBytes);
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(std::stoi(hex.substr(2 * i, 2), nullptr, 16));
  std::vector<sim::Vlp16Point> points;
  sim::decodeVlp16Packet(bytes.data(), bytes.size(), 1000.0, {}, points, "first packet");
  ASSERT_FALSE(points.empty());
  EXPECT_LT(points.front().azimuth_deg, 0.01);
  EXPECT_NEAR(bytes[1204], 0x37, 0);
  // The pcap holds the same stream: 80 turns of 76 datagrams.
  const std::string pcap = runPython("read_pcap.py", "'" + data + "/velodyne.pcap' '" + simulated() + "/payloads.bin'");
  nlohmann::json p;
  ASSERT_NO_THROW(p = nlohmann::json::parse(pcap)) << pcap;
  EXPECT_EQ(p["packets"], 80 * 76);
  EXPECT_EQ(p["bad_udp_checksums"], 0);
  EXPECT_NEAR(p["first_stamp"].get<double>(), 1000.0, 1e-6);
}

TEST(Vlp16Bags, LocalizeOnThePacketsLikeOnTheClouds) {
  const std::string bag = simulated() + "/data/dataset.bag";
  const auto clouds = localizeJson(bag);
  const auto packets = localizeJson(bag, "--cloud-topic /velodyne_packets");
  ASSERT_TRUE(clouds["converged"]);
  EXPECT_EQ(packets["converged"], true);
  EXPECT_EQ(packets["false_convergence"], false);
  EXPECT_EQ(packets["found_room"], clouds["found_room"]);
  // The same turns within the packets' 2 mm and 0.01 deg: the same place, nearly the same pose.
  EXPECT_NEAR(packets["position_error_m"].get<double>(), clouds["position_error_m"].get<double>(), 0.02);
  const auto r = runBimloc("localize '" + bag + "' --plan '" + kPlan + "' --cloud-topic /velodyne_packets");
  EXPECT_NE(r.out.find("de-skew: on (per-point time from the VLP-16's packets on /velodyne_packets)"), std::string::npos)
      << r.out;
}

TEST(Vlp16Bags, OtherDriversLayoutsDeskewFromTheirOwnTimeFieldsAndNoTimeIsSaidOnce) {
  const std::string bag = simulated() + "/data/dataset.bag";
  const auto velodyne = localizeJson(bag);
  for (const auto& [mode, field] : {std::pair<std::string, std::string>{"ouster", "t"}, {"hesai", "timestamp"}}) {
    SCOPED_TRACE(mode);
    const auto j = localizeJson(rewritten(mode));
    EXPECT_EQ(j["converged"], velodyne["converged"]);
    EXPECT_NEAR(j["position_error_m"].get<double>(), velodyne["position_error_m"].get<double>(), 1e-3);
    const auto r = runBimloc("localize '" + rewritten(mode) + "' --plan '" + kPlan + "'");
    EXPECT_NE(r.out.find("de-skew: on (per-point time from the field '" + field + "')"), std::string::npos) << r.out;
  }
  const auto r = runBimloc("localize '" + rewritten("notime") + "' --plan '" + kPlan + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const std::string note = "de-skew: off (the clouds on /velodyne_points have no per-point time field";
  const auto first = r.out.find(note);
  EXPECT_NE(first, std::string::npos) << r.out;
  EXPECT_EQ(r.out.find(note, first + 1), std::string::npos) << "said more than once:\n" << r.out;
  // Without de-skew, as the Velodyne layout with --no-deskew.
  EXPECT_NEAR(localizeJson(rewritten("notime"))["position_error_m"].get<double>(),
              localizeJson(bag, "--no-deskew")["position_error_m"].get<double>(), 1e-3);
}

TEST(Vlp16Bags, APacketsTopicInAnMcapBagLocalizesAsInTheRos1Bag) {
  // velodyne_msgs/msg/VelodyneScan in CDR, with its ros2msg schema: the same packets, the same run.
  const std::string mcap = test::simulatedCorridor("vlp16-mcap", "--packets --format mcap") + "/data/rosbag2";
  const auto ros2 = localizeJson(mcap, "--cloud-topic /velodyne_packets");
  const auto ros1 = localizeJson(simulated() + "/data/dataset.bag", "--cloud-topic /velodyne_packets");
  EXPECT_EQ(ros2["converged"], true);
  EXPECT_EQ(ros2["converged"], ros1["converged"]);
  EXPECT_NEAR(ros2["position_error_m"].get<double>(), ros1["position_error_m"].get<double>(), 1e-6);
}
