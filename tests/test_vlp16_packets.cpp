// The VLP-16's own packets (issue 29, part 3). The truths: the manual's tables and formulas
// worked by hand on hand-made packets, the bench's own sensor model (its turns written as
// packets and decoded back: a round trip), and python's struct and Debian's tcpdump reading
// the pcap we write. The real driver's decoding of real packets is in test_vlp16_nebula.cpp.
#include "sim_fixtures.hpp"
#include "bag_fixtures.hpp"
#include "test_support.hpp"

#include "sim/dataset/pcap_writer.hpp"
#include "sim/lidar/vlp16.hpp"
#include "sim/dataset/velodyne_scan_points.hpp"
#include "sim/lidar/vlp16_packet.hpp"
#include "sim/lidar/vlp16_packet_encoder.hpp"
#include "sim/lidar/vlp16_turns.hpp"
#include "sim/world/world.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

using namespace bimloc;

namespace {

using Packet = std::array<std::uint8_t, sim::kVlp16PacketBytes>;

void put16(Packet& p, std::size_t at, std::uint16_t v) { p[at] = v & 0xFF, p[at + 1] = v >> 8; }

// A packet with the given block azimuths (0.01 deg), no returns, mode and product set.
Packet emptyPacket(const std::array<std::uint16_t, 12>& azimuth, std::uint8_t mode) {
  Packet p{};
  for (int b = 0; b < 12; ++b) {
    p[b * 100] = 0xFF, p[b * 100 + 1] = 0xEE;
    put16(p, b * 100 + 2, azimuth[b]);
  }
  p[1204] = mode, p[1205] = 0x22;
  return p;
}

void setReturn(Packet& p, int block, int firing, int laser, std::uint16_t units, std::uint8_t reflectivity) {
  const std::size_t at = block * 100 + 4 + 3 * (16 * firing + laser);
  put16(p, at, units);
  p[at + 2] = reflectivity;
}

std::vector<sim::Vlp16Point> decode(const Packet& p, double stamp_s, const sim::Vlp16DecodeOptions& o = {}) {
  std::vector<sim::Vlp16Point> out;
  sim::decodeVlp16Packet(p.data(), p.size(), stamp_s, o, out, "test packet");
  return out;
}

}  // namespace

TEST(Vlp16Packets, FiringTimesFollowTheManualsTimingTable) {
  // Single return: block b holds sequences 2b and 2b+1; 2.304 us per laser, 55.296 us per sequence.
  EXPECT_DOUBLE_EQ(sim::vlp16FiringOffsetS(0, 0, 0, false), 0.0);
  EXPECT_NEAR(sim::vlp16FiringOffsetS(0, 0, 15, false), 34.560e-6, 1e-12);
  EXPECT_NEAR(sim::vlp16FiringOffsetS(0, 1, 0, false), 55.296e-6, 1e-12);
  EXPECT_NEAR(sim::vlp16FiringOffsetS(11, 1, 15, false), 1306.368e-6, 1e-12);  // the manual's last entry
  // Dual return: the two blocks of a pair report the same firings.
  EXPECT_DOUBLE_EQ(sim::vlp16FiringOffsetS(1, 0, 0, true), 0.0);
  EXPECT_NEAR(sim::vlp16FiringOffsetS(11, 1, 15, true), 642.816e-6, 1e-12);
  // 24 sequences a packet: about 754 packets a second in single return, as the manual says.
  EXPECT_NEAR(1.0 / (24 * 55.296e-6), 754.0, 0.5);
}

