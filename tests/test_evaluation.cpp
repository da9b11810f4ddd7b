// The scorer (sim/runner/evaluation.hpp) against analytic truths: synthetic localizer results
// along a straight walk, with an estimate whose error is known in closed form.
#include "sim/runner/evaluation.hpp"
#include "sim_fixtures.hpp"
#include "sim/world/world.hpp"

#include <gtest/gtest.h>

#include <algorithm>

using namespace bimloc;

namespace {

LocalizationResult tracking(const Eigen::Isometry3d& estimate) {
  LocalizationResult r;
  r.state = LocalizationState::Tracking;
  r.storey = 0;
  r.T_map_base = estimate;
  return r;
}

}  // namespace

TEST(Evaluation, RpeOfAScaleErrorIsTheScaleAndAnOffsetHasNone) {
  // Walking along x at 0.1 m per step: an estimate stretched by 2 % drifts 0.02 m per metre
  // (RPE 0.02 m/m); one shifted by a constant 0.3 m has ATE 0.3 m and no relative error.
  const auto& building = test::officeWorld().building();
  sim::RunScore scaled(building, 0), shifted(building, 0);
  for (int k = 0; k <= 100; ++k) {
    const double x = 0.1 * k;
    const Eigen::Isometry3d truth = test::pose(1.0 + x, 6.1, 0.0);
    EXPECT_EQ(scaled.add(0.1 * k, tracking(test::pose(1.0 + 1.02 * x, 6.1, 0.0)), truth), k == 0);
    shifted.add(0.1 * k, tracking(test::pose(1.0 + x, 6.4, 0.0)), truth);
  }
  sim::ScenarioResult a, b;
  scaled.finish(a);
  shifted.finish(b);
  ASSERT_TRUE(a.rpe_m_per_m && b.rpe_m_per_m);
  EXPECT_NEAR(*a.rpe_m_per_m, 0.02, 1e-9);
  EXPECT_NEAR(*b.rpe_m_per_m, 0.0, 1e-9);
  EXPECT_NEAR(*b.ate_m, 0.3, 1e-9);
  EXPECT_FALSE(b.false_convergence);  // 0.3 m is within the 0.5 m bound
}

TEST(Evaluation, LostStepsAreNotScoredAndSearchingIsNotConverged) {
  // A localizer that says it is lost is not wrong with confidence: a pose 2 m off while lost
  // is neither a false convergence nor part of the ATE; a search never converges.
  const auto& building = test::officeWorld().building();
  sim::RunScore score(building, 0);
  LocalizationResult searching = tracking(test::pose(9, 9, 0));
  searching.state = LocalizationState::Searching;
  EXPECT_FALSE(score.add(0.0, searching, test::pose(1, 6, 0)));
  EXPECT_FALSE(score.converged());
  EXPECT_TRUE(score.add(0.1, tracking(test::pose(1.1, 6, 0)), test::pose(1, 6, 0)));
  LocalizationResult lost = tracking(test::pose(3, 6, 0));
  lost.state = LocalizationState::Lost;
  lost.losses = 1;
  score.add(0.2, lost, test::pose(1, 6, 0));
  sim::ScenarioResult r;
  score.finish(r);
  EXPECT_TRUE(r.converged);
  EXPECT_FALSE(r.false_convergence);
  EXPECT_NEAR(*r.ate_m, 0.1, 1e-9);
  EXPECT_EQ(r.losses, 1);
  EXPECT_FALSE(r.rpe_m_per_m.has_value()) << "less than 1 m walked";
}

TEST(Evaluation, TheTrueStoreyFollowsTheBaseUpTheStairsAndTheLocalizerHasFiveSeconds) {
  // Two storeys 3 m apart (a plan's storeys copied, the second raised): the base climbs from
  // t = 1 s to 4 s. A localizer on the new storey 2 s after it stepped off follows the change;
  // one that stays on the old storey past 5 s is on the wrong storey: a false convergence.
  bim::Building building = test::officeWorld().building();
  building.storeys.resize(1);
  building.storeys.push_back(building.storeys[0]);
  building.storeys[1].elevation_m = building.storeys[0].elevation_m + 3.0;
  const auto truthAt = [](double t) {
    const double z = 0.5 + std::clamp(t - 1.0, 0.0, 3.0);  // 1 m a second up the flight
    return test::pose(2.0 + 0.1 * t, 6.0, 0.0, z);
  };
  const auto walk = [&](double switch_s) {
    sim::RunScore score(building, 0);
    for (int k = 0; k <= 150; ++k) {
      const double t = 0.1 * k;
      LocalizationResult r = tracking(truthAt(t));
      r.storey = t >= switch_s ? 1 : 0;
      score.add(t, r, truthAt(t));
    }
    sim::ScenarioResult out;
    score.finish(out);
    EXPECT_EQ(score.trueStorey(), 1u);
    return out;
  };
  const sim::ScenarioResult followed = walk(6.0), missed = walk(10.0);
  EXPECT_EQ(followed.storey_changes, 1);
  EXPECT_EQ(followed.storey_changes_followed, 1);
  // On the new floor (within 0.3 m of it) from t = 3.7-3.8 s, on the new storey from 6.0 s.
  ASSERT_EQ(followed.storey_follow_lags_s.size(), 1u);
  EXPECT_NEAR(followed.storey_follow_lags_s[0], 2.25, 0.06);
  EXPECT_FALSE(followed.false_convergence) << "the old storey on the stairs and for 2 s after is no error";
  EXPECT_EQ(missed.storey_changes, 1);
  EXPECT_EQ(missed.storey_changes_followed, 0);
  EXPECT_TRUE(missed.storey_follow_lags_s.empty());
  EXPECT_TRUE(missed.false_convergence);
  EXPECT_EQ(sim::RunScore::floorStorey(building, 0, 0.5, 2.0), std::nullopt) << "half way up: on no floor";
}

