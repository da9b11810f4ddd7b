#include "sim/base/base_trajectory.hpp"
#include "sim/common/angles.hpp"

#include "sim/base/free_space.hpp"
#include "sim/base/gait.hpp"
#include "sim/base/motion_profile.hpp"
#include "sim/base/room_lookup.hpp"
#include "sim/base/script_builder.hpp"
#include "sim/common/seeded_random.hpp"
#include "sim/world/world.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>

namespace bimloc::sim {
namespace {

// Random walk: targets at least this far apart (or a third of the room's smaller side), so
// the walk covers the room rather than shuffling; a bound on legs and draws keeps it finite.
constexpr double kWalkMinStep_m = 1.0;
constexpr int kWalkMaxLegs = 2000;
constexpr int kWalkDraws = 200;
// Goals in a room: the centre, or the nearest spot within this distance where the body fits.
constexpr double kSpotSearch_m = 3.0;


std::string metres(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f m", v);
  return text;
}

std::string xyz(const Eigen::Vector3d& p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.2f, %.2f, %.2f)", p.x(), p.y(), p.z());
  return text;
}

const bim::Room& roomOrThrow(const bim::Storey& storey, const std::string& name) {
  std::string problem;
  const bim::Room* room = lookUpRoom(storey, name, &problem);
  if (!room) throw MotionError(problem, MotionError::Where::Script);
  return *room;
}

Eigen::Vector2d roomGoal(const FreeSpace& space, const bim::Room& room) {
  const auto spot = space.freeSpotNear(room.centre, &room.footprint, kSpotSearch_m);
  if (!spot)
    throw MotionError("no spot near the centre of room " + room.name + " where a body of radius " + metres(space.radius()) +
                          " fits",
                      MotionError::Where::Script);
  return *spot;
}

void randomWalk(ScriptBuilder& script, const bim::Storey& storey, const MotionConfig& motion, const Pose2& start,
                double duration_s, std::uint64_t seed) {
  const bim::Room* room = motion.walk_room.empty() ? roomAt(storey, {start.x, start.y})
                                                   : &roomOrThrow(storey, motion.walk_room);
  if (!room)
    throw MotionError("random walk: the start " + pointText({start.x, start.y}) + " is in no room of storey '" + storey.name +
                          "'; name the room (motion.room)",
                      MotionError::Where::Script);
  Eigen::Vector2d lo = room->footprint.front(), hi = lo;
  for (const auto& q : room->footprint) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const double min_step = std::min(kWalkMinStep_m, (hi - lo).minCoeff() / 3.0);
  SeededRandom random(seed, RandomStream::Walk);
  for (int legs = 0; legs < kWalkMaxLegs && script.timeline().end_s() < duration_s; ++legs) {
    std::vector<Eigen::Vector2d> leg;
    for (int draw = 0; draw < kWalkDraws && leg.empty(); ++draw) {
      const Eigen::Vector2d q(random.uniform(lo.x(), hi.x()), random.uniform(lo.y(), hi.y()));
      if (!bim::pointInPolygon(room->footprint, q) || (q - script.timeline().position()).norm() < min_step ||
          !script.space().spotFree(q, FreeSpace::kMargin_m))
        continue;
      leg = script.space().path(script.timeline().position(), q);
    }
    if (!leg.empty()) leg.erase(leg.begin());  // where the base already is
    if (leg.empty()) {
      if (legs == 0)
        throw MotionError("random walk: no spot in room " + room->name + " where the body fits is reachable from " +
                              pointText(script.timeline().position()),
                          MotionError::Where::Script);
      break;
    }
    script.addLeg(leg);
  }
}

// After a tour: on to the nearest room not yet visited that the base can reach, until the
// duration is used; every reachable room visited, a new round from where it stands (a robot
// on a long walk keeps walking its rooms: in a small house a random walk in the last room
// turned on the spot for minutes, and 5-minute walks covered 67-95 m); a round that reached
// no room, a random walk where it stands (if that is a room).
// From where the base is, through the doors, to a free spot near the room's centre.
// The spot nearest the centre may be walled in by furniture: then the reachable spot of the
// room nearest it (FreeSpace::pathInto).
void legToRoom(ScriptBuilder& script, const bim::Room& room) {
  const Eigen::Vector2d from = script.timeline().position(), goal = roomGoal(script.space(), room);
  std::vector<Eigen::Vector2d> leg = script.space().pathInto(from, goal, room.footprint);
  if (leg.empty())
    throw MotionError("no path from " + pointText(from) + " into room " + room.name + " for a body of radius " +
                          metres(script.space().radius()),
                      MotionError::Where::Script);
  leg.erase(leg.begin());  // `from`: where the base already is
  script.addLeg(leg);
}

void explore(ScriptBuilder& script, const bim::Storey& storey, const MotionConfig& motion,
             std::vector<const bim::Room*> visited, double duration_s, std::uint64_t seed) {
  const auto seen = [&visited](const bim::Room& r) { return std::find(visited.begin(), visited.end(), &r) != visited.end(); };
  bool reached_one = script.corners().size() > 1;  // in this round (the tour's legs count)
  double round_start_s = -1.0;
  while (script.timeline().end_s() < duration_s) {
    const Eigen::Vector2d here = script.timeline().position();
    std::vector<std::pair<double, const bim::Room*>> next;
    for (const auto& room : storey.rooms)
      if (!seen(room)) next.emplace_back((room.centre - here).norm(), &room);
    std::stable_sort(next.begin(), next.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    bool moved = false;
    for (const auto& [distance, room] : next) {
      visited.push_back(room);
      try {
        legToRoom(script, *room);
        moved = true;
        break;
      } catch (const MotionError&) {
        // out of reach (another flat, a closed door): the next nearest
      }
    }
    if (moved) {
      reached_one = true;
      continue;
    }
    if (reached_one && script.timeline().end_s() > round_start_s) {
      // every room it can reach visited: round again, the room it stands in done
      round_start_s = script.timeline().end_s();
      visited.assign(1, roomAt(storey, here));
      reached_one = false;
      continue;
    }
    if (!roomAt(storey, here)) return;  // nowhere to wander: it stands
    const Pose2 now{here.x(), here.y(), script.timeline().yaw()};
    MotionConfig wander = motion;
    wander.walk_room.clear();
    try {
      randomWalk(script, storey, wander, now, duration_s, seed);
    } catch (const MotionError&) {
    }
    return;
  }
}

std::size_t storeyOrThrow(const World& world, const std::string& name) {
  try {
    return world.storeyIndex(name);
  } catch (const std::invalid_argument& e) {
    throw MotionError(std::string("motion.storeys: ") + e.what(), MotionError::Where::Script);
  }
}

// Every storey the stairs reach from where the base stands, nearest by stairs first: an equal
// share of the time left exploring each (its rooms through the doors), then over the stairs to
// the next; the last one explored until the end. A storey whose flight cannot be reached is left out.
void tourStoreys(ScriptBuilder& script, const MotionConfig& motion, std::vector<const bim::Room*> visited,
                 double duration_s, std::uint64_t seed) {
  const std::vector<std::size_t> order = reachableStoreys(script.links(), script.storey());
  const double t0 = script.timeline().end_s();
  const double share = (duration_s - t0) / static_cast<double>(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k > 0) {
      try {
        script.goToStorey(order[k]);
      } catch (const MotionError&) {
        continue;  // its flight walled in on this storey: the next storey
      }
      visited.assign(1, roomAt(script.storeyPlan(), script.timeline().position()));
    }
    const double until = k + 1 == order.size() ? duration_s : t0 + share * static_cast<double>(k + 1);
    if (script.timeline().end_s() < until) explore(script, script.storeyPlan(), motion, visited, until, seed + k);
    if (script.timeline().end_s() >= duration_s) break;
  }
}

}  // namespace

