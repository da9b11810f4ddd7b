// `bimloc eval`: APE and RPE as evo computes them, checked against values worked out by hand
// on small trajectories, and against the ATE that `bimloc run` reports for the same run.
#include "sim/dataset/tum_reader.hpp"
#include "sim/dataset/tum_writer.hpp"
#include "sim/metrics/trajectory_error.hpp"
#include "sim/metrics/trajectory_sync.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <png.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

using namespace bimloc::sim;
using bimloc::test::runBimloc;
using bimloc::test::tempDir;

namespace {

Eigen::Isometry3d pose(double x, double y, double z, double yaw) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  p.translation() = Eigen::Vector3d(x, y, z);
  return p;
}

// A non-planar loop (a helix turn), so that every rotation is determined by the positions.
TumTrajectory helix(int n, const std::string& name = "truth") {
  TumTrajectory t;
  t.path = name;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    t.stamps_s.push_back(100.0 + 0.1 * i);
    t.poses.push_back(pose(3 * std::cos(a), 2 * std::sin(a), 0.3 * i, a + M_PI / 2));
  }
  return t;
}

TumTrajectory transformed(const TumTrajectory& t, const Eigen::Isometry3d& T, double position_scale = 1.0) {
  TumTrajectory out = t;
  out.path = "estimate";
  for (auto& p : out.poses) {
    p = T * p;
    p.translation() *= position_scale;
  }
  return out;
}

std::string writeTum(const std::string& path, const TumTrajectory& t) {
  std::ofstream out(path);
  out << "# test trajectory\n";
  for (std::size_t i = 0; i < t.poses.size(); ++i)
    out << tumLine(static_cast<std::uint64_t>(std::llround(t.stamps_s[i] * 1e9)), t.poses[i]) << "\n";
  return path;
}

}  // namespace

TEST(EvalStatistics, AsEvoReportsThem) {
  const ErrorStatistics s = errorStatistics({4, 1, 3, 2});
  EXPECT_EQ(s.count, 4u);
  EXPECT_DOUBLE_EQ(s.sse, 30.0);                 // 16 + 1 + 9 + 4
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(30.0 / 4));
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);               // numpy: the mean of the middle two
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(1.25));      // numpy: population, (2.25 + 0.25) * 2 / 4
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.max, 4.0);
  EXPECT_DOUBLE_EQ(errorStatistics({3, 1, 2}).median, 2.0);
  EXPECT_THROW(errorStatistics({}), std::invalid_argument);
}

TEST(EvalApe, ConstantOffsetUnalignedAndRemovedBySe3) {
  const TumTrajectory truth = helix(20);
  const TumTrajectory estimate = transformed(truth, pose(0.3, -0.4, 0, 0));  // 0.5 m off everywhere
  TrajectoryEvalOptions o;
  TrajectoryEvaluation e = evaluateTrajectory(truth, estimate, o);
  EXPECT_EQ(e.ape.count, 20u);
  EXPECT_NEAR(e.ape.rmse, 0.5, 1e-12);
  EXPECT_NEAR(e.ape.mean, 0.5, 1e-12);
  EXPECT_NEAR(e.ape.median, 0.5, 1e-12);
  EXPECT_NEAR(e.ape.std, 0.0, 1e-12);
  EXPECT_NEAR(e.ape.sse, 20 * 0.25, 1e-12);
  // A translation of the whole path changes no relative pose: RPE 0, 19 consecutive pairs.
  ASSERT_TRUE(e.rpe);
  EXPECT_EQ(e.rpe->count, 19u);
  EXPECT_NEAR(e.rpe->max, 0.0, 1e-12);
  o.align = TrajectoryAlignment::SE3;
  e = evaluateTrajectory(truth, estimate, o);
  EXPECT_NEAR(e.ape.max, 0.0, 1e-9);
  EXPECT_NEAR((e.alignment.translation - Eigen::Vector3d(-0.3, 0.4, 0)).norm(), 0.0, 1e-9);
}

