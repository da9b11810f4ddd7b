#include "sim/world/site_config.hpp"

#include <stdexcept>

namespace bimloc::sim {

const char* toString(DoorState state) {
  switch (state) {
    case DoorState::Open: return "open";
    case DoorState::Shut: return "shut";
    case DoorState::Ajar: return "ajar";
  }
  return "open";
}

bool SiteConfig::exact() const {
  bool glass = false;
  for (const auto& [type, fraction] : this->glass.pass_fraction) glass = glass || fraction > 0.0;
  const bool walls_moved = this->walls.fraction > 0.0 && (this->walls.max_offset_m > 0.0 || this->walls.max_angle_deg > 0.0);
  return !walls_moved && this->walls.missing_fraction == 0.0 && this->walls.partitions_per_storey == 0 &&
         this->walls.edits.empty() && !glass && doors.shut_fraction == 0.0 && doors.ajar_fraction == 0.0 &&
         doors.edits.empty() && clutter.density_per_m2 == 0.0 && people.count_per_storey == 0 && people.paths.empty() &&
         !sensor.any();
}

const std::vector<std::string>& sitePresetNames() {
  static const std::vector<std::string> names{"exact", "as_built", "construction", "heavy"};
  return names;
}

SiteConfig sitePreset(const std::string& name) {
  SiteConfig c;
  c.preset = name;
  if (name == "exact") return c;
  // as_built: every wall a little off its drawn place; a 0.25 deg turn moves the ends of a
  // 10 m wall by 2.2 cm, so with the shift no point is more than about 5 cm off.
  c.walls.fraction = 1.0;
  c.walls.max_offset_m = 0.05;
  c.walls.max_angle_deg = 0.25;
  if (name == "as_built") return c;
  // construction: the figures (±10 cm, 10 % of the walls missing, doors mixed), with
  // two partitions a storey and windows and curtain walls glazed.
  c.walls.max_offset_m = 0.10;
  c.walls.max_angle_deg = 0.5;
  c.walls.missing_fraction = 0.10;
  c.walls.partitions_per_storey = 2;
  c.glass.pass_fraction = {{"IfcWindow", 0.9}, {"IfcCurtainWall", 0.9}, {"IfcPlate", 0.9}};
  c.doors.shut_fraction = 0.2;
  c.doors.ajar_fraction = 0.3;
  c.clutter.density_per_m2 = 0.2;
  c.people.count_per_storey = 2;
  if (name == "construction") return c;
  if (name == "heavy") {
    c.walls.max_offset_m = 0.20;
    c.walls.max_angle_deg = 1.0;
    c.walls.missing_fraction = 0.20;
    c.walls.partitions_per_storey = 4;
    c.glass.pass_fraction = {{"IfcWindow", 1.0}, {"IfcCurtainWall", 1.0}, {"IfcPlate", 1.0}};
    c.doors.shut_fraction = 0.3;
    c.doors.ajar_fraction = 0.4;
    c.clutter.density_per_m2 = 0.4;
    c.people.count_per_storey = 6;
    // Sensor effects only here (the construction site has none; they are keys): of the
    // order a VLP-16 shows on glass and at door jambs.
    c.sensor.glass_dropout = 0.5;
    c.sensor.dark_fraction = 0.2;
    c.sensor.dark_dropout = 0.5;
    c.sensor.mixed_probability = 0.5;
    return c;
  }
  std::string names;
  for (const auto& n : sitePresetNames()) names += (names.empty() ? "" : ", ") + n;
  throw std::invalid_argument("no site preset '" + name + "' (presets: " + names + ")");
}

}  // namespace bimloc::sim
