// `bimloc localize` on ROS1 bags (issue 13, part 1). The truths: the dataset folder of the
// same simulation (the folder reader is independent of the bag reader), the same bag
// rewritten by ROS's own python rosbag (tests/rewrite_bag.py: renamed topics and frames,
// the clouds' fields in another order and width, no odometry), analytic clouds and motions
// for the field decoding and the de-skew, and python rosbag again reading localized.bag.
#include "bag_fixtures.hpp"
#include "test_support.hpp"

#include "sim/dataset/cloud_fields.hpp"
#include "sim/dataset/deskew.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using namespace bimloc;
using test::runBimloc;

namespace {

const std::string& kPlan = test::officePlan();

const std::string& simulated() { return test::simulatedCorridor("bag-input"); }

std::string rewritten(const std::string& mode) { return test::rewrittenBag(simulated(), mode); }

using test::localizeJson;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

template <class T>
void put(std::vector<std::uint8_t>& data, std::size_t at, T value, bool big_endian = false) {
  std::uint8_t bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T); ++i) data[at + i] = bytes[big_endian ? sizeof(T) - 1 - i : i];
}

}  // namespace

TEST(BagInput, CloudFieldsAreDecodedByNameWhateverTheirOrderWidthAndByteOrder) {
  const std::vector<Eigen::Vector3f> truth{{1.5f, -2.25f, 0.125f}, {3.0f, 4.0f, -1.0f}, {-7.5f, 0.5f, 2.0f}};
  const std::vector<double> times{0.0, 0.025, 0.05};
  // The driver's wire layout (x y z intensity f32, ring u16, time f32 at 18; step 22), and a
  // converter's: time f64 first, ring, z f32, y f64, x f32, padded, big-endian.
  sim::CloudLayout driver;
  driver.fields = {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"intensity", 12, 7, 1}, {"ring", 16, 4, 1}, {"time", 18, 7, 1}};
  driver.width = 3, driver.height = 1, driver.point_step = 22, driver.row_step = 66;
  std::vector<std::uint8_t> a(66);
  sim::CloudLayout other;
  other.fields = {{"time", 0, 8, 1}, {"ring", 9, 4, 1}, {"z", 12, 7, 1}, {"y", 17, 8, 1}, {"x", 26, 7, 1}};
  other.width = 3, other.height = 1, other.point_step = 32, other.row_step = 96, other.is_bigendian = true;
  std::vector<std::uint8_t> b(96);
  for (std::size_t i = 0; i < 3; ++i) {
    put(a, i * 22 + 0, truth[i].x()), put(a, i * 22 + 4, truth[i].y()), put(a, i * 22 + 8, truth[i].z());
    put(a, i * 22 + 18, static_cast<float>(times[i]));
    put(b, i * 32 + 0, times[i], true), put(b, i * 32 + 12, truth[i].z(), true);
    put(b, i * 32 + 17, static_cast<double>(truth[i].y()), true), put(b, i * 32 + 26, truth[i].x(), true);
  }
  for (const auto& [layout, data] : {std::pair{driver, a}, std::pair{other, b}}) {
    const sim::CloudPoints p = sim::decodeCloud(layout, data.data(), data.size(), "test");
    ASSERT_EQ(p.xyz.size(), 3u);
    ASSERT_EQ(p.time_s.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(p.xyz[i], truth[i]) << i;
      EXPECT_NEAR(p.time_s[i], times[i], 1e-7) << i;
    }
  }
  // A point with no return (NaN) is dropped; a cloud with no z, or data shorter than the
  // layout, is refused by name.
  put(a, 22 + 0, std::nanf(""));
  EXPECT_EQ(sim::decodeCloud(driver, a.data(), a.size(), "test").xyz.size(), 2u);
  try {
    sim::decodeCloud(driver, a.data(), 60, "bag.bag: /velodyne_points message 4");
    ADD_FAILURE() << "short data accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bag.bag: /velodyne_points message 4: data holds 60 bytes"), std::string::npos) << e.what();
  }
  sim::CloudLayout no_z = driver;
  no_z.fields.erase(no_z.fields.begin() + 2);
  EXPECT_THROW(sim::decodeCloud(no_z, a.data(), a.size(), "test"), std::runtime_error);
}

