// ROS 2 bags in (issue 29 §1): the CDR decoding and the rosbag2 reader. The truths: the real
// nebula bags, written by a real rosbag2 recorder, with their counts and timestamps as
// python3's own sqlite3 module reads them; CDR bytes laid out by hand from the XCDR1 rules.
#include "sim/ros2/cdr.hpp"
#include "sim/ros2/messages.hpp"
#include "sim/ros2/rosbag2_reader.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

namespace fs = std::filesystem;
using namespace bimloc::sim::ros2;

namespace {

std::string nebulaBag(const std::string& sensor) {
  const fs::path dir = fs::path(BIMLOC_SHARED_REALDATA_DIR) / "nebula" / sensor;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return "";
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_directory()) return e.path().string();
  return "";
}

// python3's sqlite3 module, an independent reader of the same file: "count min max" of a topic.
std::string pythonSqlite(const std::string& db3) {
  const std::string cmd = "/usr/bin/python3 -c \"import sqlite3,sys; c=sqlite3.connect('file:'+sys.argv[1]+'?immutable=1',uri=True); "
                          "print(*c.execute('select count(*),min(timestamp),max(timestamp) from messages').fetchone())\" '" + db3 + "'";
  std::unique_ptr<FILE, decltype(&pclose)> p(popen(cmd.c_str(), "r"), pclose);
  std::string out;
  char buf[256];
  while (p && fgets(buf, sizeof buf, p.get())) out += buf;
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

}  // namespace

TEST(Ros2Cdr, AlignsFromThePayloadStartAndReadsBothEndians) {
  // uint8 1, then uint32 0x01020304 at payload offset 4 (3 bytes of padding), then a string.
  const std::vector<std::uint8_t> le = {0x00, 0x01, 0x00, 0x00, 0x01, 0, 0, 0, 0x04, 0x03, 0x02, 0x01, 3, 0, 0, 0, 'h', 'i', 0};
  CdrReader r(le.data(), le.size(), "le");
  EXPECT_FALSE(r.bigEndian());
  EXPECT_EQ(r.u8(), 1);
  EXPECT_EQ(r.u32(), 0x01020304u);
  EXPECT_EQ(r.string(), "hi");
  EXPECT_EQ(r.remaining(), 0u);
  const std::vector<std::uint8_t> be = {0x00, 0x00, 0x00, 0x00, 0x01, 0, 0, 0, 0, 0, 0, 0, 0x40, 0x09, 0x21, 0xFB, 0x54, 0x44, 0x2D, 0x18};
  CdrReader b(be.data(), be.size(), "be");
  EXPECT_TRUE(b.bigEndian());
  EXPECT_EQ(b.u8(), 1);
  EXPECT_DOUBLE_EQ(b.f64(), 3.141592653589793);  // aligned to 8 from the payload start
}

TEST(Ros2Cdr, RefusesBrokenBytesByName) {
  const std::vector<std::uint8_t> xcdr2 = {0x00, 0x07, 0, 0, 1, 2, 3, 4};
  EXPECT_THROW(CdrReader(xcdr2.data(), xcdr2.size(), "x"), std::runtime_error);
  const std::vector<std::uint8_t> huge_string = {0x00, 0x01, 0, 0, 0xFF, 0xFF, 0xFF, 0x7F, 'a'};
  CdrReader r(huge_string.data(), huge_string.size(), "FILE: /t message 0");
  try {
    r.string();
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("FILE: /t message 0: broken CDR at byte"), std::string::npos) << e.what();
  }
  const std::vector<std::uint8_t> no_nul = {0x00, 0x01, 0, 0, 2, 0, 0, 0, 'a', 'b'};
  CdrReader n(no_nul.data(), no_nul.size(), "n");
  EXPECT_THROW(n.string(), std::runtime_error);
}

