// A storey's site mesh, composed from the plan's mesh element by element: each element kept,
// dropped, moved (a rigid motion) or glazed (into the storey's GlassLayer), and boxes added
// (door leaves, partitions). Elements left alone keep their bytes: with nothing changed but
// the doors dropped, the mesh is exactly the one the plan's extraction makes without doors.
#pragma once

#include "sim/world/glass_layer.hpp"
#include "sim/world/world_impl.hpp"

#include <Eigen/Geometry>

namespace bimloc::sim {

struct PartEdit {
  bool drop = false;
  bool moved = false;
  Eigen::Affine3d transform = Eigen::Affine3d::Identity();  // applied when moved
  float pass_fraction = 0.0f;  // > 0: into the glass layer, passing that fraction of the rays
};

struct ComposedStorey {
  bim::TriangleMesh mesh;              // opaque
  std::vector<bim::MeshPart> parts;    // of `mesh`
  GlassLayer glass;
};

ComposedStorey composeStorey(const PlanStorey& plan, const std::vector<PartEdit>& edits);

// A box on the segment a -> b (XY), `thickness_m` across it, from z0 to z1, appended as a part.
void appendBox(ComposedStorey& storey, const std::string& id, const std::string& ifc_class, const Eigen::Vector2d& a,
               const Eigen::Vector2d& b, double thickness_m, double z0, double z1);

// Is the part a door (IfcDoor, IfcDoorStandardCase)? Glazed class of a part (IfcWindow,
// IfcCurtainWall, IfcPlate, by prefix: IfcWindowStandardCase is an IfcWindow), or "".
bool isDoorPart(const bim::MeshPart& part);
std::string glassClass(const bim::MeshPart& part);

}  // namespace bimloc::sim