TEST(Vlp16Packets, AHandMadePacketDecodesAsTheManualSays) {
  std::array<std::uint16_t, 12> az{};
  for (int b = 0; b < 12; ++b) az[b] = static_cast<std::uint16_t>(10000 + 40 * b);
  Packet p = emptyPacket(az, 0x37);
  setReturn(p, 2, 1, 3, 5000, 77);    // laser 3 (+3 deg), the block's second sequence, 10 m
  setReturn(p, 11, 1, 0, 1000, 12);   // the last block: its gap is the previous one's
  setReturn(p, 0, 0, 5, 150, 9);      // 0.3 m: below the 0.4 m minimum
  const auto points = decode(p, 100.0);
  ASSERT_EQ(points.size(), 2u);
  const auto& a = points[0];
  // Azimuth: the block's, plus the gap to the next block times the firing's share of the block.
  const double az_a = (10080 + 40 * (55.296 + 3 * 2.304) / 110.592) / 100.0;
  EXPECT_NEAR(a.azimuth_deg, az_a, 1e-4);
  EXPECT_EQ(a.elevation_deg, 3.0f);
  EXPECT_EQ(a.laser, 3);
  EXPECT_EQ(a.ring, 9);
  EXPECT_EQ(a.intensity, 77);
  EXPECT_EQ(a.kind, sim::Vlp16Return::kStrongest);
  EXPECT_NEAR(a.distance_m, 10.0, 1e-6);
  const double el = 3.0 * M_PI / 180, t = az_a * M_PI / 180;
  EXPECT_NEAR(a.x, 10 * std::cos(el) * std::cos(t), 1e-5);
  EXPECT_NEAR(a.y, -10 * std::cos(el) * std::sin(t), 1e-5);  // clockwise azimuth: 90 deg is -y
  EXPECT_NEAR(a.z, 10 * std::sin(el) - 0.0022, 1e-5);        // laser 3 sits 2.2 mm below the centre
  EXPECT_NEAR(a.time_s, 100.0 + (5 * 55.296 + 3 * 2.304) * 1e-6, 1e-9);
  EXPECT_NEAR(points[1].azimuth_deg, (10440 + 40 * 0.5) / 100.0, 1e-4);
  // The drivers' stock calibration: no vertical offsets.
  sim::Vlp16DecodeOptions flat;
  flat.vertical_offsets = false;
  EXPECT_NEAR(decode(p, 100.0, flat)[0].z, 10 * std::sin(el), 1e-5);
  // Through north: a gap across 0 deg is counted forward.
  for (int b = 0; b < 12; ++b) az[b] = static_cast<std::uint16_t>((35900 + 40 * b) % 36000);
  Packet q = emptyPacket(az, 0x38);
  setReturn(q, 2, 1, 15, 1000, 1);
  const auto wrapped = decode(q, 0.0);
  ASSERT_EQ(wrapped.size(), 1u);
  EXPECT_NEAR(wrapped[0].azimuth_deg, (35980 + 40 * (55.296 + 15 * 2.304) / 110.592) / 100.0 - 360.0, 1e-4);
  EXPECT_EQ(wrapped[0].kind, sim::Vlp16Return::kLast);
}

TEST(Vlp16Packets, DualReturnPairsShareTheirFiringsAndDropARepeatedEcho) {
  std::array<std::uint16_t, 12> az{};
  for (int b = 0; b < 12; ++b) az[b] = static_cast<std::uint16_t>(2000 + 40 * (b / 2));  // pairs share one azimuth
  Packet p = emptyPacket(az, 0x39);
  setReturn(p, 4, 0, 0, 1000, 50), setReturn(p, 5, 0, 0, 1000, 50);  // one echo, reported twice
  setReturn(p, 4, 1, 1, 2000, 10), setReturn(p, 5, 1, 1, 1500, 90);  // last at 4 m, strongest at 3 m
  const auto points = decode(p, 0.0);
  ASSERT_EQ(points.size(), 3u);
  EXPECT_EQ(points[0].kind, sim::Vlp16Return::kDualLast);
  EXPECT_EQ(points[1].kind, sim::Vlp16Return::kDualLast);
  EXPECT_EQ(points[2].kind, sim::Vlp16Return::kDualStrongest);
  EXPECT_NEAR(points[1].distance_m, 4.0, 1e-6);
  EXPECT_NEAR(points[2].distance_m, 3.0, 1e-6);
  // The two returns of one firing: one instant, one direction.
  EXPECT_EQ(points[1].time_s, points[2].time_s);
  EXPECT_EQ(points[1].azimuth_deg, points[2].azimuth_deg);
  EXPECT_NEAR(points[1].time_s, (5 * 55.296 + 2.304) * 1e-6, 1e-12);  // pair 2 = sequences 4 and 5; firing 1
  EXPECT_NEAR(points[1].azimuth_deg, (2080 + 40 * (55.296 + 2.304) / 110.592) / 100.0, 1e-4);
  // Only the strongest returns: the repeated echo comes back from the second block.
  sim::Vlp16DecodeOptions strongest;
  strongest.keep_last = false;
  const auto s = decode(p, 0.0, strongest);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].kind, sim::Vlp16Return::kDualStrongest);
  EXPECT_NEAR(s[0].distance_m, 2.0, 1e-6);
  EXPECT_NEAR(s[1].distance_m, 3.0, 1e-6);
}

