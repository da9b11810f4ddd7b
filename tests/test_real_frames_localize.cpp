// `bimloc localize` on the real frames (issue 29 §4, "Localization"): each of the five frames,
// WHOLE (as the PCD has it, nothing chosen in the test), as a standing robot in the measured plan
// worlds/nebula_room.ifc, written as a dataset folder by the project's writer. A rectangle room
// allows two places, 180 degrees apart: the run does not converge, and lists the places it still
// fits (`hypotheses` in the report).
//
// The places listed are fitted poses (pf FilterAccess::fitPlaces: each of the path evidence's
// places fitted again on the latest scans with the sensor's own noise, as the converged pose
// is). The plan's north wall is the wall behind the shelving (7.12 m wide): on the plan with its
// north face at the shelving's front (6.56 m), the wall seen between and above the shelves lay
// behind that face, a contradiction, and the VLP-16, the 40P and the XT32 got the other reading
// across the room, 0.50-0.59 m off. With the wall where it is, the shelving is clutter before it;
// and the local search weighs the pieces of one surface as one surface, matched or not (the
// support-weighted mean of their costs, measurement.cpp), so that the shelving's front cut into
// five pieces no longer outvotes the wall seen in two, and a wall with cabinets along it is not
// dearer matched than left unexplained (the XT32's place was fitted 0.29 m off while unexplained
// pieces counted once and matched ones each: docs/results/2026-11-27-h29close.md). Measured: the nearest place 0.058, 0.046, 0.042, 0.081
// and 0.029 m from the pose the walls give (VLP-16, 40P, 64, XT32, QT64).
#include "real_frames.hpp"
#include "test_support.hpp"

#include "sim/dataset/dataset_writer.hpp"

#include <bimloc/bim/ifc_reader.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <iostream>
#include <string>

using namespace bimloc;

namespace {

constexpr int kTurns = 30;              // 3 s of a 10 Hz lidar
constexpr double kMountHeight_m = 0.5;  // SOURCES.md: the floor 0.4-0.6 m below each sensor
// A listed place is the walls' reading (or its turned twin) within these: the brief's heading,
// and 0.65 m for the twin; the brief's bar, 0.1 m, for the place nearest the walls' pose.
constexpr double kReading_m = 0.65, kPlace_m = 0.1, kPlace_deg = 2.0;
// The shelving's front from the south wall as measured (docs/realdata_room.md section 3): where
// the VLP-16 stands across the room, which sees no south wall.
constexpr double kShelfFromSouth_m = 6.56;

double yawDiffDeg(double a_deg, double b_deg) { return std::abs(std::remainder(a_deg - b_deg, 360.0)); }

// The frame repeated kTurns times at 10 Hz, the odometry still at 50 Hz.
void writeStandingRobot(const std::string& dir, const std::vector<Eigen::Vector3f>& points, const std::string& sensor) {
  sim::DatasetInfo info;
  info.metadata = {{"source", "nebula " + sensor + " (../shared/realdata), one real turn repeated"}};
  info.T_base_lidar.translation() = Eigen::Vector3d(0, 0, kMountHeight_m);
  sim::DatasetWriter writer(dir, info);
  sim::LidarScan scan;
  for (const auto& p : points) scan.points.push_back({p.x(), p.y(), p.z(), 0.f, 0, 0.f});
  for (int i = 0; i <= 5 * kTurns; ++i) {
    if (i % 5 == 0 && i / 5 < kTurns) {
      scan.stamp_s = 0.1 * (i / 5);
      writer.addScan(scan);
    }
    sim::OdometrySample odom;
    odom.stamp_s = 0.02 * i;
    writer.addOdometry(odom);
  }
  writer.commit();
}

}  // namespace

