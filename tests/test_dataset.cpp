// The dataset of `bimloc simulate`, read back by independent readers: ROS's python rosbag
// for the bag (tests/read_bag.py under Debian's /usr/bin/python3), PCL for the PCD files,
// nlohmann for metadata.json and a plain split for the TUM and CSV files.
#include "test_support.hpp"

#include "sim/dataset/dataset_writer.hpp"

#include <gtest/gtest.h>
#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

namespace fs = std::filesystem;
using namespace bimloc;

namespace {

constexpr int kScans = 3;
constexpr int kPointsPerScan = 100;
constexpr int kPoses = 50;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

sim::LidarPoint expectedPoint(int scan, int k) {
  sim::LidarPoint p;
  p.x = static_cast<float>(scan) + 0.01f * static_cast<float>(k);
  p.y = -0.5f * static_cast<float>(k);
  p.z = 0.25f * static_cast<float>(k % 4) - 0.3f;
  p.intensity = static_cast<float>((k * 7) % 256);
  p.ring = static_cast<std::uint16_t>(k % 16);
  p.time = 1e-4f * static_cast<float>(k);
  return p;
}

Eigen::Isometry3d planarPose(double x, double y, double yaw_rad) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, y, 0.0);
  T.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return T;
}

Eigen::Isometry3d mount() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0.1, 0.0, 0.5);
  T.linear() = Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return T;
}

sim::DatasetInfo info() {
  sim::DatasetInfo i;
  i.metadata = {{"scenario", "unit"}, {"seed", 42}};
  i.T_base_lidar = mount();
  return i;
}

// Scans at 10 Hz, odometry and ground truth at 50 Hz, interleaved as a simulator would.
std::vector<std::string> writeDataset(const std::string& dir) {
  sim::DatasetWriter writer(dir, info());
  for (int i = 0; i < kPoses; ++i) {
    if (i % 5 == 0 && i / 5 < kScans) {
      sim::LidarScan scan;
      scan.stamp_s = 0.1 * (i / 5);
      for (int k = 0; k < kPointsPerScan; ++k) scan.points.push_back(expectedPoint(i / 5, k));
      writer.addScan(scan);
    }
    sim::OdometrySample odom;
    odom.stamp_s = 0.02 * i;
    odom.T_odom_base = planarPose(0.1 * i, 0.05 * i, 0.01 * i);
    odom.linear_velocity_base = Eigen::Vector3d(0.5, 0.0, 0.0);
    odom.angular_velocity_base = Eigen::Vector3d(0.0, 0.0, 0.1);
    writer.addOdometry(odom);
    writer.addGroundTruth({0.02 * i, planarPose(2.0 + 0.1 * i, 1.0, 0.3 + 0.01 * i)});
  }
  return writer.commit();
}

// Stdout must be the JSON alone: stderr goes to a file, shown only when the script fails.
nlohmann::json readBag(const std::string& bag) {
  const std::string err = test::tempDir("read-bag") + "/stderr.txt";
  const std::string cmd =
      "/usr/bin/python3 '" + std::string(BIMLOC_TESTS_DIR) + "/read_bag.py' '" + bag + "' 2>'" + err + "'";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) throw std::runtime_error("cannot run " + cmd);
  std::string out;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
  const int status = ::pclose(pipe);
  const std::string messages = slurp(err);
  fs::remove(err);
  if (status != 0) throw std::runtime_error(cmd + " failed:\n" + out + messages);
  return nlohmann::json::parse(out);
}

void expectPose(const nlohmann::json& xyz, const nlohmann::json& xyzw, const Eigen::Isometry3d& T) {
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(xyz[a].get<double>(), T.translation()[a], 1e-12);
  const Eigen::Quaterniond q(xyzw[3].get<double>(), xyzw[0].get<double>(), xyzw[1].get<double>(),
                             xyzw[2].get<double>());
  EXPECT_NEAR(q.angularDistance(Eigen::Quaterniond(T.linear())), 0.0, 1e-9);
}

sim::OdometrySample odometryAt(double stamp_s) {
  sim::OdometrySample odom;
  odom.stamp_s = stamp_s;
  return odom;
}

class Dataset : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::tempDir("dataset") + "/out";
    files_ = writeDataset(dir_);
  }
  std::string dir_;
  std::vector<std::string> files_;
};

}  // namespace