TEST(EvalApe, Se3AlignmentRecoversRotationAndTranslation) {
  const TumTrajectory truth = helix(30);
  Eigen::Isometry3d T = pose(5, -2, 1, 0.7);
  T.linear() = T.linear() * Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const TumTrajectory estimate = transformed(truth, T);
  TrajectoryEvalOptions o;
  o.align = TrajectoryAlignment::SE3;
  const TrajectoryEvaluation e = evaluateTrajectory(truth, estimate, o);
  EXPECT_NEAR(e.ape.max, 0.0, 1e-9);
  EXPECT_NEAR((e.alignment.rotation - T.inverse().linear()).norm(), 0.0, 1e-9);
  EXPECT_NEAR((e.alignment.translation - T.inverse().translation()).norm(), 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(e.alignment.scale, 1.0);
  // Unaligned, the error is each position moved by T: |T p - p|, computed directly.
  o.align = TrajectoryAlignment::None;
  const TrajectoryEvaluation raw = evaluateTrajectory(truth, estimate, o);
  double sse = 0;
  for (const auto& p : truth.poses) sse += ((T * p).translation() - p.translation()).squaredNorm();
  EXPECT_NEAR(raw.ape.sse, sse, 1e-9);
  EXPECT_NEAR(raw.ape.rmse, std::sqrt(sse / 30), 1e-12);
}

TEST(EvalApe, Se3ScaleRecoversTheScale) {
  const TumTrajectory truth = helix(25);
  const TumTrajectory estimate = transformed(truth, pose(1, 2, 0, -0.4), 0.5);  // half size, moved, turned
  TrajectoryEvalOptions o;
  o.align = TrajectoryAlignment::SE3Scale;
  const TrajectoryEvaluation e = evaluateTrajectory(truth, estimate, o);
  EXPECT_NEAR(e.alignment.scale, 2.0, 1e-9);
  EXPECT_NEAR(e.ape.max, 0.0, 1e-9);
  o.align = TrajectoryAlignment::SE3;  // without the scale, it cannot fit
  EXPECT_GT(evaluateTrajectory(truth, estimate, o).ape.rmse, 0.5);
}

TEST(EvalApe, DegenerateAlignmentIsAClearError) {
  TumTrajectory line;
  line.path = "line.tum";
  for (int i = 0; i < 5; ++i) line.stamps_s.push_back(i), line.poses.push_back(pose(i, 0, 0, 0));
  TrajectoryEvalOptions o;
  o.align = TrajectoryAlignment::SE3;
  try {
    evaluateTrajectory(line, line, o);
    FAIL() << "a straight line cannot be aligned";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("degenerate"), std::string::npos) << e.what();
  }
}

