// Garbage in a recording never passes in silence (issue 29, section 5). The damaged bags are
// written by ROS's own python rosbag (tests/garble_bag.py) from a bag of `bimloc simulate`;
// each case gets an error naming the file and the problem with exit status 2, or a warning
// with exact counts (the truth: how many points and samples the script damaged) and the
// summary's numbers. The layout and odometry checks are also tested on their own, against
// layouts and motions built by hand.
#include "recording_fixtures.hpp"
#include "test_support.hpp"

#include "sim/dataset/cloud_fields.hpp"
#include "sim/dataset/recording_checks.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <tuple>

namespace fs = std::filesystem;
using namespace bimloc;
using test::runBimloc;

namespace {

const std::string kPlan = test::recordingPlan();
std::string simulated() { return test::simulatedRecording("garbage"); }  // made once, 8 s from the corridor

std::string cleanBag() { return simulated() + "/data/dataset.bag"; }

// The bag damaged by garble_bag.py MODE.
std::string garbled(const std::string& mode) {
  const std::string out = simulated() + "/" + mode + ".bag";
  if (!fs::exists(out)) {
    const std::string cmd = "/usr/bin/python3 '" + std::string(BIMLOC_TESTS_DIR) + "/garble_bag.py' '" + cleanBag() + "' '" +
                            out + "' " + mode + " >/dev/null";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
  return out;
}

test::CommandResult localize(const std::string& bag, const std::string& options = "") {
  return runBimloc("localize '" + bag + "' --plan '" + kPlan + "' " + options, 300.0);
}

nlohmann::json scenario(const test::CommandResult& r) {
  try {
    return nlohmann::json::parse(r.out)["scenarios"][0];
  } catch (const std::exception&) {
    ADD_FAILURE() << "not JSON: " << r.out << r.err;
    return {};
  }
}

// A bag refused: exit 2, one error naming the bag (and the message) and the problem, no output.
void expectRefused(const std::string& mode, const std::string& problem) {
  const std::string bag = garbled(mode);
  const std::string out = simulated() + "/out-" + mode;
  const auto r = localize(bag, "--out '" + out + "'");
  EXPECT_EQ(r.exit_code, 2) << mode << ": " << r.err << r.out;
  EXPECT_EQ(r.signal, 0) << mode;
  EXPECT_NE(r.err.find("bimloc localize: error: " + bag + ": "), std::string::npos) << mode << ": " << r.err;
  EXPECT_NE(r.err.find(problem), std::string::npos) << mode << ": " << r.err;
  EXPECT_FALSE(fs::exists(out)) << mode << ": output written for a refused input";
}

// The clean bag's cloud sizes: the truth for the counts.
struct CleanCounts {
  std::size_t clouds = 0, points = 0, odometry = 0;
  std::vector<std::size_t> per_cloud;
};

const CleanCounts& clean() {
  static const CleanCounts c = [] {
    CleanCounts counts;
    const auto r = localize(cleanBag(), "--json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const auto s = scenario(r);
    counts.clouds = s["recording"]["scans"]["read"];
    counts.points = s["recording"]["points"]["read"];
    counts.odometry = s["recording"]["odometry"]["read"];
    EXPECT_EQ(s["recording"]["points"]["dropped"], 0) << s["recording"];
    EXPECT_EQ(s["recording"]["odometry"]["dropped"], 0) << s["recording"];
    EXPECT_EQ(s["recording"]["odometry_jumps"]["count"], 0) << s["recording"];
    // Every cloud's own size, for the cases that damage a share of each (python rosbag).
    const std::string cmd = "/usr/bin/python3 -c \"import rosbag\nfor _, m, _ in rosbag.Bag('" + cleanBag() +
                            "').read_messages(topics=['/velodyne_points']): print(m.width * m.height)\"";
    FILE* pipe = ::popen(cmd.c_str(), "r");
    char line[64];
    while (pipe && std::fgets(line, sizeof line, pipe)) counts.per_cloud.push_back(std::stoul(line));
    if (pipe) ::pclose(pipe);
    EXPECT_EQ(counts.per_cloud.size(), counts.clouds);
    return counts;
  }();
  return c;
}

}  // namespace

// --- The layout checked against itself (checkCloudLayout), one case each ------------------

namespace {

sim::CloudLayout driverLayout(std::uint32_t points) {
  sim::CloudLayout l;
  l.fields = {{"x", 0, 7, 1}, {"y", 4, 7, 1}, {"z", 8, 7, 1}, {"intensity", 12, 7, 1}, {"ring", 16, 4, 1}, {"time", 18, 7, 1}};
  l.width = points, l.height = 1, l.point_step = 22, l.row_step = 22 * points;
  return l;
}

std::string layoutError(const sim::CloudLayout& l, std::size_t size) {
  try {
    sim::checkCloudLayout(l, size, "bag.bag: /velodyne_points message 7");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST(RecordingGarbage, CloudLayoutsThatContradictThemselvesAreRefusedByName) {
  const std::string where = "bag.bag: /velodyne_points message 7: ";
  EXPECT_EQ(layoutError(driverLayout(10), 220), "accepted");
  // Overlapping fields: x, y, z as FLOAT64 in the driver's 22-byte point.
  auto overlap = driverLayout(10);
  for (int i = 0; i < 3; ++i) overlap.fields[i].datatype = 8;
  EXPECT_EQ(layoutError(overlap, 220),
            where + "fields 'x' (FLOAT64, bytes 0 to 7) and 'y' (FLOAT64, bytes 4 to 11) overlap in a point of 22 bytes");
  // A field beyond point_step, counted fields included.
  auto beyond = driverLayout(10);
  beyond.fields[5].datatype = 8;
  EXPECT_EQ(layoutError(beyond, 220), where + "field 'time' (FLOAT64 at offset 18) lies outside point_step 22");
  auto counted = driverLayout(10);
  counted.fields[4].count = 2;  // ring x 2 at 16..19 runs into time at 18
  EXPECT_NE(layoutError(counted, 220).find("fields 'ring' (UINT16, bytes 16 to 19) and 'time'"), std::string::npos);
  // height 0 over a full data block; data too short; row_step too short; point_step 0.
  auto flat = driverLayout(10);
  flat.height = 0;
  EXPECT_EQ(layoutError(flat, 220), where + "data holds 220 bytes, the layout (10 x 0 points of 22 bytes, row_step 220) "
                                            "describes 0: the layout does not describe the data");
  EXPECT_EQ(layoutError(driverLayout(10), 200), where + "data holds 200 bytes, the layout (10 x 1 points of 22 bytes, "
                                                        "row_step 220) describes 220: points are missing");
  auto rows = driverLayout(10);
  rows.height = 2, rows.width = 5, rows.row_step = 100;
  EXPECT_EQ(layoutError(rows, 200), where + "row_step 100 is shorter than width * point_step = 110 (5 x 2 points of 22 "
                                            "bytes, row_step 100)");
  rows.row_step = 112;  // rows padded by 2 bytes: fine
  EXPECT_EQ(layoutError(rows, 224), "accepted");
  auto zero = driverLayout(10);
  zero.point_step = 0, zero.fields = {{"x", 0, 7, 0}, {"y", 0, 7, 0}, {"z", 0, 7, 0}};
  EXPECT_NE(layoutError(zero, 0).find("has count 0"), std::string::npos);
  // x, y, z: present once, FLOAT32 or FLOAT64.
  auto ints = driverLayout(10);
  ints.fields[1].datatype = 3;
  EXPECT_EQ(layoutError(ints, 220), where + "field 'y' is INT16: coordinates must be FLOAT32 or FLOAT64");
  auto unknown = driverLayout(10);
  unknown.fields[2].datatype = 42;
  EXPECT_EQ(layoutError(unknown, 220), where + "field 'z' has unknown datatype 42");
  auto twice = driverLayout(10);
  twice.fields[3].name = "x";
  EXPECT_EQ(layoutError(twice, 220), where + "the cloud has 2 fields named 'x'");
  // A field that is not read, of unknown datatype: a warning, not an error.
  auto odd = driverLayout(10);
  odd.fields[3].datatype = 13;
  const auto check = sim::checkCloudLayout(odd, 220, "w");
  ASSERT_EQ(check.warnings.size(), 1u);
  EXPECT_EQ(check.warnings[0], "field 'intensity' has unknown datatype 13 (not read)");
}

TEST(RecordingGarbage, AByteOrderFlagThatLiesIsRefusedAndATrueOneIsRead) {
  // 300 points of a room (1 to 20 m, mm detail), little-endian as every x86/ARM writer.
  const std::uint32_t n = 300;
  std::vector<std::uint8_t> data(22 * n), swapped(22 * n);
  std::vector<Eigen::Vector3f> truth;
  for (std::uint32_t i = 0; i < n; ++i) {
    const float r = 1.0f + 19.0f * static_cast<float>(i) / n + 0.001f * static_cast<float>(i % 7);
    const Eigen::Vector3f p(r * std::cos(0.1f * i), r * std::sin(0.1f * i), 0.3f - 0.002f * static_cast<float>(i % 11));
    truth.push_back(p);
    std::memcpy(&data[22 * i], p.data(), 12);
    for (int k = 0; k < 3; ++k)  // the same numbers big-endian
      for (int b = 0; b < 4; ++b) swapped[22 * i + 4 * k + b] = data[22 * i + 4 * k + 3 - b];
  }
  auto layout = driverLayout(n);
  layout.fields.resize(3);
  EXPECT_EQ(sim::decodeCloud(layout, data.data(), data.size(), "w").xyz, truth);
  layout.is_bigendian = true;
  EXPECT_EQ(sim::decodeCloud(layout, swapped.data(), swapped.size(), "w").xyz, truth);  // true big-endian data: read
  try {
    sim::decodeCloud(layout, data.data(), data.size(), "bag.bag: /velodyne_points message 0");
    ADD_FAILURE() << "little-endian data declared big-endian was read";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bag.bag: /velodyne_points message 0: is_bigendian = 1, but read so "), std::string::npos) << what;
    EXPECT_NE(what.find("the writer set is_bigendian wrongly"), std::string::npos) << what;
  }
  layout.is_bigendian = false;  // and the other way round
  EXPECT_THROW(sim::decodeCloud(layout, swapped.data(), swapped.size(), "w"), std::runtime_error);
}

TEST(RecordingGarbage, PointsAreCountedByWhyTheyAreNoMeasurement) {
  std::vector<Eigen::Vector3f> xyz{{1, 0, 0}, {0, 0, 0}, {0.1f, 0, 0}, {150, 0, 0}, {1e30f, 0, 0},
                                   {std::numeric_limits<float>::infinity(), 0, 0}, {0, 99.9f, 0}, {3e38f, 3e38f, 0}};
  std::vector<double> times{0, 1, 2, 3, 4, 5, 6, 7};
  sim::PointDrops before;
  before.non_finite = 2;
  const auto d = sim::keepUsablePoints(xyz, &times, sim::SensorRange{}, before);
  EXPECT_EQ(d.read, 10u);
  EXPECT_EQ(d.non_finite, 3u);  // 2 before, +inf
  EXPECT_EQ(d.at_origin, 1u);
  EXPECT_EQ(d.below_min_range, 1u);
  EXPECT_EQ(d.beyond_max_range, 3u);  // 150 m, 1e30 m, and 4e38 m (finite in double)
  EXPECT_EQ(xyz, (std::vector<Eigen::Vector3f>{{1, 0, 0}, {0, 99.9f, 0}}));
  EXPECT_EQ(times, (std::vector<double>{0, 6}));
}

TEST(RecordingGarbage, OdometryJumpsAreJudgedAgainstASpeedScaledWithTheInterval) {
  auto at = [](double t, double x, double yaw_deg) {
    sim::StampedPose p;
    p.stamp_s = t;
    p.pose.translation().x() = x;
    p.pose.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return p;
  };
  // 50 Hz: 1.9 m and 44 deg pass, 2.1 m and 46 deg do not.
  EXPECT_EQ(sim::findJumps({at(0, 0, 0), at(0.02, 1.9, 44)}).count, 0u);
  EXPECT_EQ(sim::findJumps({at(0, 0, 0), at(0.02, 2.1, 0)}).count, 1u);
  EXPECT_EQ(sim::findJumps({at(0, 0, 0), at(0.02, 0, 46)}).count, 1u);
  // 10 Hz: five times the bound (10 m); 1 kHz: never below the 50 Hz bound.
  EXPECT_EQ(sim::findJumps({at(0, 0, 0), at(0.1, 9.5, 0)}).count, 0u);
  EXPECT_EQ(sim::findJumps({at(0, 0, 0), at(0.1, 10.5, 0)}).count, 1u);
  EXPECT_EQ(sim::findJumps({at(0, 0, 0), at(0.001, 1.5, 0)}).count, 0u);
  const auto j = sim::findJumps({at(0, 0, 0), at(0.02, 0.1, 0), at(0.04, 5.1, 0), at(0.06, 0.2, 0)});
  EXPECT_EQ(j.count, 2u);  // there and back
  EXPECT_NEAR(j.worst_m, 5.0, 1e-9);
  // Samples that are no pose.
  sim::PoseSampleDrops drops;
  EXPECT_FALSE(sim::checkedPose(NAN, 0, 0, 0, 0, 0, 1, drops));
  EXPECT_FALSE(sim::checkedPose(0, 0, 0, 0, 0, 0, 0, drops));
  EXPECT_FALSE(sim::checkedPose(0, 0, 0, 0, 0, 0, 0.5, drops));
  EXPECT_TRUE(sim::checkedPose(1, 2, 3, 0, 0, 0, 1, drops));
  EXPECT_EQ(drops.read, 4u);
  EXPECT_EQ(drops.non_finite, 1u);
  EXPECT_EQ(drops.zero_quaternion, 1u);
  EXPECT_EQ(drops.not_unit_quaternion, 1u);
}

// --- The seven bags that ran in silence, and more, through `bimloc localize` --------------

TEST(RecordingGarbage, EveryPointNaNIsRefused) {
  const auto& c = clean();
  expectRefused("nan", "no scan has a usable point: " + std::to_string(c.clouds) + " of " + std::to_string(c.clouds) +
                           " scans skipped: no usable point");
  const auto r = localize(garbled("nan"));
  EXPECT_NE(r.err.find(std::to_string(c.points) + " of " + std::to_string(c.points) + " points dropped (" +
                       std::to_string(c.points) + " not finite)"),
            std::string::npos) << r.err;
}

TEST(RecordingGarbage, EveryPointInfiniteIsRefused) {
  const auto& c = clean();
  expectRefused("inf", std::to_string(c.points) + " of " + std::to_string(c.points) + " points dropped (" +
                           std::to_string(c.points) + " not finite)");
}

TEST(RecordingGarbage, EveryPointAt1e30MetresIsRefused) {
  const auto& c = clean();
  expectRefused("far", std::to_string(c.points) + " of " + std::to_string(c.points) + " points dropped (" +
                           std::to_string(c.points) + " beyond the sensor's max range)");
}

TEST(RecordingGarbage, EveryPointAtTheSensorsOriginIsRefused) {
  const auto& c = clean();
  expectRefused("origin", std::to_string(c.points) + " of " + std::to_string(c.points) + " points dropped (" +
                              std::to_string(c.points) + " at the sensor's origin)");
}

TEST(RecordingGarbage, HeightZeroOverAFullDataBlockIsRefused) {
  const auto n = clean().per_cloud.at(0);
  expectRefused("height0", "/velodyne_points message 0: data holds " + std::to_string(22 * n) + " bytes, the layout (" +
                               std::to_string(n) + " x 0 points of 22 bytes, row_step " + std::to_string(22 * n) +
                               ") describes 0: the layout does not describe the data");
}

TEST(RecordingGarbage, OverlappingFieldsAreRefused) {
  expectRefused("overlap", "/velodyne_points message 0: fields 'x' (FLOAT64, bytes 0 to 7) and 'y' (FLOAT64, bytes 4 to 11) "
                           "overlap in a point of 22 bytes");
}

TEST(RecordingGarbage, BigEndianDeclaredOnLittleEndianDataIsRefused) {
  expectRefused("bigendian", "/velodyne_points message 0: is_bigendian = 1, but read so ");
}

TEST(RecordingGarbage, ScansWithNoUsablePointAreSkippedAndCounted) {
  const auto& c = clean();
  const auto r = localize(garbled("halfnan"), "--json");
  EXPECT_EQ(r.exit_code, 0) << r.err;  // half the turns still localize the robot
  std::size_t skipped = 0, nan_points = 0;
  for (std::size_t i = 0; i < c.per_cloud.size(); i += 2) ++skipped, nan_points += c.per_cloud[i];
  const auto s = scenario(r);
  EXPECT_EQ(s["recording"]["scans"]["skipped_no_usable_point"], skipped);
  EXPECT_EQ(s["recording"]["points"]["non_finite"], nan_points);
  EXPECT_EQ(s["recording"]["points"]["dropped"], nan_points);
  const auto summary = nlohmann::json::parse(r.out)["summary"]["recording"];
  EXPECT_EQ(summary["scans"]["skipped_no_usable_point"], skipped);
  const std::string warning = std::to_string(skipped) + " of " + std::to_string(c.clouds) +
                              " scans skipped: no usable point (" + garbled("halfnan") + ": message 0; ";
  EXPECT_NE(r.err.find("bimloc localize: warning: " + garbled("halfnan") + ": " + warning), std::string::npos) << r.err;
  EXPECT_EQ(s["warnings"][0].get<std::string>().rfind(warning, 0), 0u) << s["warnings"];
  // The table says it too, and report.json.
  const std::string out = simulated() + "/out-halfnan";
  const auto table = localize(garbled("halfnan"), "--out '" + out + "'");
  EXPECT_NE(table.out.find(": dropped " + std::to_string(skipped) + " of " + std::to_string(c.clouds) +
                           " scans (no usable point), " + std::to_string(nan_points) + " of " + std::to_string(c.points) +
                           " points (" + std::to_string(nan_points) + " not finite, 0 at the origin"),
            std::string::npos) << table.out;
  std::ifstream report(out + "/report.json");
  const auto j = nlohmann::json::parse(report);
  EXPECT_EQ(j["scenarios"][0]["recording"]["scans"]["skipped_no_usable_point"], skipped);
  EXPECT_EQ(j["summary"]["recording"]["points"]["non_finite"], nan_points);
}

TEST(RecordingGarbage, PointsOutOfTheSensorsRangeAreDroppedAndCounted) {
  const auto& c = clean();
  std::size_t far = 0, near = 0;
  for (std::size_t n : c.per_cloud) far += (n + 9) / 10, near += (n + 4) / 10;
  const auto r = localize(garbled("someout"), "--json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto s = scenario(r);
  EXPECT_EQ(s["recording"]["points"]["beyond_max_range"], far);
  EXPECT_EQ(s["recording"]["points"]["below_min_range"], near);
  EXPECT_EQ(s["recording"]["scans"]["skipped_no_usable_point"], 0);
  EXPECT_NE(r.err.find(std::to_string(far + near) + " of " + std::to_string(c.points) + " points dropped (" +
                       std::to_string(near) + " below the sensor's min range, " + std::to_string(far) +
                       " beyond the sensor's max range)"),
            std::string::npos) << r.err;
  // The range is the user's to set: with 200 m, only the near ones go.
  const auto wide = scenario(localize(garbled("someout"), "--json --max-range 200"));
  EXPECT_EQ(wide["recording"]["points"]["beyond_max_range"], 0);
  EXPECT_EQ(wide["recording"]["points"]["below_min_range"], near);
  const auto bad = localize(garbled("someout"), "--min-range 5 --max-range 1");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--min-range and --max-range: expected 0 <= min < max"), std::string::npos) << bad.err;
}

TEST(RecordingGarbage, OdometrySamplesThatAreNoPoseAreDroppedAndCounted) {
  const auto& c = clean();
  const std::size_t every_tenth = (c.odometry + 9) / 10;
  for (const auto& [mode, key, words] :
       {std::tuple{"odomnan", "non_finite", "not finite"}, std::tuple{"odomzeroq", "zero_quaternion", "with a zero quaternion"}}) {
    const auto r = localize(garbled(mode), "--json");
    EXPECT_EQ(r.exit_code, 0) << mode << ": " << r.err;  // the other 90 % carry the run
    const auto s = scenario(r);
    EXPECT_EQ(s["recording"]["odometry"]["read"], c.odometry) << mode;
    EXPECT_EQ(s["recording"]["odometry"][key], every_tenth) << mode;
    EXPECT_EQ(s["recording"]["odometry"]["dropped"], every_tenth) << mode;
    EXPECT_NE(r.err.find("warning: " + garbled(mode) + ": odometry: " + std::to_string(every_tenth) + " of " +
                         std::to_string(c.odometry) + " samples dropped (" + std::to_string(every_tenth) + " " + words + ")"),
              std::string::npos) << mode << ": " << r.err;
  }
}

TEST(RecordingGarbage, OdometryJumpsAreWarnedWithCounts) {
  const auto r = localize(garbled("odomjump"), "--json");
  EXPECT_NE(r.exit_code, 2) << r.err;
  const auto s = scenario(r);
  EXPECT_EQ(s["recording"]["odometry_jumps"]["count"], 2);  // there and back
  EXPECT_NEAR(s["recording"]["odometry_jumps"]["worst_m"].get<double>(), 5.0, 0.2);
  EXPECT_NE(r.err.find("odometry: 2 jumps beyond what a base can do (2 m or 45 deg per 20 ms); the largest "), std::string::npos)
      << r.err;
}

// --- Exit statuses: 0 localized, 1 ran and did not localize, 2 the input cannot be used -----

TEST(RecordingGarbage, ExitStatusesTellNotLocalizedFromUnusableInput) {
  const auto ok = localize(cleanBag());
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  // Ran and did not localize: a convergence rule no run can meet (the corridor start is decided
  // from its first turn, so no cut of this bag is too short to localize).
  const std::string never = simulated() + "/never.yaml";
  std::ofstream(never) << "pf: {converged_updates: 1000}\n";
  const auto not_localized = localize(cleanBag(), "--json --config '" + never + "'");
  EXPECT_EQ(not_localized.exit_code, 1) << not_localized.err;
  EXPECT_FALSE(scenario(not_localized)["converged"].get<bool>());
  // The input cannot be used: not a bag, a missing plan, a bad option value, a missing option.
  std::ofstream(simulated() + "/notes.bag") << "not a bag";
  EXPECT_EQ(localize(simulated() + "/notes.bag").exit_code, 2);
  EXPECT_EQ(runBimloc("localize '" + cleanBag() + "' --plan /nonexistent.ifc").exit_code, 2);
  EXPECT_EQ(localize(cleanBag(), "--mount 1,2").exit_code, 2);
  EXPECT_EQ(runBimloc("localize '" + cleanBag() + "'").exit_code, 2);  // no --plan
  // `run` and `sweep` alike: a scenario file that cannot be used, a plan that is not one.
  std::ofstream(simulated() + "/bad.yaml") << "name: [unclosed\n";
  const auto run_bad = runBimloc("run '" + simulated() + "/bad.yaml'");
  EXPECT_EQ(run_bad.exit_code, 2) << run_bad.err;
  EXPECT_NE(run_bad.err.find(simulated() + "/bad.yaml"), std::string::npos) << run_bad.err;
  EXPECT_EQ(runBimloc("sweep /nonexistent.ifc").exit_code, 2);
  EXPECT_EQ(runBimloc("run --plan '" + kPlan + "' --all-rooms --rooms NOSUCHROOM").exit_code, 2);
  // Ran, and not every run localized: 1 s is too short to localize from a room.
  const auto run_short = runBimloc("run --plan '" + kPlan + "' --all-rooms --rooms R101 --duration 1 --json", 300.0);
  EXPECT_EQ(run_short.exit_code, 1) << run_short.err;
  const auto sweep_short = runBimloc("sweep '" + kPlan + "' --rooms-per-storey 1 --seeds 1 --duration 1 --json", 300.0);
  EXPECT_EQ(sweep_short.exit_code, 1) << sweep_short.err;
  // --help says so.
  for (const char* command : {"localize", "run", "sweep"}) {
    const auto help = runBimloc(std::string(command) + " --help");
    EXPECT_EQ(help.exit_code, 0);
    EXPECT_NE(help.out.find("docs/exit_codes.md"), std::string::npos) << command << ": " << help.out;
  }
}
