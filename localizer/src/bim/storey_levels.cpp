// The height of each storey's floor in the frame the geometry is in (paper: floor information
// extraction), from its placement or its Elevation attribute (extraction.hpp: storeyLevels).
#include "extraction.hpp"

#include <cmath>
#include <cstdio>

namespace bimloc::bim::detail {
namespace {

// Closer than this, a placement's height and an Elevation are the same level (a millimetre:
// the plans write levels to it; Jesse.1 writes -2.0e-11 m for its level 0).
constexpr double kSameLevelM = 1e-3;
// No floor lies farther from sea level than this (the highest sites and deepest mines are a
// few kilometres): a height beyond it is damage, and beyond a float's range the simulator's
// ray caster aborts on it (a storey written at Elevation -1e300).
constexpr double kFarthestLevelM = 1e4;

bool usable(double z) { return std::isfinite(z) && std::abs(z) <= kFarthestLevelM; }

std::string metres(double v) {
  char text[40];
  std::snprintf(text, sizeof text, std::abs(v) < 1e6 ? "%.3f m" : "%.3g m", v);  // millimetres, or the damage's size
  return text;
}

}  // namespace

std::vector<StoreyLevel> storeyLevels(const RawModel& raw, std::vector<std::string>& warnings) {
  // IFC positions a storey, as every product, by its ObjectPlacement: the walls' and spaces'
  // placements hang from it, so its world height is the level in the walls' own frame.
  // Elevation is the same level "relative to the building's base", a frame the file does not
  // tie to the geometry: where the site or the building is placed above the world's origin
  // (a site at its height above sea level: ifc-lite's mapped_instances_site_rotated places its
  // site 300 m up, its storey's Elevation says 0), Elevation puts the floor below the walls,
  // and the robot fell through the plan's world. Every shared plan has both equal.
  // Where both agree within a millimetre, Elevation is kept (the level as written, without the
  // placement chain's rounding: every plan read before this rule reads the same). Elevation
  // also stands where the placements do not carry the levels: not finite, or two storeys at
  // one placement height that their Elevations tell apart.
  bool placements_carry_levels = true;
  for (std::size_t a = 0; a < raw.storeys.size(); ++a) {
    const RawStorey& s = raw.storeys[a];
    if (!usable(s.placement_z_m)) placements_carry_levels = false;
    for (std::size_t b = a + 1; b < raw.storeys.size(); ++b) {
      const RawStorey& t = raw.storeys[b];
      if (s.elevation_m && t.elevation_m && usable(*s.elevation_m) && usable(*t.elevation_m) &&
          std::abs(s.placement_z_m - t.placement_z_m) < kSameLevelM &&
          std::abs(*s.elevation_m - *t.elevation_m) >= kSameLevelM)
        placements_carry_levels = false;
    }
  }
  std::vector<StoreyLevel> levels;
  levels.reserve(raw.storeys.size());
  for (const RawStorey& s : raw.storeys) {
    const std::string storey = "IfcBuildingStorey #" + std::to_string(s.entity_id) + " " + s.global_id + " '" + s.name + "'";
    const bool has_elevation = s.elevation_m && usable(*s.elevation_m);
    if (s.elevation_m && !has_elevation)
      warnings.push_back(storey + ": Elevation " + metres(*s.elevation_m) + " is no floor's height: ignored");
    StoreyLevel level;
    if (has_elevation && usable(s.placement_z_m) && std::abs(*s.elevation_m - s.placement_z_m) < kSameLevelM) {
      level = {*s.elevation_m, "Elevation"};  // the same level: the one written, free of the chain's rounding
    } else if (usable(s.placement_z_m) && (placements_carry_levels || !has_elevation)) {
      level = {s.placement_z_m, "placement"};
      if (has_elevation && std::abs(*s.elevation_m - s.placement_z_m) >= kSameLevelM)
        warnings.push_back(storey + ": Elevation " + metres(*s.elevation_m) + ", placed at " + metres(s.placement_z_m) +
                           " in the geometry's frame: the placement's height is used");
    } else if (has_elevation) {
      level = {*s.elevation_m, "Elevation"};
    } else {
      level = {0.0, "none"};
      warnings.push_back(storey + ": neither its Elevation nor its placement gives a floor's height: 0 m is used");
    }
    levels.push_back(level);
  }
  return levels;
}

}  // namespace bimloc::bim::detail
