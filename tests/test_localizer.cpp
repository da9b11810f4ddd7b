// bimloc::Localizer, the one entry point of the bench and of robots, checked step by step on a
// simulated walk through the default world (real Embree scans, legged odometry): the state
// sequence, the hand-over from the filter to the S-Graph, its accuracy against the ground
// truth, determinism, a loss of track and the search that follows, and bad input.
#include "sim/scenario/scenario.hpp"
#include "sim/simulation/simulator.hpp"
#include "sim/world/world.hpp"
#include "localizer_walk.hpp"
#include "sim_fixtures.hpp"
#include "test_support.hpp"

#include <bimloc/geometry/planar_pose.hpp>
#include <bimloc/localizer.hpp>

#include <Eigen/Eigenvalues>

#include <gtest/gtest.h>

#include <fstream>

namespace {

using namespace bimloc;

using Walk = test::SimulatedWalk;
using Step = test::WalkStep;

// S100 to the corridor and on to R108: the filter converges within 20 s (test_run).
std::unique_ptr<Walk> walk(double duration_s) { return test::officeWalk(duration_s, "localizer"); }

// Every turn of the walk through a localizer; `blind(t)`: that turn's points are withheld.
std::vector<Step> run(const Walk& w, LocalizerMethod method, const std::function<bool(double)>& blind = {}) {
  LocalizerConfig config;
  config.method = method;
  config.seed = 1;
  return test::walkThrough(w, config, blind);
}

double error(const Step& s) { return test::positionError(s); }

}  // namespace

TEST(Localizer, SearchesThenConvergesOnceThenTheSGraphTracksWithinCentimetres) {
  const auto w = walk(40);
  const auto steps = run(*w, LocalizerMethod::SGraph);
  std::size_t converged_at = steps.size();
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const auto& r = steps[i].result;
    if (converged_at == steps.size()) {
      if (r.state == LocalizationState::Converged) {
        converged_at = i;
        ASSERT_TRUE(r.T_map_odom.has_value());
        ASSERT_TRUE(r.sgraph.has_value()) << "the tracker takes its first keyframe on the hand-over step";
      } else {
        ASSERT_EQ(r.state, LocalizationState::Searching) << "step " << i;
        EXPECT_FALSE(r.T_map_odom.has_value());
        EXPECT_FALSE(r.sgraph.has_value());
      }
      continue;
    }
    // After the hand-over: the S-Graph tracks, the filter rests, map <- odom stays published.
    ASSERT_EQ(r.state, LocalizationState::Tracking) << "step " << i;
    EXPECT_FALSE(r.filter.has_value());
    ASSERT_TRUE(r.T_map_odom.has_value());
    EXPECT_TRUE(r.T_map_base.isApprox(*r.T_map_odom * steps[i].odom, 1e-9)) << "map <- base = map <- odom * odom <- base";
    EXPECT_EQ(r.convergence_stamp_s, steps[converged_at].result.stamp_s);
    EXPECT_LT(error(steps[i]), 0.15) << "t=" << r.stamp_s;
    // The S-Graph's marginal covariance: a covariance, and not wildly off the error it describes.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(r.covariance);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
    EXPECT_LT(std::sqrt(r.covariance(0, 0)), 0.3);
  }
  ASSERT_LT(converged_at, steps.size()) << "never converged";
  double sum_sq = 0;
  for (std::size_t i = converged_at; i < steps.size(); ++i) sum_sq += error(steps[i]) * error(steps[i]);
  EXPECT_LT(std::sqrt(sum_sq / static_cast<double>(steps.size() - converged_at)), 0.06);
  EXPECT_EQ(steps.back().result.room_name.empty(), steps.back().result.room < 0);
}

TEST(Localizer, SameSeedSameBytesAndThePfMethodNeverStartsATracker) {
  const auto w = walk(25);
  const auto a = run(*w, LocalizerMethod::SGraph), b = run(*w, LocalizerMethod::SGraph);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].result.state, b[i].result.state);
    EXPECT_TRUE(a[i].result.T_map_base.matrix() == b[i].result.T_map_base.matrix()) << "step " << i;
  }
  const auto pf = run(*w, LocalizerMethod::Pf);
  bool tracked = false;
  for (std::size_t i = 0; i < pf.size(); ++i) {
    EXPECT_FALSE(pf[i].result.sgraph.has_value());
    EXPECT_NE(pf[i].result.state, LocalizationState::Lost);
    // The filter is the same until convergence, whichever stage tracks after it.
    if (a[i].result.state == LocalizationState::Searching) {
      EXPECT_TRUE(pf[i].result.T_map_base.matrix() == a[i].result.T_map_base.matrix());
    }
    tracked = tracked || pf[i].result.state == LocalizationState::Tracking;
  }
  EXPECT_TRUE(tracked);
}

TEST(Localizer, BlindForLongTheTrackerSaysLostThenTheSearchFindsThePlanAgain) {
  const auto w = walk(75);
  const auto seeing = run(*w, LocalizerMethod::SGraph);
  std::optional<double> converged;
  for (const auto& s : seeing)
    if (s.result.state == LocalizationState::Converged) converged = s.result.stamp_s;
  ASSERT_TRUE(converged);
  // Withhold every scan for 20 s after convergence: no wall is seen while the robot walks on.
  const double from = *converged + 2.0, to = from + 20.0;
  const auto steps = run(*w, LocalizerMethod::SGraph, [&](double t) { return t > from && t < to; });
  bool lost = false, back = false;
  for (const auto& s : steps) {
    const auto& r = s.result;
    if (r.stamp_s < from) {
      EXPECT_NE(r.state, LocalizationState::Lost);
    }
    if (r.state == LocalizationState::Lost) {
      lost = true;
      EXPECT_TRUE(r.T_map_odom.has_value()) << "dead reckoning goes on while lost";
    }
    if (lost && r.stamp_s > to && r.state != LocalizationState::Lost) back = true;
    if (back) {
      EXPECT_LT(error(s), 0.3) << "t=" << r.stamp_s;
    }
  }
  EXPECT_TRUE(lost);
  EXPECT_TRUE(back) << "never found the plan again";
  EXPECT_EQ(steps.back().result.losses, 1);
}

TEST(Localizer, BadInputIsWarnedAboutNeverACrash) {
  LocalizerConfig config;
  config.storey = "0";
  EXPECT_THROW(Localizer(test::officeWorld().building(), Eigen::Isometry3d::Identity(), [] {
                 LocalizerConfig c;
                 c.storey = "no such storey";
                 return c;
               }()),
               std::invalid_argument);
  Localizer localizer(test::officeWorld().building(), Eigen::Isometry3d::Identity(), config);
  Eigen::Isometry3d nan = Eigen::Isometry3d::Identity();
  nan.translation().x() = NAN;
  const std::vector<Eigen::Vector3f> garbage{{NAN, 0, 0}, {INFINITY, 1, 1}, {0, 0, 0}};
  for (int i = 0; i < 20; ++i) {
    const auto r = localizer.step(0.1 * i, i % 2 ? nan : test::pose(0.1 * i, 0, 0), garbage);
    EXPECT_EQ(r.state, LocalizationState::Searching);
    EXPECT_TRUE(r.T_map_base.matrix().allFinite());
  }
}