TEST_F(Dataset, BagReadsBackWithRosbag) {
  const nlohmann::json bag = readBag(dir_ + "/dataset.bag");
  const auto& topics = bag["topics"];
  ASSERT_EQ(topics.size(), 4u) << bag.dump(1);
  const std::map<std::string, std::pair<std::string, int>> expected{
      {"/velodyne_points", {"sensor_msgs/PointCloud2", kScans}},
      {"/odom", {"nav_msgs/Odometry", kPoses}},
      {"/tf", {"tf2_msgs/TFMessage", kPoses}},
      {"/ground_truth", {"nav_msgs/Odometry", kPoses}}};
  for (const auto& [topic, type_count] : expected) {
    SCOPED_TRACE(topic);
    ASSERT_TRUE(topics.contains(topic));
    EXPECT_EQ(topics[topic]["type"], type_count.first);
    EXPECT_EQ(topics[topic]["count"], type_count.second);
    EXPECT_TRUE(topics[topic]["in_order"].get<bool>());
    EXPECT_TRUE(topics[topic]["stamps_match"].get<bool>());  // header.stamp == bag time
    EXPECT_EQ(topics[topic]["first_stamp"], "1000.000000000");
  }
  EXPECT_EQ(topics["/velodyne_points"]["last_stamp"], "1000.200000000");
  EXPECT_EQ(topics["/odom"]["last_stamp"], "1000.980000000");
  EXPECT_EQ(topics["/velodyne_points"]["frame_ids"], nlohmann::json({"velodyne"}));
  EXPECT_EQ(topics["/odom"]["frame_ids"], nlohmann::json({"odom"}));
  EXPECT_EQ(topics["/odom"]["child_frame_ids"], nlohmann::json({"base_link"}));
  EXPECT_EQ(topics["/ground_truth"]["frame_ids"], nlohmann::json({"map"}));
  EXPECT_EQ(topics["/ground_truth"]["child_frame_ids"], nlohmann::json({"base_link"}));

  // The velodyne driver's PointcloudXYZIRT layout: packed, 22 bytes a point.
  const auto& cloud = bag["cloud"];
  const nlohmann::json fields = nlohmann::json::parse(R"([
    {"name": "x", "offset": 0, "datatype": 7, "count": 1},
    {"name": "y", "offset": 4, "datatype": 7, "count": 1},
    {"name": "z", "offset": 8, "datatype": 7, "count": 1},
    {"name": "intensity", "offset": 12, "datatype": 7, "count": 1},
    {"name": "ring", "offset": 16, "datatype": 4, "count": 1},
    {"name": "time", "offset": 18, "datatype": 7, "count": 1}])");
  EXPECT_EQ(cloud["fields"], fields);
  EXPECT_EQ(cloud["point_step"], 22);
  EXPECT_EQ(cloud["height"], 1);
  EXPECT_EQ(cloud["row_step"], 22 * kPointsPerScan);
  EXPECT_TRUE(cloud["is_dense"].get<bool>());
  EXPECT_FALSE(cloud["is_bigendian"].get<bool>());
  EXPECT_EQ(cloud["widths"], nlohmann::json({kPointsPerScan, kPointsPerScan, kPointsPerScan}));
  EXPECT_EQ(cloud["data_sizes"], nlohmann::json({22 * kPointsPerScan, 22 * kPointsPerScan, 22 * kPointsPerScan}));
  EXPECT_EQ(cloud["seqs"], nlohmann::json({0, 1, 2}));
  const sim::LidarPoint p = expectedPoint(0, 0);
  const auto& first = cloud["first_point"];
  EXPECT_EQ(first["x"].get<float>(), p.x);
  EXPECT_EQ(first["y"].get<float>(), p.y);
  EXPECT_EQ(first["z"].get<float>(), p.z);
  EXPECT_EQ(first["intensity"].get<float>(), p.intensity);
  EXPECT_EQ(first["ring"].get<int>(), p.ring);
  EXPECT_EQ(first["time"].get<float>(), p.time);

  // Odometry: pose, twist, covariance as configured.
  const auto& odom = bag["first_odom"];
  expectPose(odom["position"], odom["orientation"], planarPose(0, 0, 0));
  EXPECT_EQ(odom["linear"], nlohmann::json({0.5, 0.0, 0.0}));
  EXPECT_EQ(odom["angular"], nlohmann::json({0.0, 0.0, 0.1}));
  const sim::DatasetInfo defaults;
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(odom["pose_covariance_diagonal"][i].get<double>(), defaults.odometry_pose_variance[i]);
    EXPECT_EQ(odom["twist_covariance_diagonal"][i].get<double>(), defaults.odometry_twist_variance[i]);
  }
  const auto& truth = bag["first_ground_truth"];
  expectPose(truth["position"], truth["orientation"], planarPose(2.0, 1.0, 0.3));

  // tf: odom -> base_link and the mount, once per odometry sample each.
  const auto& tf = bag["tf"];
  ASSERT_EQ(tf.size(), 2u) << tf.dump();
  EXPECT_EQ(tf["odom -> base_link"]["count"], kPoses);
  EXPECT_EQ(tf["base_link -> velodyne"]["count"], kPoses);
  expectPose(tf["base_link -> velodyne"]["translation"], tf["base_link -> velodyne"]["rotation"], mount());
}

