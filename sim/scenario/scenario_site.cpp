// The scenario's `site:` section: a preset name, or a mapping starting from a preset (default
// exact) whose keys override it. Checked against the world (wall and door ids) in
// checkSiteAgainstWorld.
#include "sim/scenario/scenario_sections.hpp"
#include "sim/world/site_draws.hpp"
#include "sim/world/site_people.hpp"
#include "sim/world/world.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::sim::detail {
namespace {

const Range kFraction = Range::closed(0.0, 1.0);

int readCount(const Mapping& m, const std::string& key, int out, int max) {
  double v = out;
  m.read(key, v, Range::closed(0.0, max));
  if (v != std::floor(v)) m.fail(key, m.name(key) + " must be a whole number, got " + m.value(key).Scalar());
  return static_cast<int>(v);
}

// The items of an `edit:` list, each a mapping with `keys`.
std::vector<Mapping> editItems(const Mapping& m, const std::vector<std::string>& keys) {
  std::vector<Mapping> items;
  if (!m.has("edit")) return items;
  const YAML::Node& list = m.value("edit");
  if (!list.IsSequence())
    m.fail("edit", m.name("edit") + " must be a list of {id: ..., ...} mappings, got " + describe(list));
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = m.name("edit") + "[" + std::to_string(i) + "]";
    items.emplace_back(m.file(), list[i], path, m.line("edit"), keys);
    items.back().require("id");
  }
  return items;
}

void readWalls(const Mapping& site, SiteWalls& walls) {
  const Mapping m = site.mapping("walls", {"fraction", "max_offset_m", "max_angle_deg", "missing_fraction", "partitions", "edit"});
  m.read("fraction", walls.fraction, kFraction);
  m.read("max_offset_m", walls.max_offset_m, Range::closed(0.0, 1.0));
  m.read("max_angle_deg", walls.max_angle_deg, Range::closed(0.0, 10.0));
  m.read("missing_fraction", walls.missing_fraction, kFraction);
  const Mapping p = m.mapping("partitions", {"count", "min_length_m", "max_length_m", "thickness_m", "height_m", "clearance_m"});
  walls.partitions_per_storey = readCount(p, "count", walls.partitions_per_storey, 100);
  p.read("min_length_m", walls.partition_min_length_m, Range::positive(20.0));
  p.read("max_length_m", walls.partition_max_length_m, Range::positive(20.0));
  if (walls.partition_min_length_m > walls.partition_max_length_m)
    p.fail(p.has("max_length_m") ? "max_length_m" : "min_length_m",
           "site.walls.partitions.min_length_m must not exceed max_length_m");
  p.read("thickness_m", walls.partition_thickness_m, Range::positive(0.5));
  p.read("height_m", walls.partition_height_m, Range::positive(5.0));
  // Below the base's diameter and the planner's margins, a partition could close a passage.
  p.read("clearance_m", walls.partition_clearance_m, Range::closed(0.8, 5.0));
  for (const Mapping& item : editItems(m, {"id", "offset_m", "angle_deg", "missing"})) {
    WallEdit edit;
    item.read("id", edit.id);
    edit.line = item.line("id");
    double v = 0.0;
    if (item.has("offset_m")) item.read("offset_m", v, Range::closed(-1.0, 1.0)), edit.offset_m = v;
    if (item.has("angle_deg")) item.read("angle_deg", v, Range::closed(-45.0, 45.0)), edit.angle_deg = v;
    item.read("missing", edit.missing);
    if (edit.missing && (edit.offset_m || edit.angle_deg))
      item.fail("missing", "a wall not built has no offset or angle: give missing: true alone");
    walls.edits.push_back(edit);
  }
}

