// Moves a georeferenced plan near the origin before its geometry is converted. Plans from
// surveyed sites place the IfcSite (or the building) at map coordinates (Swiss LV95
// 2 600 000 / 1 200 000 m, a UTM northing of 5 500 000 m): there a float, which the storey
// meshes and the ray caster use, holds 0.25-0.5 m, and IFC++'s boolean cuts lost whole walls
// (site_office placed at UTM coordinates: 3 of 16 walls "degenerate", its runs' ATE 0.115 m
// against 0.010 m). So the root placements (IfcLocalPlacement without PlacementRelTo) are
// moved by one horizontal offset, in whole metres, before the conversion (the first storey's
// place, or the walls' middle where they hang far from it): every product hangs from them, so
// the plan is the same plan, shifted. bimloc's map frame is then the plan's frame less that
// offset (Building::map_origin_in_plan_m, in building.json; REP 105's earth -> map). Heights
// are kept: a site 400 m above sea level is no problem for a float. A plan whose walls lie
// within kLocalFrameM of its origin is left exactly as it was.
// Header-only on purpose: included by ifc_geometry.cpp alone, the one IFC++ translation unit.
#pragma once

#include <ifcpp/IFC4/include/IfcAxis2Placement2D.h>
#include <ifcpp/IFC4/include/IfcAxis2Placement3D.h>
#include <ifcpp/IFC4/include/IfcBuildingStorey.h>
#include <ifcpp/IFC4/include/IfcCartesianPoint.h>
#include <ifcpp/IFC4/include/IfcWall.h>
#include <ifcpp/IFC4/include/IfcLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcLocalPlacement.h>
#include <ifcpp/geometry/Carve/PlacementConverter.h>
#include <ifcpp/model/BuildingModel.h>

#include "extraction.hpp"
#include "ifc_profile.hpp"

#include <Eigen/Core>

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace bimloc::bim::detail {

// Within this of the origin a float holds a millimetre (its step at 8 192 m is 0.98 mm).
constexpr double kLocalFrameM = 8192.0;

// Returns the offset taken off (plan frame, metres; zero when none) and says so in `warnings`.
inline Eigen::Vector2d moveRootsNearOrigin(BuildingModel& model, double length_unit_m, std::vector<std::string>& warnings) {
  std::vector<IfcLocalPlacement*> roots;
  // Where the building is: the first storey's placement in the world (the site's location, or
  // the building's under a site at the origin, as some exporters write a survey point); and
  // where its walls are, the median of their placements (a file may hang them from a far
  // placement under a storey at the origin).
  // IFC++'s own placement converter (ProfileReader), the one the geometry is converted with;
  // its origins are in metres.
  shared_ptr<PlacementConverter> converter(new PlacementConverter(model.getUnitConverter()));
  const ProfileReader places(converter, length_unit_m);
  std::optional<Eigen::Vector3d> storey_at;
  std::vector<Eigen::Vector2d> walls;
  for (const auto& [id, entity] : model.getMapIfcEntities()) {
    auto local = dynamic_pointer_cast<IfcLocalPlacement>(entity);
    if (local && !local->m_PlacementRelTo && dynamic_pointer_cast<IfcPlacement>(local->m_RelativePlacement))
      roots.push_back(local.get());
    if (auto storey = dynamic_pointer_cast<IfcBuildingStorey>(entity); storey && !storey_at && storey->m_ObjectPlacement)
      storey_at = places.placementOrigin(storey->m_ObjectPlacement);
    if (auto wall = dynamic_pointer_cast<IfcWall>(entity); wall && wall->m_ObjectPlacement)
      walls.push_back(places.placementOrigin(wall->m_ObjectPlacement).head<2>());
  }
  std::optional<Eigen::Vector2d> walls_at;
  if (std::any_of(walls.begin(), walls.end(), [](const Eigen::Vector2d& w) { return w.allFinite(); }))
    walls_at = planMiddle(walls);
  // The storey's place where its walls are near it (a whole-metre offset that is the survey
  // point's own), else the walls' middle; nothing to move where the walls are near the origin.
  Eigen::Vector2d at = walls_at ? *walls_at : storey_at ? Eigen::Vector2d(storey_at->head<2>()) : Eigen::Vector2d::Zero();
  if (walls_at && storey_at && storey_at->allFinite() && (storey_at->head<2>() - *walls_at).norm() <= kLocalFrameM)
    at = storey_at->head<2>();
  if (!at.allFinite()) return Eigen::Vector2d::Zero();
  // Whole metres: the map frame is the plan's less round numbers.
  const Eigen::Vector2d offset_m(std::round(at.x()), std::round(at.y()));
  if (!(offset_m.norm() > kLocalFrameM) || !(offset_m.norm() < 1e9)) return Eigen::Vector2d::Zero();
  for (IfcLocalPlacement* root : roots) {
    // A new location and a new placement for each root: both may be shared with placements
    // that are not roots (site_office's #4 is every wall's).
    auto old = dynamic_pointer_cast<IfcPlacement>(root->m_RelativePlacement);
    shared_ptr<IfcCartesianPoint> moved(new IfcCartesianPoint());
    const std::size_t dims = old->m_Location ? old->m_Location->m_Coordinates.size() : 0;
    for (std::size_t k = 0; k < std::max<std::size_t>(dims, 2); ++k) {
      const double v = k < dims && old->m_Location->m_Coordinates[k] ? old->m_Location->m_Coordinates[k]->m_value : 0.0;
      const double by = k == 0 ? offset_m.x() : k == 1 ? offset_m.y() : 0.0;
      moved->m_Coordinates.emplace_back(new IfcLengthMeasure(v - by / length_unit_m));
    }
    if (auto p3 = dynamic_pointer_cast<IfcAxis2Placement3D>(old)) {
      shared_ptr<IfcAxis2Placement3D> copy(new IfcAxis2Placement3D(*p3));
      copy->m_Location = moved;
      root->m_RelativePlacement = copy;
    } else if (auto p2 = dynamic_pointer_cast<IfcAxis2Placement2D>(old)) {
      shared_ptr<IfcAxis2Placement2D> copy(new IfcAxis2Placement2D(*p2));
      copy->m_Location = moved;
      root->m_RelativePlacement = copy;
    }
  }
  char text[200];
  std::snprintf(text, sizeof text,
                "the plan's building lies %.1f km from its origin: the map frame is the plan's moved by (%.0f, %.0f) m "
                "(building.json: map_origin_in_plan_m)",
                offset_m.norm() / 1000.0, -offset_m.x(), -offset_m.y());
  warnings.emplace_back(text);
  return offset_m;
}

}  // namespace bimloc::bim::detail
