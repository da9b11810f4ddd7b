// How the simulated site differs from its plan: walls off their drawn place or not built yet,
// temporary partitions, glass the lidar sees through, doors open, shut or ajar. Only the
// simulator's world changes; the localizer always gets the plan. Every draw comes from the
// scenario's seed (World::withSite), and what was drawn is the SiteTruth.
#pragma once

#include <Eigen/Core>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::sim {

// One wall changed by hand: its GlobalId or name, and what to do to it.
struct WallEdit {
  std::string id;                   // GlobalId or name
  std::optional<double> offset_m;   // along the wall's faces[0] normal (as in building.json)
  std::optional<double> angle_deg;  // about the wall's vertical centre line, counter-clockwise
  bool missing = false;             // not built yet
  int line = 0;                     // where the scenario gave it, for messages
};

struct SiteWalls {
  double fraction = 0.0;       // of the walls shifted and turned (each by a uniform draw)
  double max_offset_m = 0.0;   // shift along faces[0]'s normal, uniform in [-max, max]
  double max_angle_deg = 0.0;  // turn about the vertical centre line, uniform in [-max, max]
  double missing_fraction = 0.0;  // of the walls not built yet
  // Temporary partitions: free-standing boards in rooms, kept clear of every wall, doorway and
  // other partition by `partition_clearance_m` so they never cut a room or a path in two.
  int partitions_per_storey = 0;
  double partition_min_length_m = 1.0;
  double partition_max_length_m = 3.0;
  double partition_thickness_m = 0.1;
  double partition_height_m = 2.0;
  double partition_clearance_m = 1.0;  // > the base's 0.6 m diameter plus the planner's margins
  std::vector<WallEdit> edits;         // applied after the draws, they win
};

// Fraction of the rays that pass an element of each glazed IFC class (IfcWindow, IfcCurtainWall,
// IfcPlate); 0 (or absent) = opaque, as in the plan's world. The robot never passes glass.
struct SiteGlass {
  std::map<std::string, double> pass_fraction;
};

enum class DoorState { Open, Shut, Ajar };
const char* toString(DoorState state);

struct DoorEdit {
  std::string id;  // GlobalId or name of the IfcDoor
  DoorState state = DoorState::Open;
  int line = 0;
};

// Door leaves: open (left out, as in the plan's world: swung back flat against the wall), shut
// (a leaf closing the doorway: the planner finds no way through), or ajar (the leaf standing
// open `ajar_angle_deg` about its hinge jamb: at the default 90 deg the base still passes and
// the lidar sees the leaf; below about 60 deg a 0.9 m door no longer lets a 0.6 m base through).
// Each door draws its state from the fractions.
struct SiteDoors {
  double shut_fraction = 0.0;
  double ajar_fraction = 0.0;
  double ajar_angle_deg = 90.0;
  double leaf_thickness_m = 0.04;
  std::vector<DoorEdit> edits;
};

// Clutter: boxes (material stacks, pallets, scaffold towers as their bounding boxes) in the
// rooms, `density_per_m2` of room area. A box stands against one edge of its room (a fraction
// `against_walls` of them) or free, and keeps `clearance_m` from everything else (other edges,
// walls, doors plus 1 m, partitions, other boxes), so it never closes a passage: every tour
// the plan allows stays possible, and the planner (which plans on the site) goes round it.
struct SiteClutter {
  double density_per_m2 = 0.0;
  double min_size_m[3] = {0.4, 0.4, 0.3};  // along, across, up
  double max_size_m[3] = {1.2, 1.0, 1.5};
  double against_walls = 0.7;
  double clearance_m = 1.0;
};

// One walking person given in the scenario: a polyline walked at `speed_mps`, there and back
// again, for ever (from the first waypoint at t = 0).
struct PersonPath {
  std::vector<Eigen::Vector2d> waypoints;  // map frame, at least two
  double speed_mps = 1.2;
  std::string storey;  // name, GlobalId or index; the scenario's storey when not given
  int line = 0;        // where the scenario gave it, for messages
};

// People: vertical cylinders walking through the site, moving occluders for the lidar only
// (the robot neither avoids nor meets them: they may cross its path, and the base's collision
// world never has them). `count_per_storey` are drawn from the seed, each walking back and forth
// between two to four points of one room (legs clear of the site's walls by its radius); `paths`
// are given. 0.25 m x 1.75 m is an adult's shoulder half-width and height (DIN 33402).
struct SitePeople {
  int count_per_storey = 0;
  double speed_mps = 1.2;  // walking pace on a site (slower than the 1.4 m/s of a street)
  double radius_m = 0.25;
  double height_m = 1.75;
  std::vector<PersonPath> paths;
};

// Sensor effects of a real site. Dropout: a return from glass (a pane the ray does not pass)
// or from a dark surface (tar paper, black-painted steel: `dark_fraction` of the elements,
// drawn from the seed) is lost with the given probability. Mixed points: where consecutive
// firings of one laser land on surfaces more than `mixed_jump_m` apart, the beam's footprint
// straddles the edge and, with `mixed_probability`, the return is a range between the two
// (uniform): the "mixed pixels" of Hebert & Krotkov 1992, the veiling points of a real VLP-16.
struct SiteSensor {
  double glass_dropout = 0.0;
  double dark_fraction = 0.0;
  double dark_dropout = 0.0;
  double mixed_probability = 0.0;
  double mixed_jump_m = 0.3;
  bool any() const { return glass_dropout > 0.0 || (dark_fraction > 0.0 && dark_dropout > 0.0) || mixed_probability > 0.0; }
};

struct SiteConfig {
  std::string preset = "exact";  // the preset it started from (the keys given override it)
  SiteWalls walls;
  SiteGlass glass;
  SiteDoors doors;
  SiteClutter clutter;
  SitePeople people;
  SiteSensor sensor;
  bool exact() const;  // nothing differs from the plan
};

// exact, as_built, construction, heavy (README.md, "Sites"); std::invalid_argument otherwise.
SiteConfig sitePreset(const std::string& name);
const std::vector<std::string>& sitePresetNames();

}  // namespace bimloc::sim
