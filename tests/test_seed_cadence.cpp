// The seeds (the global search over every room) run only at the weighings whose scan joins the
// path evidence's window, and at the first (ParticleFilterConfig::seeds_on_window_scans). The
// truth is the window's rule recomputed from the odometry the walk gave: a scan joins after
// evidence_spacing_m of motion or evidence_spacing_deg of turning since the last that joined.
#include "localizer_walk.hpp"

#include <bimloc/geometry/planar_pose.hpp>
#include <bimloc/localizer.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

namespace {

using namespace bimloc;

struct Cadence {
  int weighings = 0, joining = 0, seeded = 0, seeded_between = 0;
};

// Counts the weighings, those whose scan joins the window (by the rule above), those that
// seeded (poses computed from the scan), and those that seeded without joining.
Cadence cadenceOf(const std::vector<test::WalkStep>& steps, const pf::ParticleFilterConfig& c) {
  Cadence k;
  std::optional<PlanarPose> last_joined;
  for (const auto& s : steps) {
    if (!s.result.filter || !s.result.filter->filter.weighed) continue;
    const PlanarPose odom = planarPose(s.odom);
    const bool joins = !last_joined || std::hypot(odom.x() - last_joined->x(), odom.y() - last_joined->y()) >= c.evidence_spacing_m ||
                       std::abs(wrapAngle(odom.z() - last_joined->z())) >= c.evidence_spacing_deg * M_PI / 180.0;
    if (joins) last_joined = odom, ++k.joining;
    const bool seeded = s.result.filter->filter.hypotheses > 0;
    k.seeded += seeded ? 1 : 0;
    k.seeded_between += seeded && !joins ? 1 : 0;
    ++k.weighings;
  }
  return k;
}

TEST(SeedCadence, TheSeedsRunOnlyOnTheScansThatJoinThePathsWindow) {
  const auto walk = test::officeWalk(12.0, "seed_cadence");
  LocalizerConfig every, window;
  every.pf.seeds_on_window_scans = false;
  window.pf.seeds_on_window_scans = true;
  const auto a = test::walkThrough(*walk, every);
  const auto b = test::walkThrough(*walk, window);
  const Cadence ka = cadenceOf(a, every.pf), kb = cadenceOf(b, window.pf);
  // With the rule, no scan between two of the window's seeds; the first weighing (which joins)
  // seeds. Without it, scans between them do: the walk exercises the rule.
  EXPECT_EQ(kb.seeded_between, 0);
  EXPECT_GT(kb.seeded, 0);
  EXPECT_GT(kb.weighings, kb.joining);
  EXPECT_GT(ka.seeded_between, 0);
  // Both localize, at the truth (never falsely: within the false-convergence bounds).
  for (const auto* run : {&a, &b}) {
    ASSERT_TRUE(run->back().result.convergence_stamp_s.has_value());
    EXPECT_LT(test::positionError(run->back()), 0.5);
  }
}

}  // namespace