TEST_F(Dataset, PcdFilesReadBackWithPcl) {
  const auto index = lines(dir_ + "/clouds/index.csv");
  ASSERT_EQ(index.size(), 1u + kScans);
  EXPECT_EQ(index[0], "file,stamp_s,points");
  const char* stamps[kScans] = {"1000.000000000", "1000.100000000", "1000.200000000"};
  for (int s = 0; s < kScans; ++s) {
    char name[32];
    std::snprintf(name, sizeof name, "%06d.pcd", s);
    EXPECT_EQ(index[1 + s], std::string(name) + "," + stamps[s] + ",100");

    pcl::PCLPointCloud2 cloud;
    ASSERT_EQ(pcl::io::loadPCDFile(dir_ + "/clouds/" + name, cloud), 0) << name;
    EXPECT_EQ(cloud.width, static_cast<std::uint32_t>(kPointsPerScan));
    EXPECT_EQ(cloud.height, 1u);
    EXPECT_EQ(cloud.point_step, 22u);
    ASSERT_EQ(cloud.fields.size(), 6u);
    const char* names[] = {"x", "y", "z", "intensity", "ring", "time"};
    const std::uint32_t offsets[] = {0, 4, 8, 12, 16, 18};
    for (int f = 0; f < 6; ++f) {
      EXPECT_EQ(cloud.fields[f].name, names[f]);
      EXPECT_EQ(cloud.fields[f].offset, offsets[f]);
      EXPECT_EQ(cloud.fields[f].datatype, f == 4 ? pcl::PCLPointField::UINT16 : pcl::PCLPointField::FLOAT32);
      EXPECT_EQ(cloud.fields[f].count, 1u);
    }
    ASSERT_EQ(cloud.data.size(), 22u * kPointsPerScan);
    for (int k = 0; k < kPointsPerScan; ++k) {
      const std::uint8_t* raw = cloud.data.data() + 22 * k;
      sim::LidarPoint got;
      std::memcpy(&got.x, raw + 0, 4);
      std::memcpy(&got.y, raw + 4, 4);
      std::memcpy(&got.z, raw + 8, 4);
      std::memcpy(&got.intensity, raw + 12, 4);
      std::memcpy(&got.ring, raw + 16, 2);
      std::memcpy(&got.time, raw + 18, 4);
      const sim::LidarPoint want = expectedPoint(s, k);
      ASSERT_EQ(got.x, want.x);
      ASSERT_EQ(got.y, want.y);
      ASSERT_EQ(got.z, want.z);
      ASSERT_EQ(got.intensity, want.intensity);
      ASSERT_EQ(got.ring, want.ring);
      ASSERT_EQ(got.time, want.time);
    }
  }
}

TEST_F(Dataset, TumFilesHoldOnePosePerSample) {
  struct Case {
    const char* file;
    const char* frames;
    std::function<Eigen::Isometry3d(int)> pose;
  };
  const Case cases[] = {{"odometry.tum", "T_odom_base", [](int i) { return planarPose(0.1 * i, 0.05 * i, 0.01 * i); }},
                        {"ground_truth.tum", "T_map_base",
                         [](int i) { return planarPose(2.0 + 0.1 * i, 1.0, 0.3 + 0.01 * i); }}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    const auto rows = lines(dir_ + "/" + c.file);
    ASSERT_EQ(rows.size(), 1u + kPoses);
    EXPECT_EQ(rows[0].rfind("# timestamp tx ty tz qx qy qz qw", 0), 0u);
    EXPECT_NE(rows[0].find(c.frames), std::string::npos);
    for (int i = 0; i < kPoses; ++i) {
      std::istringstream row(rows[1 + i]);
      double v[8];
      for (double& x : v) ASSERT_TRUE(row >> x) << rows[1 + i];
      EXPECT_NEAR(v[0], 1000.0 + 0.02 * i, 1e-9);
      const Eigen::Isometry3d want = c.pose(i);
      for (int a = 0; a < 3; ++a) EXPECT_NEAR(v[1 + a], want.translation()[a], 1e-8);
      const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
      EXPECT_NEAR(q.norm(), 1.0, 1e-8);
      EXPECT_NEAR(q.angularDistance(Eigen::Quaterniond(want.linear())), 0.0, 1e-8);
    }
  }
}