TEST(RealFramesLocalize, AStandingRobotGetsTheRectanglesTwoPlaces) {
  const std::vector<test::RealFrame>* frames = test::nebulaFrames();
  if (!frames) GTEST_SKIP() << "../shared/realdata/nebula not found (BIMLOC_SHARED_REALDATA_DIR): skipping the real frames";
  const std::string plan = std::string(BIMLOC_WORLDS_DIR) + "/nebula_room.ifc";
  const bim::Building building = bim::readIfc(plan);
  Eigen::AlignedBox2d room;
  for (const auto& p : building.storeys.at(0).rooms.at(0).footprint) room.extend(p);
  // The extractor's settings of the plane tests (tests/real_frames.hpp), as a user would give them.
  const std::string work = test::tempDir("real-frames-localize");
  const std::string config = work + "/real_frames.yaml";
  std::ofstream(config) << "planes: {ransac_iterations: 5000, min_inliers: 20, ring_spacing_deg: 0, max_planes: 60, standing_height_m: 0.3}\n";
  for (const test::RealFrame& frame : *frames) {
    SCOPED_TRACE(frame.sensor);
    const std::string dir = work + "/" + frame.sensor;
    // The whole frame, as the PCD has it: the localizer's own extraction (its standing stage,
    // set in the YAML) finds the walls.
    writeStandingRobot(dir, frame.points, frame.sensor);
    const auto r = test::runBimloc("localize '" + dir + "' --plan '" + plan + "' --json --config '" + config + "'", 120);
    ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.err;
    const nlohmann::json report = nlohmann::json::parse(r.out);
    const nlohmann::json& run = report.at("scenarios").at(0);
    const Eigen::Vector3d truth = test::poseInRoom(frame, frames->front(), kShelfFromSouth_m);
    const Eigen::Vector3d twin(room.sizes().x() - truth.x(), room.sizes().y() - truth.y(), truth.z() + M_PI);
    int at_truth = 0, at_twin = 0;
    double best_off = INFINITY, best_twin_off = INFINITY;
    for (const auto& place : run.at("hypotheses")) {
      const Eigen::Vector2d xy(place.at("x").get<double>(), place.at("y").get<double>());
      const double yaw = place.at("yaw_deg").get<double>();
      const double off = (xy - truth.head<2>()).norm(), twin_off = (xy - twin.head<2>()).norm();
      if (yawDiffDeg(yaw, truth.z() * 180 / M_PI) < kPlace_deg) best_off = std::min(best_off, off);
      if (yawDiffDeg(yaw, twin.z() * 180 / M_PI) < kPlace_deg) best_twin_off = std::min(best_twin_off, twin_off);
      if (off < kReading_m && yawDiffDeg(yaw, truth.z() * 180 / M_PI) < kPlace_deg) ++at_truth;
      if (twin_off < kReading_m && yawDiffDeg(yaw, twin.z() * 180 / M_PI) < kPlace_deg) ++at_twin;
    }
    const std::string places = run.at("hypotheses").dump();
    std::cout << "[ real ] " << frame.sensor << ": walls give " << truth.x() << ", " << truth.y() << ", "
              << truth.z() * 180 / M_PI << " deg; nearest place " << best_off << " m, to the twin " << best_twin_off
              << " m; places " << places << "\n";
    EXPECT_FALSE(run.at("converged").get<bool>()) << "a rectangle cannot be told from its turned twin: " << places;
    EXPECT_GE(at_truth, 1) << "walls give " << truth.transpose() << "; places: " << places;
    EXPECT_GE(at_twin, 1) << "twin " << twin.transpose() << "; places: " << places;
    // The brief's bar: one of the two places within 0.1 m and 2 degrees of the walls' pose.
    // Measured 0.058 (VLP-16), 0.046 (40P), 0.042 (64), 0.081 (XT32), 0.029 (QT64) m; the turned
    // twin's 0.057, 0.047, 0.040, 0.147 and 0.029 m (held to kReading_m above).
    EXPECT_LT(best_off, kPlace_m) << places;
  }
}
