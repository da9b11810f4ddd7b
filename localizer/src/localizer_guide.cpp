// Where to look next (guide/; issue 28, section 4): the places kept between weighings, and the
// goal suggested while two or more remain.
#include "localizer_impl.hpp"

namespace bimloc {

using detail::kDeg;

// The places of this step's weighing (if it refreshed them, places_interval_s): its best and the
// rivals within the evidence margin, kept as map <- odom so that later steps move them with the
// odometry.
void Localizer::Impl::keepPlaces(const Eigen::Isometry3d& T_odom_base, const LocalizationResult& r) {
  if (!places_due || !r.filter) return;
  const pf::UpdateReport& u = r.filter->filter;
  const PlanarPose odom_inv = inverse(planarPose(T_odom_base));
  places.clear();
  places_storey = r.filter->leader;
  if (!u.path_best) return;
  places.push_back({compose(*u.path_best, odom_inv), 0.0});
  for (const auto& [pose, margin] : u.path_rivals) places.push_back({compose(pose, odom_inv), margin});
}

bool Localizer::Impl::samePlaces(const std::vector<KeptPlace>& a, const std::vector<KeptPlace>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if ((a[i].T_map_odom.head<2>() - b[i].T_map_odom.head<2>()).norm() > 0.5 ||
        std::abs(wrapAngle(a[i].T_map_odom.z() - b[i].T_map_odom.z())) > 10.0 * kDeg)
      return false;
  return true;
}

// The places now and a goal: planned again when the places change, the goal is reached, or it
// is config.guide.replan_interval_s old; kept in the odom frame in between.
void Localizer::Impl::suggestGoal(const Eigen::Isometry3d& T_odom_base, LocalizationResult& r) {
  const PlanarPose odom = planarPose(T_odom_base);
  if (places.size() < 2) {
    goal.reset();
    return;
  }
  for (const auto& p : places) r.places.push_back({compose(p.T_map_odom, odom), p.margin});
  if (!config.guide.enabled) return;
  const bool reached = goal && (goal->T_odom_goal.head<2>() - odom.head<2>()).norm() < config.guide.goal_reached_m;
  // A goal is suggested only where the planner predicts it decides (min_information). Reached
  // with no place ruled out, that prediction failed for these places: no new goal until one is
  // ruled out, and the base goes its own way (the bench: its tour). Planning afresh each time
  // had the base dither between nearby goals that each promised to decide
  // (random_residential_98001 R007: 12 m walked in 48 s, the tour 22 m and a fix at 9 s).
  if (reached && places.size() >= goal_planned_count) spent_count = places.size();
  if (spent_count && places.size() < *spent_count) spent_count.reset();
  if (spent_count) {
    goal.reset();
    return;
  }
  if (!samePlaces(places, goal_places) || reached || r.stamp_s - goal_stamp_s >= config.guide.replan_interval_s) {
    if (!planner || planner_storey != places_storey) {
      planner = std::make_unique<guide::GoalPlanner>(building.storeys.at(places_storey), config.guide);
      planner_storey = places_storey;
    }
    // A goal under way is kept while it still tells the places apart and stays within reach in
    // each: the places change with nearly every weighing, and a new best goal each time had the
    // base turn back and forth between two goals, walking 2 m in 40 s (site_office R104).
    std::optional<double> still;
    if (goal && !reached) still = planner->informationOf(r.places, between(odom, goal->T_odom_goal));
    if (still && *still >= config.guide.min_information)
      goal->information = *still;
    else if ((goal = planner->suggest(r.places, odom)))
      goal_planned_count = places.size();
    goal_places = places;
    goal_stamp_s = r.stamp_s;
  }
  if (!goal) return;
  // The kept goal, seen from now: the motion from the base, and where it is in each place.
  r.goal = *goal;
  r.goal->motion = between(odom, goal->T_odom_goal);
  r.goal->distance_m = r.goal->motion.head<2>().norm();
  r.goal->T_map_goal.clear();
  for (const auto& p : places) r.goal->T_map_goal.push_back(compose(p.T_map_odom, goal->T_odom_goal));
}

}  // namespace bimloc