TEST(Evaluation, TheFollowLagRunsFromTheBaseLeavingTheFlightWhenTheSimulatorSaysSo) {
  // The same climb (1 m a second, on the new floor's height from t = 4 s), the simulator saying
  // the base is on the flight until t = 5 s (it walks its last tread and steps off): the clock
  // starts at 5 s, not at 3.7-3.8 s (within 0.3 m of the floor). The window runs from there too:
  // on the new storey at 9.5 s is followed (4.5 s), at 10.5 s is not.
  bim::Building building = test::officeWorld().building();
  building.storeys.resize(1);
  building.storeys.push_back(building.storeys[0]);
  building.storeys[1].elevation_m = building.storeys[0].elevation_m + 3.0;
  const auto truthAt = [](double t) { return test::pose(2.0 + 0.1 * t, 6.0, 0.0, 0.5 + std::clamp(t - 1.0, 0.0, 3.0)); };
  const auto walk = [&](double switch_s, int steps = 150) {
    sim::RunScore score(building, 0);
    for (int k = 0; k <= steps; ++k) {
      const double t = 0.1 * k;
      LocalizationResult r = tracking(truthAt(t));
      r.storey = t >= switch_s - 1e-9 ? 1 : 0;
      score.add(t, r, truthAt(t), /*on_flight=*/t > 1.0 - 1e-9 && t < 5.0 - 1e-9);
    }
    sim::ScenarioResult out;
    score.finish(out);
    return out;
  };
  const sim::ScenarioResult soon = walk(6.0), late = walk(9.5), missed = walk(10.5), early = walk(4.5);
  ASSERT_EQ(soon.storey_follow_lags_s.size(), 1u);
  EXPECT_NEAR(soon.storey_follow_lags_s[0], 1.0, 1e-6);
  EXPECT_FALSE(soon.false_convergence);
  ASSERT_EQ(late.storey_follow_lags_s.size(), 1u);
  EXPECT_NEAR(late.storey_follow_lags_s[0], 4.5, 1e-6);
  EXPECT_FALSE(late.false_convergence) << "the old storey within 5 s of stepping off is no error";
  EXPECT_EQ(missed.storey_changes_followed, 0);
  EXPECT_TRUE(missed.false_convergence);
  ASSERT_EQ(early.storey_follow_lags_s.size(), 1u) << "on the new storey before stepping off: followed";
  EXPECT_EQ(early.storey_follow_lags_s[0], 0.0);
  // The run ends 2 s after the base stepped off, the localizer still on the old storey: the
  // change is not judged (no change, none followed, no false convergence).
  const sim::ScenarioResult cut = walk(100.0, 70);
  EXPECT_EQ(cut.storey_changes, 0);
  EXPECT_EQ(cut.storey_changes_followed, 0);
  EXPECT_FALSE(cut.false_convergence);
}

TEST(Evaluation, AChangeMadeWhileTheLocalizerStillSearchesIsCountedApart) {
  // The same climb (on the flight from 1 s to 5 s), the localizer searching until t = 8 s and
  // then converged on the new storey: it tracked no storey when the base changed, so the change
  // is no change followed or missed, it is counted apart; a second climb back down after
  // convergence is a change to follow. One that converges first and then misses is still judged.
  bim::Building building = test::officeWorld().building();
  building.storeys.resize(1);
  building.storeys.push_back(building.storeys[0]);
  building.storeys[1].elevation_m = building.storeys[0].elevation_m + 3.0;
  const auto zAt = [](double t) { return 0.5 + std::clamp(t - 1.0, 0.0, 3.0) - std::clamp(t - 11.0, 0.0, 3.0); };
  const auto truthAt = [&](double t) { return test::pose(2.0 + 0.1 * t, 6.0, 0.0, zAt(t)); };
  const auto onFlight = [](double t) { return (t > 1.0 - 1e-9 && t < 5.0 - 1e-9) || (t > 11.0 - 1e-9 && t < 15.0 - 1e-9); };
  sim::RunScore score(building, 0);
  for (int k = 0; k <= 250; ++k) {
    const double t = 0.1 * k;
    LocalizationResult r = tracking(truthAt(t));
    if (t < 8.0 - 1e-9) r.state = LocalizationState::Searching, r.storey = std::nullopt;
    else r.storey = t < 16.0 - 1e-9 ? 1 : 0;
    score.add(t, r, truthAt(t), onFlight(t));
  }
  sim::ScenarioResult out;
  score.finish(out);
  EXPECT_EQ(out.storey_changes_searching, 1);
  EXPECT_EQ(out.storey_changes, 1) << "the climb down, after convergence";
  EXPECT_EQ(out.storey_changes_followed, 1);
  ASSERT_EQ(out.storey_follow_lags_s.size(), 1u);
  EXPECT_NEAR(out.storey_follow_lags_s[0], 1.0, 1e-6);
  EXPECT_FALSE(out.false_convergence);
}
