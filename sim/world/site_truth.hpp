// What the simulated site is, against its plan: the truth a localizer's estimates of wall
// deviations (the S-Graph's) are scored against, and what `bimloc simulate` writes into the
// dataset's metadata. Get it with World::siteTruth() (or Simulator::world().siteTruth()).
#pragma once

#include "sim/world/site_config.hpp"

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace bimloc::sim {

// One wall of the plan as built. A point p of the plan's wall is at
//   c + R(angle_deg) (p - c) + offset_m n0
// on the site, c the midpoint of the wall's axis (Wall::start/end), n0 its faces[0] plane normal.
struct WallTruth {
  std::string id, name;  // IFC GlobalId and Name, as in building.json
  std::size_t storey = 0;
  double offset_m = 0.0;   // along faces[0]'s normal
  double angle_deg = 0.0;  // counter-clockwise about the vertical line through c
  bool missing = false;    // not built: the site has no such wall
};

// A temporary partition, in no plan: a board of the given thickness centred on start -> end.
struct PartitionTruth {
  std::size_t storey = 0;
  std::string room;  // name of the room it stands in
  Eigen::Vector2d start = Eigen::Vector2d::Zero(), end = Eigen::Vector2d::Zero();
  double thickness_m = 0.0, height_m = 0.0;
};

// A clutter box: centre of its base, heading of its first side, size (along, across, up).
struct ClutterTruth {
  std::size_t storey = 0;
  std::string room;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double yaw_deg = 0.0;
  Eigen::Vector3d size_m = Eigen::Vector3d::Zero();
  bool against_wall = false;
};

struct DoorTruth {
  std::string id, name;  // of the IfcDoor
  std::size_t storey = 0;
  DoorState state = DoorState::Open;
  std::string wall_id;  // the wall it stands in (its leaf follows that wall's shift)
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // of the door's plan outline (bounding box), XY
};

struct GlassTruth {
  std::string ifc_class;
  double pass_fraction = 0.0;
  std::size_t elements = 0;  // how many elements of that class the site has
};

// A walking person: a vertical cylinder whose axis walks the polyline `waypoints` at speed_mps,
// there and back again, starting `phase_m` along that loop at t = 0 (site_people.hpp).
struct PersonTruth {
  std::size_t storey = 0;
  std::string room;  // the room a drawn person walks in ("" for a path the scenario gave)
  std::vector<Eigen::Vector2d> waypoints;
  double speed_mps = 0.0, radius_m = 0.0, height_m = 0.0;
  double floor_z = 0.0;  // the cylinder stands from floor_z to floor_z + height_m
  double phase_m = 0.0;
};

struct SiteTruth {
  std::string preset = "exact";
  std::uint64_t seed = 0;
  std::vector<WallTruth> walls;  // every wall of the plan, storey by storey, in plan order
  std::vector<PartitionTruth> partitions;
  std::vector<DoorTruth> doors;
  std::vector<GlassTruth> glass;
  std::vector<ClutterTruth> clutter;
  std::vector<PersonTruth> people;
  SiteSensor sensor;                  // the lidar's site effects (dropout, mixed points)
  std::vector<std::string> dark;      // ids of the dark elements (sensor.dark_fraction)
  std::vector<std::string> warnings;  // what was asked and could not be done (a partition with no room for it, ...)

  const WallTruth* findWall(const std::string& id) const;
};

nlohmann::json siteTruthJson(const SiteTruth& truth);

}  // namespace bimloc::sim
