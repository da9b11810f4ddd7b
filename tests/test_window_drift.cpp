// The path evidence's error model follows the path its window covers (evidence_drift_of_window):
// its sigmas against the analytic drift of that path, and the one-deviation safety the bar keeps
// however small the sigmas get.
#include "sim_fixtures.hpp"

#include "sim/world/world.hpp"

#include "pf/path_evidence.hpp"

#include <bimloc/pf/particle_filter.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace bimloc;

namespace {

// The window's sigma of d over `path_m` of path: the scan's own, the drift over half the path
// (reference.md: legged odometry drifts up to 2 % of the distance), the plan's tolerance.
double sigmaD(const pf::ParticleFilterConfig& c, double path_m) {
  const double drift = c.evidence_drift_fraction * 0.5 * path_m;
  return std::sqrt(c.sigma_d_m * c.sigma_d_m + drift * drift + c.evidence_plan_tolerance_m * c.evidence_plan_tolerance_m);
}

}  // namespace

TEST(WindowDrift, TheModelsDriftIsThatOfThePathTheWindowCoversRoundedUpToAHalving) {
  const auto& storey = test::officeWorld().building().storeys[0];
  for (const bool of_window : {false, true}) {
    pf::ParticleFilterConfig config;
    config.evidence_drift_of_window = of_window;
    pf::detail::PathEvidence evidence(storey, config);
    const double window = config.evidence_window_m;
    EXPECT_DOUBLE_EQ(evidence.scanModel().sigma_d_m, sigmaD(config, of_window ? window / 16 : window));
    // A straight walk, a scan every 0.31 m (just over the window's spacing, 0.3 m, so that
    // rounding never keeps a scan out), 20.8 m: past the window's length.
    for (int k = 1; k <= 67; ++k) {
      const double walked = 0.31 * k;
      ASSERT_TRUE(evidence.addScan({walked, 0.0, 0.0}, 0.0, {}));
      // The path the model is for: the window's, or the smallest halving of it (at most four)
      // that covers the path from the window's first scan (at 0.31 m) to this one.
      const double covered = std::min(window, walked - 0.31);
      double path = window;
      if (of_window)
        for (int halvings = 0; halvings < 4 && path / 2 >= covered; ++halvings) path /= 2;
      EXPECT_NEAR(evidence.scanModel().sigma_d_m, sigmaD(config, path), 1e-12) << "walked " << walked << " m";
      EXPECT_GE(evidence.scanModel().sigma_d_m, sigmaD(config, covered) - 1e-12);  // never under the path's own drift
    }
    EXPECT_NEAR(evidence.scanModel().sigma_d_m, sigmaD(config, window), 1e-12);  // past the window: the old model
  }
}

TEST(WindowDrift, OneFaceTheRivalCannotExplainNeverReachesTheBarHoweverOftenSeen) {
  // Smaller sigmas make each look say more, but a look says at most that the rival leaves the
  // plane unexplained (clutter at the gate, m2 = gate): one face is worth at most gate / 2,
  // under the bar of two faces, however many looks and whatever their m2 (one deviation of the
  // site, a wall built where the rival has one, can fake one face, never a verdict). Two faces
  // the rival cannot explain, seen once each, reach it.
  const pf::ParticleFilterConfig config;
  const double gate = config.gate_mahalanobis2;
  std::mt19937 rng(28);
  std::uniform_real_distribution<double> m2(0.0, gate);
  for (int looks = 1; looks <= 60; looks += 7) {
    pf::detail::FaceMargin one;
    for (int k = 0; k < looks; ++k) {
      one.addScan(false, false);
      pf::detail::ObservationMatch at_p{7, static_cast<float>(m2(rng))}, at_q{-1, static_cast<float>(gate)};
      one.add(at_p, at_q);
    }
    const double margin = one.total(gate, looks);
    EXPECT_LE(margin, 0.5 * gate + 1e-9) << looks << " looks";
    EXPECT_LT(margin, config.evidenceMargin()) << looks << " looks";
  }
  pf::detail::FaceMargin two;
  two.addScan(false, false);
  two.add({3, 0.0f}, {-1, static_cast<float>(gate)});
  two.add({5, 0.0f}, {-1, static_cast<float>(gate)});
  EXPECT_GE(two.total(gate, 1), config.evidenceMargin());
}
