// The scenario against its world: storey, rooms and places named in the file must exist there.
#include "sim/scenario/scenario.hpp"

#include "sim/base/free_space.hpp"
#include "sim/base/outside_rooms.hpp"
#include "sim/base/room_lookup.hpp"
#include "sim/common/seeded_random.hpp"
#include "sim/scenario/scenario_sections.hpp"
#include "sim/scenario/yaml_mapping.hpp"
#include "sim/world/world.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace bimloc::sim {
namespace {

// A random start: draws inside the room's bounding box until one lands in the room where the body fits.
constexpr int kStartDraws = 2000;
// A room start: the centre, or the nearest spot within this distance where the body fits.
constexpr double kSpotSearch_m = 3.0;

int lineOf(const Scenario& s, const std::string& key) {
  const auto it = s.lines.find(key);
  return it != s.lines.end() ? it->second : 0;
}

std::string xy(const Eigen::Vector2d& p) {
  char text[64];
  std::snprintf(text, sizeof text, "(%.2f, %.2f)", p.x(), p.y());
  return text;
}

const bim::Room& room(const Scenario& s, const bim::Storey& storey, const std::string& name, int line) {
  std::string problem;
  const bim::Room* r = lookUpRoom(storey, name, &problem);
  if (!r) detail::fail(s.file, line, problem);
  return *r;
}

// The storey's outline, for places given as coordinates: the convex hull of its rooms and walls
// (of its mesh for a world without either). Empty when nothing is known.
bim::Polygon2 outline(const bim::Storey& storey) {
  std::vector<Eigen::Vector2d> points;
  for (const auto& r : storey.rooms) points.insert(points.end(), r.footprint.begin(), r.footprint.end());
  for (const auto& w : storey.walls)
    for (const auto& f : w.faces) points.push_back(f.start.head<2>()), points.push_back(f.end.head<2>());
  if (points.empty())
    for (const auto& v : storey.mesh.vertices) points.push_back(v.head<2>().cast<double>());
  return points.size() >= 3 ? bim::convexHull(points) : bim::Polygon2{};
}

void checkInside(const Scenario& s, const bim::Storey& storey, const bim::Polygon2& hull, const Eigen::Vector2d& p,
                 const std::string& what, int line) {
  if (roomAt(storey, p) || hull.empty() || bim::pointInPolygon(hull, p)) return;
  Eigen::Vector2d lo = hull.front(), hi = lo;
  for (const auto& q : hull) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  char span[128];
  std::snprintf(span, sizeof span, "x %.2f..%.2f, y %.2f..%.2f", lo.x(), hi.x(), lo.y(), hi.y());
  detail::fail(s.file, line, what + " " + xy(p) + " is outside the building (storey '" + storey.name + "' spans " + span + ")");
}

}  // namespace

std::size_t scenarioStorey(const Scenario& scenario, const World& world) {
  if (scenario.storey == "auto") {
    // The localizer is not told; the simulator needs the storey: the start room's.
    const auto& storeys = world.building().storeys;
    const bool named = scenario.start.kind == StartConfig::Kind::Room || scenario.start.kind == StartConfig::Kind::RandomInRoom;
    std::vector<std::size_t> holding;
    for (std::size_t i = 0; named && i < storeys.size(); ++i)
      if (lookUpRoom(storeys[i], scenario.start.room, nullptr)) holding.push_back(i);
    if (holding.size() == 1) return holding.front();
    const std::string hint = "; give the simulator's storey (storey: NAME) and tell the localizer `localizer: {storey: auto}`";
    if (!named) detail::fail(scenario.file, lineOf(scenario, "storey"), "storey: auto needs a start room to find the simulator's storey" + hint);
    detail::fail(scenario.file, lineOf(scenario, "storey"),
                 "storey: auto: start room '" + scenario.start.room + "' is a room of " + std::to_string(holding.size()) +
                     " storeys" + hint);
  }
  try {
    return world.storeyIndex(scenario.storey);
  } catch (const std::invalid_argument& e) {
    detail::fail(scenario.file, lineOf(scenario, "storey"), e.what());
  }
}

bool storeyGiven(const Scenario& s) {
  const auto it = s.localizer.find("storey");
  return s.storey != "auto" && (it == s.localizer.end() || *it != "auto");
}