TEST_F(Dataset, MetadataDescribesEverything) {
  const auto doc = nlohmann::json::parse(slurp(dir_ + "/metadata.json"));
  EXPECT_EQ(doc["format"], "bimloc.dataset");
  EXPECT_EQ(doc["version"], 1);
  EXPECT_EQ(doc["scenario"], "unit");  // the caller's metadata, kept
  EXPECT_EQ(doc["seed"], 42);
  EXPECT_EQ(doc["time_offset_s"], 1000.0);
  EXPECT_EQ(doc["frames"]["map"], "map");
  EXPECT_EQ(doc["frames"]["velodyne"], "velodyne");
  expectPose(doc["T_base_lidar"]["xyz"], doc["T_base_lidar"]["quaternion_xyzw"], mount());
  EXPECT_EQ(doc["topics"]["/velodyne_points"]["messages"], kScans);
  EXPECT_EQ(doc["topics"]["/odom"]["messages"], kPoses);
  EXPECT_EQ(doc["topics"]["/tf"]["messages"], kPoses);
  EXPECT_EQ(doc["topics"]["/ground_truth"]["messages"], kPoses);
  EXPECT_EQ(doc["counts"]["points"], kScans * kPointsPerScan);
  EXPECT_EQ(doc["pointcloud2"]["point_step"], 22);
  EXPECT_NEAR(doc["time_range_s"][0].get<double>(), 1000.0, 1e-9);
  EXPECT_NEAR(doc["time_range_s"][1].get<double>(), 1000.98, 1e-9);

  // The listed files are exactly what commit() returned and exactly what is on disk.
  EXPECT_EQ(doc["files"].get<std::vector<std::string>>(), files_);
  std::set<std::string> on_disk;
  for (const auto& e : fs::recursive_directory_iterator(dir_))
    if (e.is_regular_file()) on_disk.insert(fs::relative(e.path(), dir_).string());
  EXPECT_EQ(on_disk, std::set<std::string>(files_.begin(), files_.end()));
  EXPECT_EQ(files_.size(), 5u + kScans);
}

TEST_F(Dataset, SameInputsGiveIdenticalFiles) {
  const std::string again = test::tempDir("dataset-again") + "/out";
  EXPECT_EQ(writeDataset(again), files_);
  for (const std::string& f : files_) EXPECT_TRUE(slurp(dir_ + "/" + f) == slurp(again + "/" + f)) << f;
}

TEST(DatasetFailure, DestroyedWithoutCommitLeavesNothing) {
  const std::string parent = test::tempDir("dataset-abandon");
  {
    sim::DatasetWriter writer(parent + "/out", info());
    sim::LidarScan scan;
    scan.points.push_back(expectedPoint(0, 1));
    writer.addScan(scan);
    writer.addOdometry({});
  }
  EXPECT_TRUE(fs::is_empty(parent));  // neither out/ nor a staging directory
}

TEST(DatasetFailure, UnusableLocationNamesThePath) {
  const std::string parent = test::tempDir("dataset-bad");
  std::ofstream(parent + "/plain_file") << "not a directory\n";
  for (const std::string& bad : {parent + "/plain_file/out", parent + "/plain_file", std::string("/proc/bimloc-out")}) {
    SCOPED_TRACE(bad);
    try {
      sim::DatasetWriter writer(bad, info());
      ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

TEST(DatasetFailure, RefusesANonEmptyOutputDirectory) {
  const std::string dir = test::tempDir("dataset-full");
  std::ofstream(dir + "/old.txt") << "an earlier run\n";
  EXPECT_THROW(sim::DatasetWriter(dir, info()), std::runtime_error);
  EXPECT_TRUE(fs::exists(dir + "/old.txt"));
}

TEST(DatasetFailure, RejectsBadSamples) {
  const std::string dir = test::tempDir("dataset-samples") + "/out";
  sim::DatasetWriter writer(dir, info());
  writer.addOdometry(odometryAt(1.0));
  EXPECT_THROW(writer.addOdometry(odometryAt(1.0)), std::invalid_argument);  // same stamp
  EXPECT_THROW(writer.addOdometry(odometryAt(0.5)), std::invalid_argument);  // backwards
  sim::GroundTruthSample too_early;
  too_early.stamp_s = -2000.0;  // before the dataset's clock starts
  EXPECT_THROW(writer.addGroundTruth(too_early), std::invalid_argument);
  sim::LidarScan scan;
  scan.frame_id = "laser";
  EXPECT_THROW(writer.addScan(scan), std::invalid_argument);
  sim::GroundTruthSample nan_pose;
  nan_pose.T_map_base.translation().x() = std::nan("");
  EXPECT_THROW(writer.addGroundTruth(nan_pose), std::invalid_argument);
  const auto files = writer.commit();
  EXPECT_EQ(lines(dir + "/odometry.tum").size(), 2u);  // the rejected samples left no trace
  EXPECT_EQ(lines(dir + "/ground_truth.tum").size(), 1u);
  EXPECT_THROW(writer.commit(), std::logic_error);
  EXPECT_THROW(writer.addOdometry(odometryAt(2.0)), std::logic_error);
}