struct BaseTrajectory::Impl {
  Timeline timeline;
  std::vector<Pose2> corners;
  double duration_s = 0.0;
  double max_speed_mps = 0.0, max_turn_rate_rps = 0.0;
  GaitConfig gait;
  double gait_phase_rad = 0.0;
  std::vector<std::size_t> storeys;  // visited, in order
};

BaseTrajectory BaseTrajectory::plan(const World& world, std::size_t storey, const Pose2& start,
                                    const MotionConfig& motion, double duration_s, std::uint64_t seed) {
  if (storey >= world.storeyCount())
    throw std::invalid_argument("storey index " + std::to_string(storey) + " out of range (the world has " +
                                std::to_string(world.storeyCount()) + ")");
  if (!(duration_s > 0.0) || !(motion.max_speed_mps > 0.0) || !(motion.max_accel_mps2 > 0.0) ||
      !(motion.max_turn_rate_dps > 0.0) || !(motion.max_turn_accel_dps2 > 0.0) || !(motion.body_radius_m > 0.0))
    throw std::invalid_argument("the duration, speed, acceleration, turn-rate limits and body radius must be positive");
  const bim::Storey& st = world.building().storeys.at(storey);
  const double height = motion.gait.body_height_m;
  const Eigen::Vector2d origin(start.x, start.y);

  // The body is a sphere at body height above the floor where it starts (storeys are flat).
  const double floor0 = bodyCentreZ(world, storey, origin, height) - height;
  MotionLimits limits;
  limits.max_speed_mps = motion.max_speed_mps;
  limits.max_accel_mps2 = motion.max_accel_mps2;
  limits.max_turn_rate_rps = motion.max_turn_rate_dps * kDegToRad;
  limits.max_turn_accel_rps2 = motion.max_turn_accel_dps2 * kDegToRad;
  ScriptBuilder script(world, storey, floor0, start, motion, limits);
  Eigen::Vector3d contact = Eigen::Vector3d::Zero();
  if (!script.space().spotFree(origin, 0.0, &contact))
    throw MotionError("the start " + pointText(origin) + " leaves no room for a body of radius " + metres(motion.body_radius_m) +
                          ": it touches the building at " + xyz(contact),
                      MotionError::Where::Start);
  if (!motion.storeys.empty() && motion.storeys.size() != motion.rooms.size())
    throw MotionError("motion.storeys names " + std::to_string(motion.storeys.size()) + " storeys for " +
                          std::to_string(motion.rooms.size()) + " rooms: one storey per room",
                      MotionError::Where::Script);

  switch (motion.kind) {
    case MotionConfig::Kind::Stand:
      break;
    case MotionConfig::Kind::Waypoints:
      for (const auto& w : motion.waypoints) script.addLeg({w.xy}, w.yaw_rad);
      break;
    case MotionConfig::Kind::Tour:
    {
      bool moved = false;
      std::vector<const bim::Room*> visited{roomAt(st, origin)};
      for (std::size_t i = 0; i < motion.rooms.size(); ++i) {
        // Past the run's end, a leg is never walked: planning it (Bullet sweeps across the
        // floor) was a third of some runs on large floors.
        if (moved && script.timeline().end_s() >= duration_s) break;
        const std::size_t on = motion.storeys.empty() ? script.storey() : storeyOrThrow(world, motion.storeys[i]);
        const bim::Room& room = roomOrThrow(world.building().storeys[on], motion.rooms[i]);
        visited.push_back(&room);
        try {
          script.goToStorey(on);  // over the stairs when the room is on another storey
          legToRoom(script, room);
          moved = true;
        } catch (const MotionError&) {
          if (!motion.skip_unreachable_rooms) throw;
        }
      }
      if (motion.all_storeys) {
        tourStoreys(script, motion, std::move(visited), duration_s, seed);
        break;
      }
      // No listed room reachable (the tour's rooms in another flat): exploring still takes the
      // base out of its start room to the rooms it can reach, as it does after a tour.
      if (motion.explore_after_tour) explore(script, script.storeyPlan(), motion, std::move(visited), duration_s, seed);
      else if (!moved && motion.skip_unreachable_rooms) randomWalk(script, st, motion, start, duration_s, seed);
      break;
    }
    case MotionConfig::Kind::RandomWalk:
      randomWalk(script, st, motion, start, duration_s, seed);
      break;
  }

  auto impl = std::make_unique<Impl>();
  impl->timeline = std::move(script.timeline());
  impl->timeline.seal();
  impl->corners = std::move(script.corners());
  impl->storeys = script.storeysVisited();
  impl->duration_s = duration_s;
  impl->max_speed_mps = limits.max_speed_mps;
  impl->max_turn_rate_rps = limits.max_turn_rate_rps;
  impl->gait = motion.gait;
  impl->gait_phase_rad = 2.0 * M_PI * SeededRandom(seed, RandomStream::Gait).uniform();
  return BaseTrajectory(std::move(impl));
}