TEST(Vlp16Packets, ABrokenPacketIsRefusedNamingWhatIsWrong) {
  std::array<std::uint16_t, 12> az{};
  const Packet good = emptyPacket(az, 0x37);
  auto refused = [](const Packet& p, std::size_t size, const std::string& expected) {
    std::vector<sim::Vlp16Point> out;
    try {
      sim::decodeVlp16Packet(p.data(), size, 0.0, {}, out, "bag.db3: /velodyne_packets message 3 packet 7");
      ADD_FAILURE() << "accepted: " << expected;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("bag.db3: /velodyne_packets message 3 packet 7: " + expected), std::string::npos)
          << e.what();
    }
  };
  refused(good, 1205, "a VLP-16 data packet has 1206 bytes, this one 1205");
  Packet p = good;
  p[501] = 0xDD;  // block 5's flag: an HDL-64's lower block
  refused(p, p.size(), "block 5 does not start with the flag 0xFFEE");
  p = good;
  put16(p, 302, 36000);
  refused(p, p.size(), "block 3 has azimuth 36000 (0.01 deg), 360 deg or more");
  p = good;
  p[1205] = 0x28;  // a VLP-32C
  refused(p, p.size(), "product id 0x28 is not a VLP-16 (0x22)");
  p = good;
  p[1204] = 0x3B;
  refused(p, p.size(), "return mode 0x3B is none of the manual's");
}

// Every return dropped is counted (found by damaging packets: 0xFFFF distances, 131 m, vanished
// without a word), and a timestamp no VLP-16 writes is said.
TEST(Vlp16Packets, ReturnsOutOfRangeAreCountedAndAStampPastTheHourIsSaid) {
  std::array<std::uint16_t, 12> az{};
  Packet p = emptyPacket(az, 0x37);
  setReturn(p, 0, 0, 0, 0xFFFF, 10);  // 131.07 m: beyond the 130 m the decoder keeps
  setReturn(p, 0, 0, 1, 0xFFFF, 10);
  setReturn(p, 1, 1, 2, 100, 10);     // 0.2 m: at or below the driver's 0.4 m
  setReturn(p, 2, 0, 3, 2500, 10);    // 5 m: kept
  setReturn(p, 3, 0, 4, 0, 0);        // no return: not a point at all
  std::vector<sim::Vlp16Point> out;
  const auto header = sim::decodeVlp16Packet(p.data(), p.size(), 0.0, {}, out, "test packet");
  EXPECT_EQ(out.size(), 1u);
  EXPECT_EQ(header.beyond_max_range, 2u);
  EXPECT_EQ(header.below_min_range, 1u);
  const auto cloud = sim::decodeVelodyneScan({{0.0, p.data(), p.size()}}, 0.0, {}, "bag: /velodyne_packets message 0");
  EXPECT_EQ(cloud.beyond_max_range, 2u);
  EXPECT_EQ(cloud.below_min_range, 1u);
  EXPECT_TRUE(cloud.warnings.empty());
  // 0xFFFFFFFF microseconds past the hour: no hour is that long.
  p[1200] = p[1201] = p[1202] = p[1203] = 0xFF;
  const auto stamped = sim::decodeVelodyneScan({{0.0, p.data(), p.size()}}, 0.0, {}, "bag: /velodyne_packets message 0");
  ASSERT_EQ(stamped.warnings.size(), 1u);
  EXPECT_NE(stamped.warnings[0].find("timestamp past the hour"), std::string::npos) << stamped.warnings[0];
  put16(p, 1200, 0x0000), put16(p, 1202, 0xD693);  // 3 599 958 016 us: within the hour
  EXPECT_TRUE(sim::decodeVelodyneScan({{0.0, p.data(), p.size()}}, 0.0, {}, "m").warnings.empty());
}