void checkScenarioAgainstWorld(const Scenario& s, const World& world) {
  const bim::Storey& storey = world.building().storeys.at(scenarioStorey(s, world));
  detail::checkSiteAgainstWorld(s, world);
  const bim::Polygon2 hull = outline(storey);
  if (s.start.kind == StartConfig::Kind::Pose)
    checkInside(s, storey, hull, s.start.pose.head<2>(), "start.pose", s.start.line);
  else if (s.start.kind != StartConfig::Kind::OutsideRooms)
    room(s, storey, s.start.room, s.start.line);
  const MotionConfig& m = s.motion;
  switch (m.kind) {
    case MotionConfig::Kind::Stand:
      break;
    case MotionConfig::Kind::Waypoints:
      for (std::size_t i = 0; i < m.waypoints.size(); ++i)
        checkInside(s, storey, hull, m.waypoints[i].xy, "motion.waypoints[" + std::to_string(i) + "]",
                    lineOf(s, "motion.waypoints." + std::to_string(i)));
      break;
    case MotionConfig::Kind::Tour:
      for (std::size_t i = 0; i < m.rooms.size(); ++i) {
        // A room on another storey (motion.storeys): that storey's rooms.
        const bim::Storey* on = &storey;
        if (!m.storeys.empty()) {
          const int line = lineOf(s, "motion.storeys." + std::to_string(std::min<std::size_t>(i, m.storeys.size() - 1)));
          try {
            on = &world.building().storeys.at(world.storeyIndex(m.storeys[i]));
          } catch (const std::invalid_argument& e) {
            detail::fail(s.file, line > 0 ? line : lineOf(s, "motion"), std::string("motion.storeys: ") + e.what());
          }
        }
        room(s, *on, m.rooms[i], lineOf(s, "motion.rooms." + std::to_string(i)));
      }
      break;
    case MotionConfig::Kind::RandomWalk:
      if (!m.walk_room.empty())
        room(s, storey, m.walk_room, lineOf(s, "motion.room"));
      else if (s.start.kind == StartConfig::Kind::OutsideRooms)
        detail::fail(s.file, lineOf(s, "motion"), "a random walk without motion.room walks in the start's room, but start.outside_rooms is in none");
      else if (s.start.kind == StartConfig::Kind::Pose && !roomAt(storey, s.start.pose.head<2>()))
        detail::fail(s.file, lineOf(s, "motion"),
                     "a random walk without motion.room walks in the start's room, but start.pose " +
                         xy(s.start.pose.head<2>()) + " is in no room; rooms: " + roomList(storey));
      break;
  }
}

Pose2 startPose(const Scenario& s, const World& world) {
  const std::size_t index = scenarioStorey(s, world);
  const bim::Storey& storey = world.building().storeys.at(index);
  if (s.start.kind == StartConfig::Kind::Pose) return {s.start.pose.x(), s.start.pose.y(), s.start.pose.z()};
  if (s.start.kind == StartConfig::Kind::OutsideRooms) {
    const auto spot = outsideRoomsSpot(world, index, s.motion.body_radius_m, s.motion.gait.body_height_m, s.seed);
    if (!spot)
      detail::fail(s.file, s.start.line,
                   "no spot outside the rooms of storey '" + storey.name + "' where the body fits and from which it can walk into them");
    // The heading drawn apart from the spot: giving yaw_deg does not change which spot is drawn.
    SeededRandom random(s.seed, RandomStream::Walk);
    return {spot->x(), spot->y(), s.start.yaw_rad.value_or(random.uniform(-M_PI, M_PI))};
  }
  const bim::Room& r = room(s, storey, s.start.room, s.start.line);
  const double body_z = bodyCentreZ(world, index, r.centre, s.motion.gait.body_height_m);
  const FreeSpace space(world, index, s.motion.body_radius_m, body_z);
  if (s.start.kind == StartConfig::Kind::Room) {
    const auto spot = space.freeSpotNear(r.centre, &r.footprint, kSpotSearch_m);
    if (!spot) detail::fail(s.file, s.start.line, "no spot near the centre of room " + r.name + " where the body fits");
    return {spot->x(), spot->y(), s.start.yaw_rad.value_or(0.0)};
  }
  Eigen::Vector2d lo = r.footprint.front(), hi = lo;
  for (const auto& q : r.footprint) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  SeededRandom random(s.seed, RandomStream::Start);
  for (int draw = 0; draw < kStartDraws; ++draw) {
    const Eigen::Vector2d q(random.uniform(lo.x(), hi.x()), random.uniform(lo.y(), hi.y()));
    // Drawn with every spot, so that giving yaw_deg does not change which spot is drawn.
    const double yaw = random.uniform(-M_PI, M_PI);
    if (bim::pointInPolygon(r.footprint, q) && space.spotFree(q, FreeSpace::kMargin_m))
      return {q.x(), q.y(), s.start.yaw_rad.value_or(yaw)};
  }
  detail::fail(s.file, s.start.line, "no spot in room " + r.name + " where the body fits");
}

BaseTrajectory planTrajectory(const Scenario& s, const World& world) {
  const Pose2 start = startPose(s, world);
  try {
    return BaseTrajectory::plan(world, scenarioStorey(s, world), start, s.motion, s.duration_s, s.seed);
  } catch (const MotionError& e) {
    int line = lineOf(s, "motion");
    if (e.where == MotionError::Where::Start) line = s.start.line;
    if (e.where == MotionError::Where::Segment && s.motion.kind == MotionConfig::Kind::Waypoints)
      line = lineOf(s, "motion.waypoints." + std::to_string(e.segment - 1));
    detail::fail(s.file, line, e.what());
  }
}

}  // namespace bimloc::sim