BaseTrajectory::BaseTrajectory(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
BaseTrajectory::BaseTrajectory(BaseTrajectory&&) noexcept = default;
BaseTrajectory& BaseTrajectory::operator=(BaseTrajectory&&) noexcept = default;
BaseTrajectory::~BaseTrajectory() = default;

double BaseTrajectory::duration_s() const { return impl_->duration_s; }
double BaseTrajectory::script_duration_s() const { return impl_->timeline.end_s(); }
const std::vector<Pose2>& BaseTrajectory::corners() const { return impl_->corners; }

double BaseTrajectory::distance_m(double t_s) const {
  return impl_->timeline.at(std::clamp(t_s, 0.0, impl_->duration_s)).distance;
}

double BaseTrajectory::restAfter(double t_s) const { return impl_->timeline.restAfter(t_s); }

double BaseTrajectory::floor_z(double t_s) const {
  return impl_->timeline.at(std::clamp(t_s, 0.0, impl_->duration_s)).floor_z;
}

std::size_t BaseTrajectory::storey(double t_s) const {
  return static_cast<std::size_t>(impl_->timeline.at(std::clamp(t_s, 0.0, impl_->duration_s)).storey);
}

bool BaseTrajectory::onStairs(double t_s) const {
  return impl_->timeline.at(std::clamp(t_s, 0.0, impl_->duration_s)).on_stairs;
}

const std::vector<std::size_t>& BaseTrajectory::storeys() const { return impl_->storeys; }

Eigen::Isometry3d BaseTrajectory::T_map_base(double t_s) const {
  const double t = std::clamp(t_s, 0.0, impl_->duration_s);
  const PlanarState s = impl_->timeline.at(t);
  const double activity = gaitActivity(s.speed, s.turn_rate, impl_->max_speed_mps, impl_->max_turn_rate_rps);
  const GaitOffsets g = gaitOffsets(impl_->gait, t, activity, impl_->gait_phase_rad);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(s.xy.x(), s.xy.y(), s.floor_z + impl_->gait.body_height_m + g.dz_m);
  // On a flight the body pitches with the run line: nose up going up (a rotation about y by
  // minus the slope lifts the x axis), nose down going down.
  T.linear() = (Eigen::AngleAxisd(s.yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(g.pitch_rad - s.slope_rad, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(g.roll_rad, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return T;
}

}  // namespace bimloc::sim
