#include "sim/base/script_builder.hpp"

#include "sim/base/gait.hpp"
#include "sim/world/world.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace bimloc::sim {

// A plan point as text for errors: "(x, y)" in metres.
std::string pointText(const Eigen::Vector2d& p) {
  char text[64];
  std::snprintf(text, sizeof text, "(%.2f, %.2f)", p.x(), p.y());
  return text;
}

namespace {

// Floor search under the body: from body height down to a bit below the storey floor.
constexpr double kFloorSearchBelow_m = 1.0;
// The base lines up this far (beyond its radius) before a flight's first nosing and steps off
// this far past its last one: the sphere of the body then clears the first riser and the
// opening's edge, and the Bullet checks of the storey resume there.
constexpr double kFlightClearance_m = 0.15;
// Where the spot before a flight is walled in (a railing, a newel), the nearest free spot within this.
constexpr double kFlightSpotSearch_m = 1.0;

std::string pointText3(const Eigen::Vector3d& p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.2f, %.2f, %.2f)", p.x(), p.y(), p.z());
  return text;
}

Eigen::Vector2d travelDirection(const StairLink& link, std::size_t i) {
  const Eigen::Vector2d d = (link.exit(i) - link.entry(i)).head<2>();
  return d.norm() > 1e-9 ? Eigen::Vector2d(d.normalized()) : Eigen::Vector2d::UnitX();
}

}  // namespace

ScriptBuilder::ScriptBuilder(const World& world, std::size_t storey, double floor_z, const Pose2& start,
                             const MotionConfig& motion, const MotionLimits& limits)
    : world_(world),
      motion_(motion),
      links_(stairLinks(world.building())),
      storey_(storey),
      floor_ref_(floor_z),
      corners_{start},
      visited_storeys_{storey} {
  const double height = motion.gait.body_height_m;
  // The sampler reads the builder's current storey: after a climb, the floor of the new one.
  timeline_ = Timeline(
      {start.x, start.y}, start.yaw, limits,
      [this, height](const Eigen::Vector2d& p) {
        double z = floor_ref_;
        return world_.floorBelow(storey_, {p.x(), p.y(), floor_ref_ + height}, height + kFloorSearchBelow_m, &z) ? z
                                                                                                                 : floor_ref_;
      },
      static_cast<int>(storey));
}

const bim::Storey& ScriptBuilder::storeyPlan() const { return world_.building().storeys.at(storey_); }

FreeSpace& ScriptBuilder::space() {
  auto& s = spaces_[storey_];
  if (!s) s = std::make_unique<FreeSpace>(world_, storey_, motion_.body_radius_m, floor_ref_ + motion_.gait.body_height_m);
  return *s;
}

void ScriptBuilder::addLeg(const std::vector<Eigen::Vector2d>& points, std::optional<double> final_yaw) {
  for (const auto& p : points) {
    const Eigen::Vector2d from = timeline_.position();
    ++segments_;  // counted even when empty, so waypoint K always ends segment K
    if ((p - from).norm() < 1e-9) continue;
    Eigen::Vector3d contact = Eigen::Vector3d::Zero();
    if (!space().segmentClear(from, p, 0.0, &contact))
      throw MotionError("motion segment " + std::to_string(segments_) + " from " + pointText(from) + " to " +
                            pointText(p) + " hits the building at " + pointText3(contact),
                        MotionError::Where::Segment, segments_);
    timeline_.moveTo(p);
    corners_.push_back({p.x(), p.y(), std::remainder(timeline_.yaw(), 2.0 * M_PI)});
  }
  if (final_yaw) timeline_.turnTo(*final_yaw);
}

void ScriptBuilder::enterStorey(std::size_t storey, double floor_z) {
  // A storey entered again keeps its free space (made from the same floor).
  if (!spaces_.count(storey)) floor_ref_ = floor_z;
  else floor_ref_ = spaces_[storey]->bodyZ() - motion_.gait.body_height_m;
  storey_ = storey;
  if (std::find(visited_storeys_.begin(), visited_storeys_.end(), storey) == visited_storeys_.end())
    visited_storeys_.push_back(storey);
}

void ScriptBuilder::walkLink(const StairLink& link) {
  const double clearance = motion_.body_radius_m + kFlightClearance_m;
  const Eigen::Vector3d& entry = link.entry(0);
  const Eigen::Vector2d before = entry.head<2>() - clearance * travelDirection(link, 0);
  // To the spot before the flight, through this storey's rooms and doors.
  FreeSpace& here = space();
  const auto spot = here.freeSpotNear(before, nullptr, kFlightSpotSearch_m);
  std::vector<Eigen::Vector2d> leg;
  if (spot) leg = here.path(timeline_.position(), *spot);
  const bim::StairFlight& first = *link.flights.front();
  if (leg.empty())
    throw MotionError("no path from " + pointText(timeline_.position()) + " to the " + (link.up ? "foot" : "head") +
                          " of flight " + (first.name.empty() ? first.id : first.name) + " at " + pointText(before) +
                          " on storey '" + storeyPlan().name + "'",
                      MotionError::Where::Script);
  leg.erase(leg.begin());
  addLeg(leg);
  // Onto the flight and along it (unchecked: the steps are the flight's own mesh), landing by landing.
  timeline_.moveFlatTo(entry.head<2>(), entry.z());
  for (std::size_t i = 0; i < link.flights.size(); ++i) {
    if (i > 0) timeline_.moveFlatTo(link.entry(i).head<2>(), link.entry(i).z());
    const bool last = i + 1 == link.flights.size();
    timeline_.climbTo(link.exit(i).head<2>(), link.exit(i).z(), stairSpeed_mps(*link.flights[i], motion_),
                      static_cast<int>(last ? link.to : storey_));
    corners_.push_back({link.exit(i).x(), link.exit(i).y(), std::remainder(timeline_.yaw(), 2.0 * M_PI)});
  }
  const Eigen::Vector3d& off = link.exit(link.flights.size() - 1);
  const Eigen::Vector2d beyond = off.head<2>() + clearance * travelDirection(link, link.flights.size() - 1);
  timeline_.moveFlatTo(beyond, off.z());
  corners_.push_back({beyond.x(), beyond.y(), std::remainder(timeline_.yaw(), 2.0 * M_PI)});
  enterStorey(link.to, off.z());
  // Where the landing's edge crowds the body, on to the nearest spot it fits.
  if (!space().spotFree(beyond, 0.0)) {
    if (const auto free = space().freeSpotNear(beyond, nullptr, kFlightSpotSearch_m)) {
      timeline_.moveFlatTo(*free, off.z());
      corners_.push_back({free->x(), free->y(), std::remainder(timeline_.yaw(), 2.0 * M_PI)});
    }
  }
}

void ScriptBuilder::goToStorey(std::size_t storey) {
  if (storey == storey_) return;
  const auto route = stairRoute(links_, storey_, storey);
  if (!route)
    throw MotionError("no stairs lead from storey '" + storeyPlan().name + "' to storey '" +
                          world_.building().storeys.at(storey).name + "' (" +
                          std::to_string(world_.building().stairs.size()) + " flights in the plan)",
                      MotionError::Where::Script);
  for (const StairLink* link : *route) walkLink(*link);
}

}  // namespace bimloc::sim
