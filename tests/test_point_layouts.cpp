// Every common lidar driver's point layout (issue 29, part 4): the per-point time and ring
// fields as Velodyne, Ouster, Hesai, Livox, RoboSense and nebula write them, each cloud built
// byte by byte here from a turning, moving sensor, decoded by name and de-skewed; the truth is
// the analytic motion.
#include "sim/dataset/cloud_fields.hpp"
#include "sim/dataset/deskew.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>

using namespace bimloc;

namespace {

// sensor_msgs/PointField datatypes.
enum : std::uint8_t { INT8 = 1, UINT8, INT16, UINT16, INT32, UINT32, FLOAT32, FLOAT64 };

constexpr double kHeaderStamp = 1700000123.25;  // seconds since the epoch, as a real recording
constexpr double kYawRate = 1.5, kSpeed = 0.8;  // rad/s about z, m/s along x: a turning, walking base

// odom <- base at t: the analytic motion (the lidar is the base: mount identity).
Eigen::Isometry3d motion(double t) {
  const double dt = t - kHeaderStamp;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(kYawRate * dt, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(kSpeed * dt, 0, 0);
  return T;
}

struct Field {
  std::string name;
  std::uint32_t offset;
  std::uint8_t datatype;
};

struct Layout {
  std::string driver;
  std::vector<Field> fields;
  std::uint32_t point_step;
  // Writes the point's time (seconds after the header stamp) as the driver does; empty: none.
  std::function<void(std::uint8_t*, double)> write_time;
  std::string time_field;
  bool has_ring = true;
};

template <class T>
void put(std::uint8_t* p, T v) {
  std::memcpy(p, &v, sizeof v);
}

std::vector<Layout> layouts() {
  return {
      {"Velodyne (velodyne_pointcloud)",
       {{"x", 0, FLOAT32}, {"y", 4, FLOAT32}, {"z", 8, FLOAT32}, {"intensity", 12, FLOAT32}, {"ring", 16, UINT16}, {"time", 18, FLOAT32}},
       22, [](std::uint8_t* p, double t) { put(p + 18, float(t)); }, "time"},
      {"Ouster (ouster-ros)",
       {{"x", 0, FLOAT32}, {"y", 4, FLOAT32}, {"z", 8, FLOAT32}, {"intensity", 16, FLOAT32}, {"t", 20, UINT32},
        {"reflectivity", 24, UINT16}, {"ring", 26, UINT8}, {"ambient", 28, UINT16}, {"range", 32, UINT32}},
       48, [](std::uint8_t* p, double t) { put(p + 20, std::uint32_t(std::llround(t * 1e9))); }, "t"},
      {"Hesai (HesaiLidar_ROS_2.0)",
       {{"x", 0, FLOAT32}, {"y", 4, FLOAT32}, {"z", 8, FLOAT32}, {"intensity", 16, FLOAT32}, {"timestamp", 24, FLOAT64}, {"ring", 32, UINT16}},
       48, [](std::uint8_t* p, double t) { put(p + 24, kHeaderStamp + t); }, "timestamp"},
      {"Livox (livox_ros_driver2, timestamp)",
       {{"x", 0, FLOAT32}, {"y", 4, FLOAT32}, {"z", 8, FLOAT32}, {"intensity", 12, FLOAT32}, {"tag", 16, UINT8}, {"line", 17, UINT8},
        {"timestamp", 18, FLOAT64}},
       26, [](std::uint8_t* p, double t) { put(p + 18, std::round((kHeaderStamp + t) * 1e9)); }, "timestamp", false},
      {"Livox (offset_time)",
       {{"x", 0, FLOAT32}, {"y", 4, FLOAT32}, {"z", 8, FLOAT32}, {"intensity", 12, FLOAT32}, {"offset_time", 16, UINT32}, {"line", 20, UINT8}},
       21, [](std::uint8_t* p, double t) { put(p + 16, std::uint32_t(std::llround(t * 1e9))); }, "offset_time", false},
      {"RoboSense (rslidar_sdk)",
       {{"x", 0, FLOAT32}, {"y", 4, FLOAT32}, {"z", 8, FLOAT32}, {"intensity", 16, FLOAT32}, {"ring", 20, UINT16}, {"timestamp", 24, FLOAT64}},
       32, [](std::uint8_t* p, double t) { put(p + 24, kHeaderStamp + t); }, "timestamp"},
      {"tier4/nebula",
       {{"x", 0, FLOAT32}, {"y", 4, FLOAT32}, {"z", 8, FLOAT32}, {"intensity", 12, UINT8}, {"return_type", 13, UINT8},
        {"channel", 14, UINT16}, {"azimuth", 16, FLOAT32}, {"elevation", 20, FLOAT32}, {"distance", 24, FLOAT32}, {"time_stamp", 28, UINT32}},
       32, [](std::uint8_t* p, double t) { put(p + 28, std::uint32_t(std::llround(t * 1e9))); }, "time_stamp"},
      {"no time (a converter's x y z intensity)",
       {{"x", 0, FLOAT32}, {"y", 4, FLOAT32}, {"z", 8, FLOAT32}, {"intensity", 12, FLOAT32}}, 16, nullptr, "", false},
  };
}

// World points on the walls of a 12 x 8 m room around the start; the turn sweeps them in 0.1 s.
struct Sample {
  Eigen::Vector3d world;
  double t;  // after the header stamp
  std::uint16_t ring;
};

std::vector<Sample> samples() {
  std::vector<Sample> out;
  for (int i = 0; i < 1000; ++i) {
    const double t = 1e-4 * i, yaw = 2 * M_PI * i / 1000.0;
    const Eigen::Vector3d dir(std::cos(yaw), std::sin(yaw), 0.05 * ((i % 16) - 8));
    const double range = std::min(6.0 / std::max(1e-9, std::abs(dir.x())), 4.0 / std::max(1e-9, std::abs(dir.y())));
    out.push_back({range * dir, t, static_cast<std::uint16_t>(i % 16)});
  }
  return out;
}

}  // namespace

TEST(PointLayouts, EachDriversTimeAndRingFieldsDeskewToTheAnalyticTurn) {
  std::vector<sim::StampedPose> odometry;
  for (int i = -10; i <= 30; ++i) odometry.push_back({kHeaderStamp + 0.01 * i, motion(kHeaderStamp + 0.01 * i)});
  const auto truth = samples();
  const double reference = kHeaderStamp + 0.05;  // the turn's middle
  for (const Layout& l : layouts()) {
    sim::CloudLayout layout;
    for (const Field& f : l.fields) layout.fields.push_back({f.name, f.offset, f.datatype, 1});
    layout.width = static_cast<std::uint32_t>(truth.size()), layout.height = 1, layout.point_step = l.point_step;
    layout.row_step = l.point_step * layout.width;
    std::vector<std::uint8_t> data(layout.row_step);
    for (std::size_t i = 0; i < truth.size(); ++i) {
      std::uint8_t* p = data.data() + i * l.point_step;
      // Measured in the sensor frame of its own instant.
      const Eigen::Vector3f local = (motion(kHeaderStamp + truth[i].t).inverse() * truth[i].world).cast<float>();
      put(p + 0, local.x()), put(p + 4, local.y()), put(p + 8, local.z());
      for (const Field& f : l.fields) {
        if (f.name == "ring" && f.datatype == UINT16) put(p + f.offset, truth[i].ring);
        if (f.name == "ring" && f.datatype == UINT8) put(p + f.offset, std::uint8_t(truth[i].ring));
        if (f.name == "channel") put(p + f.offset, truth[i].ring);
      }
      if (l.write_time) l.write_time(p, truth[i].t);
    }
    SCOPED_TRACE(l.driver);
    sim::CloudPoints points = sim::decodeCloud(layout, data.data(), data.size(), l.driver);
    ASSERT_EQ(points.xyz.size(), truth.size());
    EXPECT_EQ(points.time_field, l.time_field);
    EXPECT_EQ(sim::cloudTimeField(layout), l.time_field);
    if (l.has_ring) {
      ASSERT_EQ(points.ring.size(), truth.size());
      for (std::size_t i = 0; i < truth.size(); ++i) ASSERT_EQ(points.ring[i], truth[i].ring) << i;
    } else {
      EXPECT_TRUE(points.ring.empty());
    }
    if (!l.write_time) {  // no time: nothing to de-skew with, and the decoder says so by an empty list
      EXPECT_TRUE(points.time_s.empty());
      continue;
    }
    ASSERT_EQ(points.time_s.size(), truth.size());
    EXPECT_EQ(points.time_absolute, l.time_field == "timestamp");
    sim::makeTimesRelative(points, kHeaderStamp);
    EXPECT_EQ(points.time_absolute, l.time_field == "timestamp");
    for (std::size_t i = 0; i < truth.size(); ++i) ASSERT_NEAR(points.time_s[i], truth[i].t, 1e-6) << i;
    // Before: bent by the motion (tens of centimetres); after: the turn seen from the middle.
    double before = 0, after = 0;
    std::vector<Eigen::Vector3f> xyz = points.xyz;
    sim::deskew(xyz, points.time_s, kHeaderStamp, reference, odometry, Eigen::Isometry3d::Identity());
    for (std::size_t i = 0; i < truth.size(); ++i) {
      const Eigen::Vector3d expected = motion(reference).inverse() * truth[i].world;
      before = std::max(before, (points.xyz[i].cast<double>() - expected).norm());
      after = std::max(after, (xyz[i].cast<double>() - expected).norm());
    }
    EXPECT_GT(before, 0.2);
    EXPECT_LT(after, 1e-4);
  }
}

TEST(PointLayouts, ARingOfUnknownDatatypeIsIgnoredAndTheOrderOfTimeFieldsIsFixed) {
  // A cloud with both `time` and `timestamp` (a converter that kept both): `time` wins, as
  // kCloudTimeFields lists them; a ring of an unknown datatype is no ring, not a refusal.
  sim::CloudLayout layout;
  layout.fields = {{"x", 0, FLOAT32, 1}, {"y", 4, FLOAT32, 1}, {"z", 8, FLOAT32, 1}, {"timestamp", 12, FLOAT64, 1},
                   {"time", 20, FLOAT32, 1}, {"ring", 24, 0, 1}};
  layout.width = 1, layout.height = 1, layout.point_step = 26, layout.row_step = 26;
  std::vector<std::uint8_t> data(26);
  put(data.data() + 12, kHeaderStamp + 0.5);
  put(data.data() + 20, 0.025f);
  const auto p = sim::decodeCloud(layout, data.data(), data.size(), "test");
  EXPECT_EQ(p.time_field, "time");
  ASSERT_EQ(p.time_s.size(), 1u);
  EXPECT_NEAR(p.time_s[0], 0.025, 1e-8);
  EXPECT_FALSE(p.time_absolute);
  EXPECT_TRUE(p.ring.empty());
}