TEST(EvalRpe, DeltaInMetresAsEvoPicksThePairs) {
  // A straight walk in 0.5 m steps; the estimate walks 10% too far in x (0.55 m steps).
  TumTrajectory truth, estimate;
  truth.path = "truth", estimate.path = "estimate";
  for (int i = 0; i < 9; ++i) {
    truth.stamps_s.push_back(i), truth.poses.push_back(pose(0.5 * i, 0.01 * i * i, 0, 0));
    estimate.stamps_s.push_back(i), estimate.poses.push_back(pose(0.55 * i, 0.01 * i * i, 0, 0));
  }
  TrajectoryEvalOptions o;
  o.delta = 1.05;
  o.delta_metres = true;
  const TrajectoryEvaluation e = evaluateTrajectory(truth, estimate, o);
  // evo's filter_pairs_by_path on the estimate (its default): the path reaches 1.05 m at pose 2
  // (0.55 + 0.55 and a little in y), then again 2 poses later: pairs (2,4), (4,6), (6,8); the
  // first pair does not start at pose 0.
  ASSERT_EQ(e.rpe_pairs.size(), 3u);
  EXPECT_EQ(e.rpe_pairs[0], (std::pair<std::size_t, std::size_t>(2, 4)));
  EXPECT_EQ(e.rpe_pairs[2], (std::pair<std::size_t, std::size_t>(6, 8)));
  for (const double r : e.rpe_m) EXPECT_NEAR(r, 0.1, 1e-12);  // 1.1 m walked for 1.0 m in x
  // On the truth's path (evo --pairs_from_reference): 1.05 m first reached at pose 3 (1.5 m),
  // then at pose 6: one pair, 1.65 m walked for 1.5 m.
  o.pairs_from_truth = true;
  const TrajectoryEvaluation t = evaluateTrajectory(truth, estimate, o);
  ASSERT_EQ(t.rpe_pairs.size(), 1u);
  EXPECT_EQ(t.rpe_pairs[0], (std::pair<std::size_t, std::size_t>(3, 6)));
  EXPECT_NEAR(t.rpe_m[0], 0.15, 1e-12);
  o.delta = 3, o.delta_metres = false;  // frames: 0-3, 3-6 (8 is not reached a third time)
  const TrajectoryEvaluation f = evaluateTrajectory(truth, estimate, o);
  ASSERT_EQ(f.rpe_pairs.size(), 2u);
  for (const double r : f.rpe_m) EXPECT_NEAR(r, 0.15, 1e-12);
  o.delta = 50;  // no pair: the APE stands, the RPE is missing with a warning
  const TrajectoryEvaluation none = evaluateTrajectory(truth, estimate, o);
  EXPECT_FALSE(none.rpe);
  EXPECT_EQ(none.ape.count, 9u);
  ASSERT_EQ(none.warnings.size(), 1u);
  EXPECT_NE(none.warnings[0].find("no RPE: delta 50 frames"), std::string::npos) << none.warnings[0];
  o.delta = 0;
  EXPECT_THROW(evaluateTrajectory(truth, estimate, o), std::invalid_argument);
}

