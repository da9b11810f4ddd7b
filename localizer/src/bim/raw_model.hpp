// The plan as read from IFC, before any interpretation: products with their world-frame
// geometry and the relations between them. Free of IFC++ types, so that everything after
// the reading (walls, rooms, topology, meshes) compiles fast and is testable on its own.
#pragma once

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::bim::detail {

// An extruded profile read from the IFC attributes, for the elements whose body the
// geometry converter could not mesh: footprint polygon in world XY and a z range.
struct Extrusion {
  std::vector<Eigen::Vector2d> footprint;  // the profile's outline at the base, world XY
  std::vector<Eigen::Vector3d> corners;    // every corner of the prism, world frame
  double z_min = 0.0;
  double z_max = 0.0;
  bool vertical = true;  // extruded along world z
};

// What an IfcStairFlight says of itself (IFC2X3 NumberOfRiser, NumberOfTreads, RiserHeight,
// TreadLength; IFC4 NumberOfRisers, ...), lengths converted with the file's unit. Unchecked:
// exporters write nonsense here too (Revit writes feet into metre and millimetre files).
struct FlightAttributes {
  std::optional<int> risers, treads;
  std::optional<double> riser_height_m, tread_length_m;
};

struct RawProduct {
  int entity_id = 0;
  std::string global_id;
  std::string name;
  std::string long_name;  // IfcSpace only
  std::string ifc_class;  // e.g. IfcWallStandardCase
  int storey = -1;        // index into RawModel::storeys, -1 when outside the spatial tree
  int whole_entity_id = 0;  // the element it is a part of (IfcRelAggregates), 0 when none:
                            // a curtain wall's plates and members (IFC4 IfcCurtainWall)
  TriangleMesh mesh;      // world frame, metres
  std::optional<Extrusion> extrusion;
  // The Body representation when it is exactly one extruded solid (no clipping, no other
  // item), read for an element with openings whatever IFC++ made of it: openings.hpp cuts
  // them from it exactly (IFC++'s CSG cuts a different subset of them from run to run).
  std::optional<Extrusion> sole_body;
  std::string geometry_problem;  // why there is neither mesh nor extrusion
  std::string predefined_type;   // IfcSlab's PredefinedType (LANDING, FLOOR, ...), else empty
  std::optional<FlightAttributes> flight;  // IfcStairFlight only
};

// How a warning names a product: its class, its instance id in the file, its GlobalId and name
// ("IfcWallStandardCase #361 2OPn9Eo7X5uQL7Jvq1iSyR 'Basic Wall'"), enough to find it in any viewer.
inline std::string describeProduct(const RawProduct& p) {
  return p.ifc_class + " #" + std::to_string(p.entity_id) + " " + p.global_id + (p.name.empty() ? "" : " '" + p.name + "'");
}

struct RawStorey {
  int entity_id = 0;
  std::string global_id;
  std::string name;
  std::optional<double> elevation_m;  // the Elevation attribute, when set
  double placement_z_m = 0.0;         // world z of the storey's placement
};

// A void cut into an element (IfcRelVoidsElement): IFC++ subtracts it from the meshes it makes;
// the bodies we rebuild from their extrusions need it subtracted by us (openings.cpp).
struct RawOpening {
  std::string global_id;
  std::string name;
  std::string ifc_class;  // IfcOpeningElement, IfcVoidingFeature, ...
  int voided_entity_id = 0;             // RawProduct::entity_id of the element it cuts
  std::optional<Extrusion> extrusion;   // its body, world frame; read only for rebuilt elements
  bool sole = false;                    // the body is exactly that one extruded solid
  std::string geometry_problem;         // why there is no extrusion
};

struct SpaceBoundary {
  std::string space_id;    // GlobalId of the IfcSpace
  std::string element_id;  // GlobalId of the bounding element
};

struct RawModel {
  std::string schema;
  double length_unit_m = 1.0;
  Eigen::Vector2d map_origin_in_plan_m = Eigen::Vector2d::Zero();  // map_origin.hpp
  std::vector<RawStorey> storeys;
  std::vector<RawProduct> walls;     // IfcWall and subtypes (curtain walls excluded)
  std::vector<RawProduct> spaces;    // IfcSpace
  std::vector<RawProduct> elements;  // every other physical element, for the storey meshes
  std::vector<SpaceBoundary> space_boundaries;
  // Every IfcStair and IfcRamp, body or not (their bodies, if any, are in `elements` too; their
  // flights and landings are the elements whose whole_entity_id is theirs).
  std::vector<RawProduct> stairs;
  std::vector<RawOpening> openings;  // those of the elements that have no IFC++ mesh
  // The elements whose openings IFC++ was not asked to cut (own_opening_cuts.hpp): their mesh
  // is the uncut body, and rebuiltBodies must cut them (it names any it cannot).
  std::vector<int> openings_left_to_us;
  std::vector<std::string> warnings;
  double parse_s = 0.0;
  double geometry_s = 0.0;
};

}  // namespace bimloc::bim::detail