TEST(Ros2Cdr, MessagesRoundTrip) {
  PointCloud2 c;
  c.header.stamp = {12, 345};
  c.header.frame_id = "velodyne";
  c.height = 1, c.width = 2, c.point_step = 13, c.row_step = 26;
  c.fields = {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"ring", 12, 2, 1}};
  c.data.assign(26, 0x5A);
  c.is_dense = true;
  const auto bytes = serialize(c);
  CdrReader in(bytes.data(), bytes.size(), "cloud");
  const PointCloud2 back = readPointCloud2(in);
  EXPECT_EQ(in.remaining(), 0u);
  EXPECT_EQ(back.header.frame_id, "velodyne");
  EXPECT_EQ(back.header.stamp.nanosec, 345u);
  ASSERT_EQ(back.fields.size(), 4u);
  EXPECT_EQ(back.fields[3].name, "ring");
  EXPECT_EQ(back.fields[3].datatype, 2);
  EXPECT_EQ(back.data, c.data);
  EXPECT_TRUE(back.is_dense);

  Odometry o;
  o.header.frame_id = "odom", o.child_frame_id = "base_link";
  o.pose.pose.position = {1, 2, 3};
  o.pose.pose.orientation = {0, 0, 0.6, 0.8};
  o.pose.covariance[35] = 0.25;
  const auto ob = serialize(o);
  CdrReader oi(ob.data(), ob.size(), "odom");
  const Odometry ob2 = readOdometry(oi);
  EXPECT_EQ(oi.remaining(), 0u);
  EXPECT_EQ(ob2.child_frame_id, "base_link");
  EXPECT_DOUBLE_EQ(ob2.pose.pose.orientation.z, 0.6);
  EXPECT_DOUBLE_EQ(ob2.pose.covariance[35], 0.25);
}

// The real VLP-16 bag: /velodyne_packets, velodyne_msgs/msg/VelodyneScan (Header, then
// VelodynePacket[] of {Time stamp; uint8[1206] data}); the padding after each packet's 1206
// bytes is what XCDR1 alignment from the payload start gives, so the message ends where the
// last packet does when the alignment is right (Fast-CDR then pads the message to 4 bytes).
TEST(Ros2Bag, ReadsTheRealNebulaSqliteBags) {
  if (nebulaBag("vlp16").empty()) GTEST_SKIP() << BIMLOC_SHARED_REALDATA_DIR << "/nebula not found: skipping the real rosbag2 bags";
  for (const std::string sensor : {"vlp16", "40p", "64", "xt32", "qt64"}) {
    const std::string bag = nebulaBag(sensor);
    ASSERT_FALSE(bag.empty()) << sensor;
    ASSERT_TRUE(isRosbag2(bag));
    Rosbag2Reader reader(bag);
    EXPECT_EQ(reader.storageIdentifier(), "sqlite3");
    ASSERT_EQ(reader.topics().size(), 1u);
    const BagTopic& t = reader.topics()[0];
    EXPECT_EQ(t.serialization_format, "cdr");
    EXPECT_EQ(t.name, sensor == "vlp16" ? "/velodyne_packets" : "/pandar_packets");
    EXPECT_EQ(t.type, sensor == "vlp16" ? "velodyne_msgs/msg/VelodyneScan" : "pandar_msgs/msg/PandarScan");
    std::uint64_t first = 0, last = 0, n = 0, previous = 0;
    std::size_t packets = 0;
    reader.forEachMessage({}, [&](const BagMessage& m) {
      if (n == 0) first = m.log_time_ns;
      EXPECT_GE(m.log_time_ns, previous);
      previous = last = m.log_time_ns;
      ++n;
      if (sensor != "vlp16") return;
      CdrReader in(m.data, m.size, m.where);
      const Header h = readHeader(in);
      EXPECT_EQ(h.frame_id, "velodyne");
      const std::uint32_t count = in.sequenceLength(8 + 1206, "packets");
      for (std::uint32_t i = 0; i < count; ++i) {
        readTime(in);
        const std::uint8_t* data = in.bytes(1206, "data");
        EXPECT_EQ(data[0], 0xFF);  // every VLP-16 data block starts with the flag 0xFFEE
        EXPECT_EQ(data[1], 0xEE);
      }
      EXPECT_LT(in.remaining(), 4u);
      packets += count;
    });
    const std::string db3 = (fs::path(bag) / (fs::path(bag).filename().string() + "_0.db3")).string();
    EXPECT_EQ(std::to_string(n) + " " + std::to_string(first) + " " + std::to_string(last), pythonSqlite(db3)) << sensor;
    EXPECT_EQ(n, t.messages);
    if (sensor == "vlp16") {
      EXPECT_GT(packets, 300u);  // 754 packets a second at 600 rpm: 0.3 s of them
    }
  }
}