TEST(EvalSync, JitterAndMissingStampsAsEvoAssociates) {
  const std::vector<double> truth{0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9};
  // Jitter within 0.01 s, 0.3 and 0.7 missing, one stamp (0.45) far from any truth stamp.
  const std::vector<double> estimate{0.004, 0.097, 0.2, 0.409, 0.45, 0.5, 0.592, 0.8, 0.9031};
  const StampPairs p = associateStamps(truth, estimate, 0.01);
  // The estimate is shorter: each of its stamps takes the nearest truth stamp.
  EXPECT_EQ(p.first, (std::vector<std::size_t>{0, 1, 2, 4, 5, 6, 8, 9}));
  EXPECT_EQ(p.second, (std::vector<std::size_t>{0, 1, 2, 3, 5, 6, 7, 8}));
  // 0.0031 s beyond 0.01 of jitter: not associated with max_diff 0.003.
  EXPECT_EQ(associateStamps(truth, estimate, 0.003).first.size(), 3u);  // 0.2, 0.5, 0.8 exactly
  // The truth shorter: it is the one iterated; a stamp of the estimate may be taken twice.
  const StampPairs q = associateStamps({0.0, 0.05, 0.1}, {0.0, 0.02, 0.04, 0.5}, 0.07);
  EXPECT_EQ(q.first, (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(q.second, (std::vector<std::size_t>{0, 2, 2}));
  // A tie takes the earlier stamp (numpy's argmin).
  EXPECT_EQ(associateStamps({0.0, 0.5}, {0.25}, 0.3).first, (std::vector<std::size_t>{0}));
}

TEST(EvalTum, ReadsCommentsAndNormalisesWithAWarningAndNamesBadLines) {
  const std::string dir = tempDir("eval-tum");
  const std::string good = dir + "/good.tum";
  std::ofstream(good) << "# timestamp tx ty tz qx qy qz qw\n\n1.0 1 2 3 0 0 0 1\n  2.0 1 2 3 0 0 0 2\r\n";
  const TumTrajectory t = readTum(good);
  ASSERT_EQ(t.poses.size(), 2u);
  EXPECT_TRUE(t.poses[1].linear().isApprox(Eigen::Matrix3d::Identity()));
  ASSERT_EQ(t.warnings.size(), 1u);
  EXPECT_NE(t.warnings[0].find(good + ":4: 1 quaternion"), std::string::npos) << t.warnings[0];
  const auto error = [&](const std::string& text) {
    const std::string path = dir + "/bad.tum";
    std::ofstream(path) << text;
    try {
      readTum(path);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error("1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n").find("bad.tum:2: 7 values, expected 8"), std::string::npos);
  EXPECT_NE(error("1 0 0 0 0 0 0 1\n# x\n2 0 0 zero 0 0 0 1\n").find("bad.tum:3: 'zero' is not a number"), std::string::npos);
  EXPECT_NE(error("1 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n").find("bad.tum:2: timestamp"), std::string::npos);
  EXPECT_NE(error("1 0 0 0 0 0 0 0\n").find("bad.tum:1: the quaternion is zero"), std::string::npos);
  EXPECT_NE(error("1 0 0 nan 0 0 0 1\n").find("bad.tum:1: 'nan' is not a finite number"), std::string::npos);
  EXPECT_NE(error("# only a comment\n").find("no pose"), std::string::npos);
}

TEST(EvalCli, JsonTableAndPlot) {
  const std::string dir = tempDir("eval-cli");
  const TumTrajectory truth = helix(40);
  const std::string a = writeTum(dir + "/truth.tum", truth);
  const std::string b = writeTum(dir + "/estimate.tum", transformed(truth, pose(0.3, -0.4, 0, 0)));
  const auto r = runBimloc("eval '" + a + "' '" + b + "' --json --plot '" + dir + "/eval.png'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["poses"]["associated"], 40);
  EXPECT_NEAR(j["ape"]["statistics"]["rmse"].get<double>(), 0.5, 1e-6);  // TUM text: 9 digits
  EXPECT_EQ(j["rpe"]["statistics"]["count"], 39);
  // The plot: one PNG, the top view above the error plot.
  FILE* f = std::fopen((dir + "/eval.png").c_str(), "rb");
  ASSERT_NE(f, nullptr);
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_init_io(png, f);
  png_read_info(png, info);
  EXPECT_EQ(png_get_image_width(png, info), 1200u);
  EXPECT_EQ(png_get_image_height(png, info), 1600u);
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(f);
  const auto table = runBimloc("eval '" + a + "' '" + b + "' --align se3");
  EXPECT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("APE translation"), std::string::npos) << table.out;
  const auto bad = runBimloc("eval '" + a + "' '" + dir + "/missing.tum'");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("missing.tum: cannot open"), std::string::npos) << bad.err;
}

// `bimloc run --tum` writes the run's truth and estimate; eval with no alignment, projected on
// the plane as the run's ATE is measured (x, y), gives the ATE the run reports.
TEST(EvalCli, AgreesWithTheAteOfBimlocRun) {
  const std::string dir = tempDir("eval-run");
  const auto run = runBimloc(std::string("run --plan '") + BIMLOC_WORLDS_DIR +
                             "/site_office.ifc' --all-rooms --rooms S100,W100 --duration 12 --json --tum '" + dir + "'");
  ASSERT_FALSE(run.out.empty()) << run.err;
  const auto report = nlohmann::json::parse(run.out);
  int compared = 0;
  for (const auto& s : report["scenarios"]) {
    if (s["ate_m"].is_null()) continue;
    const std::string folder = dir + "/" + s["name"].get<std::string>();
    std::string safe = folder;
    for (auto& c : safe) c = c == ' ' ? '_' : c;
    const std::string d = std::filesystem::exists(folder) ? folder : safe;
    const auto e = runBimloc("eval '" + d + "/truth.tum' '" + d + "/estimate.tum' --align none --project xy --json");
    ASSERT_EQ(e.exit_code, 0) << e.err;
    const auto j = nlohmann::json::parse(e.out);
    EXPECT_NEAR(j["ape"]["statistics"]["rmse"].get<double>(), s["ate_m"].get<double>(), 1e-6) << s["name"];
    ++compared;
  }
  EXPECT_GE(compared, 1) << run.out;
}
