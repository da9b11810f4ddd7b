// The places and goal while searching are advice, refreshed at GuideConfig::places_interval_s
// (1 s) rather than at every weighing. The oracle is the same walk with the interval 0 (every
// weighing, the former computation): the decision must be the same bits at every step, a
// refresh must list the places the former computation lists then, and between refreshes the
// places listed are the last refresh's, moved by the odometry.
#include "localizer_walk.hpp"

#include <bimloc/geometry/planar_pose.hpp>
#include <bimloc/localizer.hpp>

#include <gtest/gtest.h>

#include <limits>

namespace {

using namespace bimloc;

// The place listed at `refresh` (map pose then), seen from the odometry at `now`, as the
// Localizer keeps it: map <- odom at the refresh, then composed with the odometry now.
PlanarPose movedOn(const PlanarPose& place_then, const Eigen::Isometry3d& odom_then, const Eigen::Isometry3d& odom_now) {
  return compose(compose(place_then, inverse(planarPose(odom_then))), planarPose(odom_now));
}

TEST(PlacesInterval, TheDecisionIsTheSameAndAFreshListingIsTheFormerOne) {
  const auto walk = test::officeWalk(12.0, "places_interval");
  LocalizerConfig every, rated;
  every.guide.places_interval_s = 0.0;
  rated.guide.places_interval_s = 1.0;
  const auto a = test::walkThrough(*walk, every);
  const auto b = test::walkThrough(*walk, rated);
  ASSERT_EQ(a.size(), b.size());
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::size_t refresh = kNone;  // b's last refresh
  int refreshes = 0, weighings_searching = 0, listed_between = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const LocalizationResult &ra = a[i].result, &rb = b[i].result;
    // The decision: the same bits.
    ASSERT_EQ(ra.state, rb.state) << "step " << i;
    ASSERT_TRUE(ra.T_map_base.matrix() == rb.T_map_base.matrix()) << "step " << i;
    ASSERT_EQ(ra.convergence_stamp_s, rb.convergence_stamp_s);
    ASSERT_EQ(ra.filter.has_value(), rb.filter.has_value());
    if (ra.filter) {
      ASSERT_EQ(ra.filter->filter.path_margin, rb.filter->filter.path_margin) << "step " << i;
      ASSERT_EQ(ra.filter->filter.converged, rb.filter->filter.converged);
    }
    if (rb.state != LocalizationState::Searching || !rb.filter || !rb.filter->filter.weighed) continue;
    ++weighings_searching;
    const bool due = refresh == kNone || rb.stamp_s - b[refresh].result.stamp_s >= 1.0 - 1e-6;
    EXPECT_EQ(rb.filter->filter.places_fitted, due && rb.filter->filter.path_best.has_value()) << "t = " << rb.stamp_s;
    EXPECT_TRUE(ra.filter->filter.places_fitted || !ra.filter->filter.path_best);  // interval 0: every weighing
    if (due) {
      refresh = i, ++refreshes;
      // A refresh lists what the former computation lists at this step.
      ASSERT_EQ(ra.places.size(), rb.places.size()) << "t = " << rb.stamp_s;
      for (std::size_t k = 0; k < ra.places.size(); ++k) {
        EXPECT_TRUE(ra.places[k].T_map_base == rb.places[k].T_map_base);
        EXPECT_EQ(ra.places[k].margin, rb.places[k].margin);
      }
    }
  }
  // Between refreshes (every step, weighed or not, while searching): the refresh's places moved on.
  refresh = kNone;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const LocalizationResult& rb = b[i].result;
    if (rb.state != LocalizationState::Searching) continue;
    if (rb.filter && rb.filter->filter.places_fitted) refresh = i;
    if (refresh == kNone || refresh == i || rb.places.empty()) continue;
    const auto& then = a[refresh].result.places;  // the same as b's at the refresh (above)
    ASSERT_EQ(then.size(), rb.places.size()) << "t = " << rb.stamp_s;
    for (std::size_t k = 0; k < then.size(); ++k) {
      const PlanarPose expected = movedOn(then[k].T_map_base, a[refresh].odom, b[i].odom);
      EXPECT_NEAR((expected.head<2>() - rb.places[k].T_map_base.head<2>()).norm(), 0.0, 1e-9);
      EXPECT_NEAR(wrapAngle(expected.z() - rb.places[k].T_map_base.z()), 0.0, 1e-9);
    }
    ++listed_between;
  }
  // The walk searches long enough to refresh more than once, and weighs more often than it refreshes.
  EXPECT_GT(refreshes, 1);
  EXPECT_GT(weighings_searching, refreshes);
  EXPECT_GT(listed_between, 0);
}

}  // namespace