void readDoors(const Mapping& site, SiteDoors& doors) {
  const Mapping m = site.mapping("doors", {"shut_fraction", "ajar_fraction", "ajar_angle_deg", "edit"});
  m.read("shut_fraction", doors.shut_fraction, kFraction);
  m.read("ajar_fraction", doors.ajar_fraction, kFraction);
  if (doors.shut_fraction + doors.ajar_fraction > 1.0 + 1e-12)
    m.fail(m.has("ajar_fraction") ? "ajar_fraction" : "shut_fraction",
           "site.doors.shut_fraction + ajar_fraction must not exceed 1 (the rest are open)");
  m.read("ajar_angle_deg", doors.ajar_angle_deg, Range::positive(90.0));
  for (const Mapping& item : editItems(m, {"id", "state"})) {
    DoorEdit edit;
    item.read("id", edit.id);
    edit.line = item.line("id");
    std::string state = "open";
    item.require("state");
    item.readChoice("state", state, {"open", "shut", "ajar"});
    edit.state = state == "shut" ? DoorState::Shut : state == "ajar" ? DoorState::Ajar : DoorState::Open;
    doors.edits.push_back(edit);
  }
}

void readClutter(const Mapping& site, SiteClutter& clutter) {
  const Mapping m = site.mapping("clutter", {"density_per_m2", "min_size_m", "max_size_m", "against_walls", "clearance_m"});
  m.read("density_per_m2", clutter.density_per_m2, Range::closed(0.0, 2.0));
  for (const char* key : {"min_size_m", "max_size_m"}) {
    if (!m.has(key)) continue;
    const auto v = m.numbers(m.value(key), m.name(key), m.line(key), 3, 3, Range::positive(5.0));
    double* out = std::string(key) == "min_size_m" ? clutter.min_size_m : clutter.max_size_m;
    for (int a = 0; a < 3; ++a) out[a] = v[static_cast<std::size_t>(a)];
  }
  for (int a = 0; a < 3; ++a)
    if (clutter.min_size_m[a] > clutter.max_size_m[a])
      m.fail(m.has("max_size_m") ? "max_size_m" : "min_size_m",
             "site.clutter.min_size_m must not exceed max_size_m, axis by axis ([along, across, up])");
  m.read("against_walls", clutter.against_walls, kFraction);
  // Below the base's diameter and the planner's margins, two boxes could close a passage.
  m.read("clearance_m", clutter.clearance_m, Range::closed(0.8, 5.0));
}

// people: {count, speed_mps, radius_m, height_m, paths: [{waypoints: [[x, y], ...], speed_mps, storey}]}
void readPeople(const Mapping& site, SitePeople& people) {
  const Mapping m = site.mapping("people", {"count", "speed_mps", "radius_m", "height_m", "paths"});
  people.count_per_storey = readCount(m, "count", people.count_per_storey, 100);
  m.read("speed_mps", people.speed_mps, Range::positive(3.0));
  m.read("radius_m", people.radius_m, Range::closed(0.05, 1.0));
  m.read("height_m", people.height_m, Range::closed(0.3, 2.5));
  if (!m.has("paths")) return;
  const YAML::Node& list = m.value("paths");
  if (!list.IsSequence())
    m.fail("paths", m.name("paths") + " must be a list of {waypoints: [[x, y], ...], speed_mps: ...} mappings, got " +
                        describe(list));
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Mapping item(m.file(), list[i], m.name("paths") + "[" + std::to_string(i) + "]", m.line("paths"),
                       {"waypoints", "speed_mps", "storey"});
    item.require("waypoints");
    PersonPath path;
    path.speed_mps = people.speed_mps;
    path.line = item.line("waypoints");
    item.read("speed_mps", path.speed_mps, Range::positive(3.0));
    item.read("storey", path.storey);
    const YAML::Node& points = item.value("waypoints");
    if (!points.IsSequence() || points.size() < 2)
      item.fail("waypoints", item.name("waypoints") + " must be a list of at least two [x, y] points, got " + describe(points));
    for (std::size_t k = 0; k < points.size(); ++k) {
      const auto xy = item.numbers(points[k], item.name("waypoints") + "[" + std::to_string(k) + "]", path.line, 2, 2,
                                   Range::closed(-1e6, 1e6));
      path.waypoints.emplace_back(xy[0], xy[1]);
    }
    people.paths.push_back(path);
  }
}