TEST(Vlp16Packets, TheBenchsTurnsComeBackFromTheirPacketsWithinTheQuantization) {
  const sim::World world = sim::World::fromMesh(test::boxRoomFile(Eigen::Vector3f(10, 8, 3)));
  sim::Vlp16Config config;
  config.T_base_lidar = Eigen::Isometry3d::Identity();
  config.dropout_probability = 0.05;  // some firings without a return
  const double yaw_rate = 0.8;        // turning: the points carry the skew, which the packets keep
  auto base = [yaw_rate](double t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(4, 3, 1.2);
    T.linear() = Eigen::AngleAxisd(yaw_rate * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return T;
  };
  const sim::LidarScan scan = sim::Vlp16(config).scan(world, 0, base, 0.0, 5, 2);
  const double stamp = 1000.25;
  const auto packets = sim::encodeVlp16Turn(scan, config.rpm, stamp);
  ASSERT_EQ(packets.size(), 76u);  // 1808 sequences, 24 a packet, the last one a third full
  std::vector<sim::Vlp16Point> decoded;
  for (std::size_t i = 0; i < packets.size(); ++i) {
    EXPECT_NEAR(packets[i].stamp_s, stamp + i * 24 * 55.296e-6, 1e-9);
    sim::decodeVlp16Packet(packets[i].data.data(), packets[i].data.size(), packets[i].stamp_s, {}, decoded, "turn");
  }
  // One turn, the simulator's points in its order.
  ASSERT_EQ(sim::splitVlp16Turns(decoded).size(), 1u);
  ASSERT_EQ(decoded.size(), scan.points.size());
  double worst_range = 0, worst_xyz = 0, worst_az = 0;
  for (std::size_t i = 0; i < decoded.size(); ++i) {
    const auto& d = decoded[i];
    const auto& s = scan.points[i];
    ASSERT_EQ(d.ring, s.ring) << i;
    ASSERT_NEAR(d.time_s - stamp, s.time, 1e-7) << i;
    EXPECT_EQ(d.intensity, static_cast<int>(std::lround(s.intensity))) << i;
    const double offset = sim::vlp16VerticalOffsetM(d.laser);
    const Eigen::Vector3d sp(s.x, s.y, s.z - offset);
    const double az = std::fmod(std::atan2(-sp.y(), sp.x()) * 180 / M_PI + 360.0, 360.0);
    double daz = std::abs(az - d.azimuth_deg);
    daz = std::min(daz, 360 - daz);
    worst_az = std::max(worst_az, daz);
    worst_range = std::max(worst_range, std::abs(sp.norm() - d.distance_m));
    const double err = (Eigen::Vector3d(d.x, d.y, d.z) - Eigen::Vector3d(s.x, s.y, s.z)).norm();
    // Range to the 2 mm unit (half of it); azimuth to the 0.01 deg unit of the block azimuths:
    // the block's rounding (0.005 deg) plus its gap's (0.01 deg) times the firing's share of the
    // block (at most 89.856 / 110.592), 0.0131 deg; plus float rounding.
    ASSERT_LE(err, 0.001 + sp.norm() * 0.0132 * M_PI / 180 + 2e-6) << i;
    worst_xyz = std::max(worst_xyz, err);
  }
  EXPECT_LE(worst_range, 0.001 + 1e-6);
  EXPECT_LE(worst_az, 0.0132);
  std::printf("round trip of %zu points: range within %.4f mm, azimuth within %.4f deg, xyz within %.3f mm\n",
              decoded.size(), 1e3 * worst_range, worst_az, 1e3 * worst_xyz);
}

TEST(Vlp16Packets, ThePcapHoldsTheUdpStreamAsIndependentReadersSeeIt) {
  const std::string dir = test::tempDir("pcap");
  sim::LidarScan scan;
  scan.points.push_back({1.0f, 0.0f, 0.0112f - 0.2679f, 50.0f, 0, 0.0f});  // laser 0 (-15 deg), 1.035 m ahead
  const auto packets = sim::encodeVlp16Turn(scan, 600.0, 1700000000.5);
  {
    sim::PcapWriter pcap(dir + "/v.pcap");
    for (const auto& p : packets) pcap.writeUdp(p.stamp_s, p.data.data(), p.data.size(), sim::kVlp16DataPort);
    pcap.close();
  }
  // python's struct: the global header, the frames' headers, both checksums, the payloads.
  const std::string json = test::runPython("read_pcap.py", "'" + dir + "/v.pcap' '" + dir + "/payloads.bin'");
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(json)) << json;
  EXPECT_EQ(j["magic"], "a1b2c3d4");
  EXPECT_EQ(j["linktype"], 1);
  EXPECT_EQ(j["packets"], packets.size());
  EXPECT_EQ(j["bad_ip_checksums"], 0);
  EXPECT_EQ(j["bad_udp_checksums"], 0);
  EXPECT_EQ(j["ports"], nlohmann::json::array({nlohmann::json::array({2368, 2368})}));
  EXPECT_EQ(j["source"], "192.168.1.201");
  EXPECT_NEAR(j["first_stamp"].get<double>(), 1700000000.5, 1e-6);
  std::ifstream in(dir + "/payloads.bin", std::ios::binary);
  std::string payloads((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(payloads.size(), packets.size() * 1206);
  for (std::size_t i = 0; i < packets.size(); ++i)
    ASSERT_EQ(0, std::memcmp(payloads.data() + i * 1206, packets[i].data.data(), 1206)) << i;
  // Debian's tcpdump, when installed (Makefile's DEB_PACKAGES): every datagram, checksums verified.
  if (std::system("command -v tcpdump > /dev/null 2>&1") != 0) GTEST_SKIP() << "tcpdump not installed: python's check only";
  const std::string dump = test::commandOutput("tcpdump -nn -vv -r '" + dir + "/v.pcap' 2>/dev/null");
  std::size_t lines = 0, ok = 0;
  for (std::size_t at = 0; (at = dump.find("192.168.1.201.2368 > 255.255.255.255.2368", at)) != std::string::npos; ++at) ++lines;
  for (std::size_t at = 0; (at = dump.find("udp sum ok", at)) != std::string::npos; ++at) ++ok;
  EXPECT_EQ(lines, packets.size()) << dump.substr(0, 2000);
  EXPECT_EQ(ok, packets.size()) << dump.substr(0, 2000);
  EXPECT_EQ(dump.find("bad cksum"), std::string::npos);
}