TEST(BagInput, DeskewPutsPointsMeasuredDuringATurnAndAWalkWhereTheyWereAtTheReference) {
  // The robot walks at 1 m/s along x and turns at 90 deg/s; odometry at 100 Hz. A point fixed
  // in odom, measured at t_i from the lidar pose of t_i, must come out as seen from the pose
  // at the reference. Constant velocities: the interpolation (linear, slerp) is exact.
  const double w = M_PI / 2, v = 1.0;
  auto T_odom_base = [&](double t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(w * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(v * t, 0, 0);
    return T;
  };
  std::vector<sim::StampedPose> odometry;
  for (int k = 0; k <= 100; ++k) odometry.push_back({10.0 + 0.01 * k, T_odom_base(0.01 * k)});
  Eigen::Isometry3d T_base_lidar = Eigen::Isometry3d::Identity();
  T_base_lidar.translation() = Eigen::Vector3d(0.2, 0.0, 0.5);
  T_base_lidar.linear() = Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const double stamp = 10.3, reference = 10.35;
  std::vector<Eigen::Vector3f> points;
  std::vector<double> times;
  std::vector<Eigen::Vector3d> in_odom;
  for (int i = 0; i < 100; ++i) {
    const double t = 0.001 * i;
    const Eigen::Vector3d P(5.0 * std::cos(0.3 * i), 5.0 * std::sin(0.3 * i), 0.1 * (i % 7));
    in_odom.push_back(P);
    points.push_back(((T_odom_base(stamp - 10.0 + t) * T_base_lidar).inverse() * P).cast<float>());
    times.push_back(t);
  }
  sim::deskew(points, times, stamp, reference, odometry, T_base_lidar);
  const Eigen::Isometry3d T_ref = (T_odom_base(reference - 10.0) * T_base_lidar).inverse();
  for (int i = 0; i < 100; ++i) EXPECT_LT((points[i].cast<double>() - T_ref * in_odom[i]).norm(), 1e-4) << i;
}

TEST(BagInput, ASimulatedBagLocalizesLikeItsFolder) {
  const std::string data = simulated() + "/data";
  const auto folder = localizeJson(data);
  const auto bag = localizeJson(data + "/dataset.bag", "--no-deskew");
  ASSERT_TRUE(folder["converged"]);
  EXPECT_EQ(bag["converged"], folder["converged"]);
  EXPECT_EQ(bag["found_room"], folder["found_room"]);
  EXPECT_EQ(bag["false_convergence"], false);
  // The bag interpolates the odometry at mid-turn where the folder takes the nearest sample.
  EXPECT_NEAR(bag["position_error_m"].get<double>(), folder["position_error_m"].get<double>(), 0.02);
  EXPECT_NEAR(bag["convergence_time_s"].get<double>(), folder["convergence_time_s"].get<double>(), 0.51);
  // De-skewed (the default with the driver's time field): as good.
  const auto deskewed = localizeJson(data + "/dataset.bag");
  EXPECT_TRUE(deskewed["converged"]);
  EXPECT_EQ(deskewed["false_convergence"], false);
  EXPECT_LT(deskewed["position_error_m"].get<double>(), 0.1);
}

TEST(BagInput, RenamedTopicsAndFramesLocalizeWithTheOptions) {
  const std::string bag = rewritten("rename");
  const auto refused = runBimloc("localize '" + bag + "' --plan '" + kPlan + "'");
  EXPECT_EQ(refused.exit_code, 2);  // the input cannot be used
  // The missing topic, then every topic of the bag with its type.
  EXPECT_NE(refused.err.find(bag + ": no topic /velodyne_points (sensor_msgs/PointCloud2 or velodyne_msgs/VelodyneScan; choose another with --cloud-topic)"),
            std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("/lidar/points (sensor_msgs/PointCloud2, 80 messages)"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("/legs/odom (nav_msgs/Odometry,"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("/tf_static (tf2_msgs/TFMessage, 1 messages)"), std::string::npos) << refused.err;

  const auto original = localizeJson(simulated() + "/data/dataset.bag");
  const std::string frames = "--cloud-topic /lidar/points --odom-frame odom_legs --base-frame body";
  // Odometry from the renamed topic, then from /tf alone (the same poses): the same run.
  EXPECT_EQ(localizeJson(bag, frames + " --odom-topic /legs/odom"), original);
  EXPECT_EQ(localizeJson(bag, frames), original);
  // A mount given by hand instead of /tf_static: the simulator's (metadata.json).
  const auto meta = nlohmann::json::parse(slurp(simulated() + "/data/metadata.json"))["T_base_lidar"];
  const Eigen::Quaterniond q(meta["quaternion_xyzw"][3], meta["quaternion_xyzw"][0], meta["quaternion_xyzw"][1],
                             meta["quaternion_xyzw"][2]);
  const Eigen::Vector3d rpy = q.toRotationMatrix().eulerAngles(2, 1, 0);
  std::ostringstream mount;
  mount.precision(17);
  mount << meta["xyz"][0].get<double>() << "," << meta["xyz"][1].get<double>() << "," << meta["xyz"][2].get<double>()
        << "," << rpy[2] << "," << rpy[1] << "," << rpy[0];
  const auto manual = localizeJson(bag, frames + " --mount " + mount.str());
  EXPECT_EQ(manual["converged"], true);
  EXPECT_NEAR(manual["position_error_m"].get<double>(), original["position_error_m"].get<double>(), 1e-3);
}

TEST(BagInput, OdometryOnTfThroughAFootprintFrameIsComposedWithItsFixedTransform) {
  const auto original = localizeJson(simulated() + "/data/dataset.bag");
  const auto r = runBimloc("localize '" + rewritten("footprint") + "' --plan '" + kPlan + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("odometry: /tf odom -> base_link (via base_footprint)"), std::string::npos) << r.out;
  const auto via = localizeJson(rewritten("footprint"));
  EXPECT_EQ(via["converged"], true);
  EXPECT_NEAR(via["position_error_m"].get<double>(), original["position_error_m"].get<double>(), 1e-3);
  EXPECT_NEAR(via["ate_m"].get<double>(), original["ate_m"].get<double>(), 1e-3);
}

TEST(BagInput, CloudsWithTheFieldsInAnotherOrderGiveTheSamePoints) {
  // Identical points (y widened to FLOAT64 exactly), identical times: an identical run.
  EXPECT_EQ(localizeJson(rewritten("reorder")), localizeJson(simulated() + "/data/dataset.bag"));
}

TEST(BagInput, ABagWithNoOdometryFailsClearly) {
  const std::string bag = rewritten("noodom");
  const auto r = runBimloc("localize '" + bag + "' --plan '" + kPlan + "'");
  EXPECT_EQ(r.exit_code, 2);  // the input cannot be used
  EXPECT_NE(r.err.find(bag + ": no odometry: no topic /odom (nav_msgs/Odometry; choose it with --odom-topic) and no "
                             "/tf transform odom -> base_link"),
            std::string::npos) << r.err;
  EXPECT_NE(r.err.find("/velodyne_points (sensor_msgs/PointCloud2, 80 messages)"), std::string::npos) << r.err;
  // Odometry on another clock: as good as none.
  const std::string late = rewritten("otherclock");
  const auto r2 = runBimloc("localize '" + late + "' --plan '" + kPlan + "'");
  EXPECT_EQ(r2.exit_code, 2);  // the input cannot be used
  EXPECT_NE(r2.err.find(late + ": the clouds (1000.000 to 1008.000 s) and the odometry (101000.000 to 101008.000 s) never "
                               "overlap in time"),
            std::string::npos) << r2.err;
}

TEST(BagInput, OutputsAreWrittenWholeAndReadBack) {
  const std::string out = simulated() + "/out";
  const auto r = runBimloc("localize '" + simulated() + "/data/dataset.bag' --plan '" + kPlan + "' --out '" + out + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  // trajectory.tum: 8 numbers a line, increasing stamps, near the ground truth's poses.
  std::ifstream tum(out + "/trajectory.tum");
  std::string line;
  std::size_t poses = 0;
  double previous = 0;
  while (std::getline(tum, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    double v[8];
    for (double& x : v) ASSERT_TRUE(ss >> x) << line;
    EXPECT_GT(v[0], previous);
    previous = v[0];
    EXPECT_NEAR(Eigen::Vector4d(v[4], v[5], v[6], v[7]).norm(), 1.0, 1e-6);
    ++poses;
  }
  EXPECT_GT(poses, 50u);  // 80 turns, converged within 2 s
  const auto report = nlohmann::json::parse(slurp(out + "/report.json"));
  EXPECT_EQ(report["format"], "bimloc.localize");
  EXPECT_TRUE(report["scenarios"][0]["converged"]);
  EXPECT_TRUE(fs::exists(out + "/snapshots/0_convergence.png"));
  EXPECT_TRUE(fs::exists(out + "/snapshots/1_end.png"));
  EXPECT_TRUE(fs::exists(out + "/snapshots/snapshots/errors.png") || fs::exists(out + "/snapshots/errors.png"));
  // localized.bag through python rosbag: the input's messages, one map -> odom and one
  // /localization per trajectory pose.
  const std::string cmd = "/usr/bin/python3 '" + std::string(BIMLOC_TESTS_DIR) + "/summarize_localized_bag.py' '" + out +
                          "/localized.bag'";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string text;
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe)) text.append(buffer, n);
  ASSERT_EQ(::pclose(pipe), 0) << text;
  const auto bag = nlohmann::json::parse(text);
  EXPECT_EQ(bag["counts"]["/velodyne_points"], 80);
  EXPECT_EQ(bag["counts"]["/localization"], poses);
  EXPECT_EQ(bag["map_odom"], poses);
  EXPECT_EQ(bag["poses"][0]["frame_id"], "map");
  EXPECT_GT(bag["poses"][0]["cov_xx"].get<double>(), 0.0);
  // Again into the same folder: replaced whole; into a file that is no earlier output: refused.
  ASSERT_EQ(runBimloc("localize '" + simulated() + "/data/dataset.bag' --plan '" + kPlan + "' --out '" + out + "'").exit_code, 0);
  std::ofstream(simulated() + "/precious.txt") << "keep";
  const auto refused = runBimloc("localize '" + simulated() + "/data/dataset.bag' --plan '" + kPlan + "' --out '" +
                                 simulated() + "/precious.txt'");
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_EQ(slurp(simulated() + "/precious.txt"), "keep");
}

TEST(BagInput, DamagedBagsAreRefusedByNameNeverACrash) {
  const std::string clean = simulated() + "/data/dataset.bag";
  const std::string bytes = slurp(clean);
  const std::string dir = simulated() + "/damaged";
  fs::create_directories(dir);
  int refused = 0, accepted = 0;
  // Cut at six places (a recording that stopped mid-write), and bytes overwritten at four.
  for (int i = 0; i < 10; ++i) {
    std::string damaged = bytes;
    const std::size_t at = i < 6 ? 13 + (bytes.size() - 13) * (i + 1) / 7 : 13 + (bytes.size() - 13) * (i - 5) / 5;
    if (i < 6) {
      damaged.resize(at);
    } else {
      for (std::size_t k = at; k < std::min(at + 64, damaged.size()); ++k) damaged[k] = static_cast<char>(0xA5 ^ k);
    }
    const std::string path = dir + "/" + std::to_string(i) + ".bag";
    std::ofstream(path, std::ios::binary) << damaged;
    const auto r = runBimloc("localize '" + path + "' --plan '" + kPlan + "' --json", 60.0);
    EXPECT_EQ(r.signal, 0) << i << ": " << r.err;
    EXPECT_FALSE(r.timed_out) << i;
    if (r.exit_code == 2) {  // the input cannot be used; 1 would be a run that did not localize
      ++refused;
      EXPECT_NE(r.err.find(path + ": "), std::string::npos) << i << ": " << r.err;
    } else {
      ++accepted;
    }
    if (i < 6) {
      EXPECT_EQ(r.exit_code, 2) << i << ": a truncated bag was accepted";
    }
  }
  std::cout << "damaged bags: " << refused << " refused, " << accepted << " accepted" << std::endl;
}