void readSensorEffects(const Mapping& site, SiteSensor& sensor) {
  const Mapping m =
      site.mapping("sensor", {"glass_dropout", "dark_fraction", "dark_dropout", "mixed_probability", "mixed_jump_m"});
  m.read("glass_dropout", sensor.glass_dropout, kFraction);
  m.read("dark_fraction", sensor.dark_fraction, kFraction);
  m.read("dark_dropout", sensor.dark_dropout, kFraction);
  m.read("mixed_probability", sensor.mixed_probability, kFraction);
  m.read("mixed_jump_m", sensor.mixed_jump_m, Range::positive(10.0));
}

}  // namespace

SiteConfig readSite(const Mapping& top, std::map<std::string, int>& lines) {
  if (!top.has("site")) return sitePreset("exact");
  lines["site"] = top.line("site");
  const YAML::Node& node = top.value("site");
  if (node.IsScalar()) {  // site: as_built
    const auto& names = sitePresetNames();
    if (std::find(names.begin(), names.end(), node.Scalar()) != names.end()) return sitePreset(node.Scalar());
    const std::string guess = nearestWord(node.Scalar(), names);
    top.fail("site", "site must be a preset (exact, as_built, construction, heavy) or a mapping, got '" + node.Scalar() +
                         "'" + (guess.empty() ? "" : " (did you mean '" + guess + "'?)"));
  }
  const Mapping m = top.mapping("site", {"preset", "walls", "glass", "doors", "clutter", "people", "sensor"});
  std::string preset = "exact";
  m.readChoice("preset", preset, sitePresetNames());
  SiteConfig site = sitePreset(preset);
  readWalls(m, site.walls);
  const Mapping glass = m.mapping("glass", {"IfcWindow", "IfcCurtainWall", "IfcPlate"});
  for (const auto& key : glass.given()) glass.read(key, site.glass.pass_fraction[key], kFraction);
  readDoors(m, site.doors);
  readClutter(m, site.clutter);
  readPeople(m, site.people);
  readSensorEffects(m, site.sensor);
  return site;
}

void checkSiteAgainstWorld(const Scenario& s, const World& world) {
  const bim::Building& building = world.building();
  for (const WallEdit& edit : s.site.walls.edits) {
    const auto walls = wallsNamed(building, edit.id);
    if (walls.empty()) {
      const std::string guess = nearestWord(edit.id, wallWords(building));
      fail(s.file, edit.line, "site.walls.edit: no wall '" + edit.id + "' (GlobalId or name) in the plan" +
                                  (guess.empty() ? "" : " (did you mean '" + guess + "'?)"));
    }
    if (walls.size() > 1) {
      std::string ids;
      for (const bim::Wall* w : walls) ids += (ids.empty() ? "" : ", ") + w->id;
      fail(s.file, edit.line, "site.walls.edit: " + std::to_string(walls.size()) + " walls are named '" + edit.id +
                                  "': give one GlobalId (" + ids + ")");
    }
  }
  std::vector<std::string> door_words;
  for (const DoorTruth& d : world.siteTruth().doors) {
    door_words.push_back(d.id);
    if (!d.name.empty()) door_words.push_back(d.name);
  }
  for (const DoorEdit& edit : s.site.doors.edits)
    if (std::find(door_words.begin(), door_words.end(), edit.id) == door_words.end()) {
      const std::string guess = nearestWord(edit.id, door_words);
      fail(s.file, edit.line, "site.doors.edit: no door '" + edit.id + "' (GlobalId or name) in the plan" +
                                  (door_words.empty() ? " (it has no IfcDoor)"
                                   : guess.empty()    ? ""
                                                      : " (did you mean '" + guess + "'?)"));
    }
  // A person's path is checked against the plan: the walls the scenario's author sees.
  for (const PersonPath& path : s.site.people.paths) {
    std::size_t storey = 0;
    try {
      storey = world.storeyIndex(path.storey.empty() ? "0" : path.storey);
    } catch (const std::invalid_argument& e) {
      fail(s.file, path.line, std::string("site.people.paths: ") + e.what());
    }
    const std::string problem = personPathProblem(world, storey, path, s.site.people.radius_m);
    if (!problem.empty())
      fail(s.file, path.line, "site.people.paths: " + problem + ": move the waypoints so that every leg keeps " +
                                  std::to_string(s.site.people.radius_m).substr(0, 4) + " m (the person's radius) from the walls");
  }
}

}  // namespace bimloc::sim::detail
