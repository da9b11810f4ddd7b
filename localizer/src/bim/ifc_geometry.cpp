// The only translation unit that includes IFC++: it is slow to compile, so everything else
// works on the RawModel it produces.
#include "ifc_geometry.hpp"

#include "extraction.hpp"
#include "utf8.hpp"

#include <bimloc/bim/ifc_reader.hpp>

#include <ifcpp/IFC4/include/IfcBuildingStorey.h>
#include <ifcpp/IFC4/include/IfcFeatureElement.h>
#include <ifcpp/IFC4/include/IfcGloballyUniqueId.h>
#include <ifcpp/IFC4/include/IfcInteger.h>
#include <ifcpp/IFC4/include/IfcLabel.h>
#include <ifcpp/IFC4/include/IfcLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcPositiveLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcRamp.h>
#include <ifcpp/IFC4/include/IfcRelAggregates.h>
#include <ifcpp/IFC4/include/IfcRelContainedInSpatialStructure.h>
#include <ifcpp/IFC4/include/IfcRelSpaceBoundary.h>
#include <ifcpp/IFC4/include/IfcRelVoidsElement.h>
#include <ifcpp/IFC4/include/IfcSlab.h>
#include <ifcpp/IFC4/include/IfcSlabTypeEnum.h>
#include <ifcpp/IFC4/include/IfcSpace.h>
#include <ifcpp/IFC4/include/IfcStair.h>
#include <ifcpp/IFC4/include/IfcStairFlight.h>
#include <ifcpp/IFC4/include/IfcVirtualElement.h>
#include <ifcpp/IFC4/include/IfcWall.h>
#include <ifcpp/geometry/Carve/GeometryConverter.h>
#include <ifcpp/model/BuildingModel.h>
#include <ifcpp/model/UnitConverter.h>
#include <ifcpp/reader/ReaderSTEP.h>

#include "ifc_profile.hpp"
#include "ifc_references.hpp"
#include "map_origin.hpp"
#include "own_opening_cuts.hpp"
#include "spatial_cycles.hpp"

#include <carve/triangulator.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace bimloc::bim::detail {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// IFC++ reports problems through a callback; keep the errors, drop the chatter.
struct MessageSink {
  std::vector<std::string> errors;
  static void collect(void* self, shared_ptr<StatusCallback::Message> m) {
    if (!m || m->m_message_type != StatusCallback::MESSAGE_TYPE_ERROR) return;
    auto* sink = static_cast<MessageSink*>(self);
    if (sink->errors.size() < 1000) sink->errors.push_back(utf8(m->m_message_text));
  }
};

std::string label(const shared_ptr<IfcLabel>& l) { return l ? utf8(l->m_value) : std::string(); }

std::string globalId(const shared_ptr<IfcRoot>& root) {
  return root && root->m_GlobalId ? utf8(root->m_GlobalId->m_value) : std::string();
}

// Maps every object to the spatial element or object that contains or aggregates it.
std::unordered_map<int, int> parentMap(const BuildingModel& model) {
  std::unordered_map<int, int> parent;
  for (const auto& [id, entity] : model.getMapIfcEntities()) {
    if (auto rel = dynamic_pointer_cast<IfcRelContainedInSpatialStructure>(entity)) {
      if (!rel->m_RelatingStructure) continue;
      for (const auto& element : rel->m_RelatedElements)
        if (element) parent.emplace(element->m_entity_id, rel->m_RelatingStructure->m_entity_id);
    } else if (auto agg = dynamic_pointer_cast<IfcRelAggregates>(entity)) {
      if (!agg->m_RelatingObject) continue;
      for (const auto& object : agg->m_RelatedObjects)
        if (object) parent.emplace(object->m_entity_id, agg->m_RelatingObject->m_entity_id);
    }
  }
  return parent;
}

// Maps every part to the element it makes up (IfcRelAggregates between elements: a curtain
// wall and its plates and members, IFC4 IfcCurtainWall "decomposition").
std::unordered_map<int, int> wholeMap(const BuildingModel& model) {
  std::unordered_map<int, int> whole;
  for (const auto& [id, entity] : model.getMapIfcEntities())
    if (auto agg = dynamic_pointer_cast<IfcRelAggregates>(entity)) {
      if (!dynamic_pointer_cast<IfcElement>(agg->m_RelatingObject)) continue;
      for (const auto& object : agg->m_RelatedObjects)
        if (object) whole.emplace(object->m_entity_id, agg->m_RelatingObject->m_entity_id);
    }
  return whole;
}

int storeyOf(int entity_id, const std::unordered_map<int, int>& parent,
             const std::unordered_map<int, int>& storey_index) {
  for (int hops = 0; hops < 64; ++hops) {  // bounded: a broken file may hold a cycle
    if (auto s = storey_index.find(entity_id); s != storey_index.end()) return s->second;
    auto p = parent.find(entity_id);
    if (p == parent.end()) return -1;
    entity_id = p->second;
  }
  return -1;
}

Eigen::Vector3d toWorld(const carve::math::Matrix& T, const carve::geom::vector<3>& v) {
  const carve::geom::vector<3> w = T * v;
  return {w.x, w.y, w.z};
}

// Carve orders the vertices of a face by heap address, which changes from run to run (ASLR):
// start every face at its smallest vertex, so that the same face is cut into the same triangles.
std::size_t canonicalStart(const std::vector<Eigen::Vector3f>& corners) {
  const std::size_t n = corners.size();
  const auto less = [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::size_t best = 0;
  for (std::size_t i = 1; i < n; ++i)
    for (std::size_t k = 0; k < n; ++k) {  // compare the rotations starting at i and at best
      const auto& a = corners[(i + k) % n];
      const auto& b = corners[(best + k) % n];
      if (less(a, b)) {
        best = i;
        break;
      }
      if (less(b, a)) break;
    }
  return best;
}

// The polygon in the coordinate plane its normal (Newell) is closest to, counter-clockwise.
std::vector<carve::geom2d::P2> projectOnFace(const std::vector<Eigen::Vector3f>& corners) {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < corners.size(); ++i)
    normal += corners[i].cast<double>().cross(corners[(i + 1) % corners.size()].cast<double>());
  int axis = 0;
  normal.cwiseAbs().maxCoeff(&axis);
  int u = (axis + 1) % 3, v = (axis + 2) % 3;
  if (normal[axis] < 0) std::swap(u, v);
  std::vector<carve::geom2d::P2> projected;
  for (const auto& c : corners) projected.push_back(carve::geom::VECTOR(double(c[u]), double(c[v])));
  return projected;
}

void appendMeshSet(const carve::mesh::MeshSet<3>& meshset, const carve::math::Matrix& T, TriangleMesh& out) {
  for (const auto* mesh : meshset.meshes) {
    for (const auto* face : mesh->faces) {
      std::vector<Eigen::Vector3f> corners;
      const auto* e = face->edge;
      for (size_t i = 0; i < face->nVertices(); ++i, e = e->next)
        corners.push_back(toWorld(T, e->vert->v).cast<float>() + Eigen::Vector3f::Zero());  // -0 -> +0
      if (corners.size() < 3) continue;
      const std::size_t start = canonicalStart(corners);
      std::rotate(corners.begin(), corners.begin() + static_cast<std::ptrdiff_t>(start), corners.end());
      const auto base = static_cast<std::uint32_t>(out.vertices.size());
      out.vertices.insert(out.vertices.end(), corners.begin(), corners.end());
      if (corners.size() == 3) {
        out.triangles.push_back({base, base + 1, base + 2});
        continue;
      }
      // Faces after CSG may be non-convex polygons: ear-clip them in the face's own plane,
      // projected from the float corners we write (not carve's doubles, whose last bits vary
      // with the order of the CSG: nearly collinear corners then clip differently).
      const std::vector<carve::geom2d::P2> projected = projectOnFace(corners);
      std::vector<carve::triangulate::tri_idx> tris;
      try {
        carve::triangulate::triangulate(projected, tris);
      } catch (...) {
        tris.clear();
        for (std::uint32_t i = 1; i + 1 < corners.size(); ++i) tris.push_back({0, i, i + 1});
      }
      for (const auto& t : tris)
        out.triangles.push_back({base + static_cast<std::uint32_t>(t.a), base + static_cast<std::uint32_t>(t.b),
                                 base + static_cast<std::uint32_t>(t.c)});
    }
  }
}

// The product's body in world coordinates. Prefers the 'Body' representation; other
// representations (Box, FootPrint, Axis) are only used when there is no body at all.
TriangleMesh worldMesh(ProductShapeData& shape) {
  const carve::math::Matrix T = shape.getTransform();
  TriangleMesh body, other;
  for (const auto& rep : shape.m_vec_representations) {
    if (!rep) continue;
    const bool is_body = rep->m_representation_identifier == L"Body" || rep->m_representation_identifier.empty();
    TriangleMesh& target = is_body ? body : other;
    for (const auto& item : rep->m_vec_item_data) {
      if (!item) continue;
      for (const auto& ms : item->m_meshsets)
        if (ms) appendMeshSet(*ms, T, target);
      for (const auto& ms : item->m_meshsets_open)
        if (ms) appendMeshSet(*ms, T, target);
    }
  }
  TriangleMesh& mesh = body.empty() ? other : body;
  canonicalSurface(mesh);  // carve's faces, and their splits, follow heap addresses
  return std::move(mesh);
}

RawProduct makeProduct(const shared_ptr<IfcProduct>& product, ProductShapeData& shape, int storey) {
  RawProduct raw;
  raw.entity_id = product->m_entity_id;
  raw.global_id = globalId(product);
  raw.name = label(product->m_Name);
  raw.ifc_class = product->className();
  raw.storey = storey;
  raw.mesh = worldMesh(shape);
  return raw;
}

// The stair-related attributes of a product: a slab's PredefinedType (LANDING marks a stair's
// landing), a stair flight's numbers (IFC++ reads IFC2X3's NumberOfRiser into the IFC4 field).
void readStairAttributes(const shared_ptr<IfcProduct>& product, double length_unit_m, RawProduct& raw) {
  if (auto slab = dynamic_pointer_cast<IfcSlab>(product); slab && slab->m_PredefinedType)
    raw.predefined_type = utf8(slab->m_PredefinedType->toString());
  auto flight = dynamic_pointer_cast<IfcStairFlight>(product);
  if (!flight) return;
  FlightAttributes a;
  if (flight->m_NumberOfRisers) a.risers = flight->m_NumberOfRisers->m_value;
  if (flight->m_NumberOfTreads) a.treads = flight->m_NumberOfTreads->m_value;
  if (flight->m_RiserHeight) a.riser_height_m = flight->m_RiserHeight->m_value * length_unit_m;
  if (flight->m_TreadLength) a.tread_length_m = flight->m_TreadLength->m_value * length_unit_m;
  raw.flight = a;
}

}  // namespace

RawModel readRawModel(const PlanText& plan, const std::string& path) {
  RawModel raw;
  raw.schema = plan.schema;
  MessageSink sink;

  const auto t_parse = Clock::now();
  shared_ptr<BuildingModel> model(new BuildingModel());
  shared_ptr<ReaderSTEP> reader(new ReaderSTEP());
  reader->setMessageCallBack(&sink, &MessageSink::collect);
  model->setMessageCallBack(&sink, &MessageSink::collect);
  try {
    std::string text = plan.text;  // IFC++ edits the buffer in place
    reader->loadModelFromString(text, model);
  } catch (const std::exception& e) {
    throw BimError(path + ": IFC parse error: " + e.what());
  }
  if (model->getMapIfcEntities().empty())
    throw BimError(path + ": no IFC entities could be read" +
                   (sink.errors.empty() ? std::string() : " (" + sink.errors.front() + ")"));
  raw.length_unit_m = model->getUnitConverter() ? model->getUnitConverter()->getLengthInMeterFactor() : 1.0;
  raw.parse_s = secondsSince(t_parse);

  const auto t_geometry = Clock::now();
  // References of the wrong type would crash the converter: drop what reaches them first.
  const ReferenceCheck references(*model, scanStep(plan.text));
  raw.warnings = plan.warnings;
  raw.warnings.insert(raw.warnings.end(), references.warnings().begin(), references.warnings().end());
  const std::map<int, GeometryDrop> drops = dropUnreadableGeometry(*model, references);
  // A cycle in the spatial structure would send the converter into endless recursion.
  for (auto& w : breakSpatialCycles(*model)) raw.warnings.push_back(std::move(w));
  // A georeferenced site, far from the origin, moved near it (map_origin.hpp).
  raw.map_origin_in_plan_m = moveRootsNearOrigin(*model, raw.length_unit_m, raw.warnings);
  GeometryConverter converter(model);
  converter.setMessageCallBack(&sink, &MessageSink::collect);
  // Colours and layers are not needed, and are reached through inverse links the check skips.
  converter.getGeomSettings()->setHandleStyledItems(false);
  converter.getGeomSettings()->setHandleLayerAssignments(false);
  ProfileReader profiles(converter.getRepresentationConverter()->getPlacementConverter(), raw.length_unit_m);
  {
    // Openings we cut ourselves (rebuiltBodies) are kept from IFC++'s cut, quadratic in one
    // wall's openings (own_opening_cuts.hpp); attached again when the conversion is done.
    const OwnOpeningCuts own_cuts(*model, profiles);
    raw.openings_left_to_us = own_cuts.elements();
    try {
      converter.convertGeometry();
    } catch (const std::exception& e) {
      raw.warnings.push_back(std::string("geometry conversion stopped early: ") + e.what());
    } catch (...) {
      raw.warnings.push_back("geometry conversion stopped early: unknown error");
    }
  }
  const auto parent = parentMap(*model);
  const auto whole = wholeMap(*model);

  // Storeys first: every product is filed under one of them.
  std::unordered_map<int, int> storey_index;
  auto& shapes = converter.getShapeInputData();
  for (const auto& [id, entity] : model->getMapIfcEntities()) {
    auto storey = dynamic_pointer_cast<IfcBuildingStorey>(entity);
    if (!storey) continue;
    RawStorey s;
    s.entity_id = id;
    s.global_id = globalId(storey);
    s.name = label(storey->m_Name);
    if (storey->m_Elevation) s.elevation_m = storey->m_Elevation->m_value * raw.length_unit_m;
    if (s.elevation_m && !std::isfinite(*s.elevation_m)) {
      raw.warnings.push_back("IfcBuildingStorey #" + std::to_string(id) + " " + s.global_id + " '" + s.name +
                             "': Elevation is not a finite number: the placement's height is used");
      s.elevation_m.reset();
    }
    if (const auto drop = drops.find(id); drop != drops.end())
      raw.warnings.push_back("IfcBuildingStorey #" + std::to_string(id) + " " + s.global_id + " '" + s.name + "': placement ignored: " +
                             drop->second.reason);
    s.placement_z_m = profiles.placementOrigin(storey->m_ObjectPlacement).z();
    storey_index[id] = static_cast<int>(raw.storeys.size());
    raw.storeys.push_back(s);
  }

  for (auto& [id, shape] : shapes) {
    if (!shape) continue;
    auto product = dynamic_pointer_cast<IfcProduct>(shape->m_ifc_object_definition.lock());
    if (!product) continue;
    const bool is_wall = dynamic_pointer_cast<IfcWall>(product) != nullptr;
    const bool is_space = dynamic_pointer_cast<IfcSpace>(product) != nullptr;
    const bool is_element = dynamic_pointer_cast<IfcElement>(product) &&
                            !dynamic_pointer_cast<IfcFeatureElement>(product) &&
                            !dynamic_pointer_cast<IfcVirtualElement>(product);
    if (!is_wall && !is_space && !is_element) continue;
    RawProduct p = makeProduct(product, *shape, storeyOf(id, parent, storey_index));
    if (const auto w = whole.find(id); w != whole.end()) p.whole_entity_id = w->second;
    const auto drop = drops.find(id);
    if (drop != drops.end() && (drop->second.all ? !is_wall && !is_space : true))
      raw.warnings.push_back(describeProduct(p) + (drop->second.all ? ": geometry skipped: " : ": ignored ") +
                             drop->second.reason);
    if (drop != drops.end() && drop->second.all) {
      p.geometry_problem = "geometry cannot be read: " + drop->second.reason;
    } else if (p.mesh.empty() || is_space) {
      // The converter skips some bodies (e.g. profiles over IfcIndexedPolyCurve): read the
      // extrusion ourselves. Spaces always: their profile is the exact room footprint.
      p.extrusion = profiles.bodyExtrusion(product, p.geometry_problem);
    } else if (!is_space && profiles.bodyIsOneExtrusion(product)) {
      std::string unread;  // p has its mesh: nothing to say
      p.sole_body = profiles.bodyExtrusion(product, unread);
    }
    if (is_space) p.long_name = label(dynamic_pointer_cast<IfcSpace>(product)->m_LongName);
    readStairAttributes(product, raw.length_unit_m, p);
    if (is_wall) raw.walls.push_back(std::move(p));
    else if (is_space) raw.spaces.push_back(std::move(p));
    else raw.elements.push_back(std::move(p));
  }

  // Stairs and ramps, with or without a body of their own (Revit's have none: their flights do).
  for (const auto& [id, entity] : model->getMapIfcEntities()) {
    auto element = dynamic_pointer_cast<IfcElement>(entity);
    if (!element || (!dynamic_pointer_cast<IfcStair>(element) && !dynamic_pointer_cast<IfcRamp>(element))) continue;
    RawProduct p;
    p.entity_id = id;
    p.global_id = globalId(element);
    p.name = label(element->m_Name);
    p.ifc_class = element->className();
    p.storey = storeyOf(id, parent, storey_index);
    raw.stairs.push_back(std::move(p));
  }
  std::sort(raw.stairs.begin(), raw.stairs.end(),
            [](const RawProduct& a, const RawProduct& b) { return a.entity_id < b.entity_id; });

  // Openings of the elements rebuilt from their extrusions (no IFC++ mesh), and of those whose
  // body is one extruded solid (openings.hpp cuts them again, exactly and the same every run).
  std::unordered_set<int> rebuilt;
  for (const auto* group : {&raw.walls, &raw.elements})
    for (const auto& p : *group)
      if ((p.mesh.empty() && p.extrusion) || p.sole_body) rebuilt.insert(p.entity_id);
  for (const auto& [id, entity] : model->getMapIfcEntities()) {
    auto rel = dynamic_pointer_cast<IfcRelVoidsElement>(entity);
    if (!rel || !rel->m_RelatingBuildingElement || !rel->m_RelatedOpeningElement) continue;
    if (!rebuilt.count(rel->m_RelatingBuildingElement->m_entity_id)) continue;
    const auto& opening = rel->m_RelatedOpeningElement;
    RawOpening o;
    o.global_id = globalId(opening);
    o.name = label(opening->m_Name);
    o.ifc_class = opening->className();
    o.voided_entity_id = rel->m_RelatingBuildingElement->m_entity_id;
    o.extrusion = profiles.bodyExtrusion(opening, o.geometry_problem);
    o.sole = o.extrusion && profiles.bodyIsOneExtrusion(opening);
    raw.openings.push_back(std::move(o));
  }

  for (const auto& [id, entity] : model->getMapIfcEntities()) {
    auto rel = dynamic_pointer_cast<IfcRelSpaceBoundary>(entity);
    if (!rel || !rel->m_RelatedBuildingElement) continue;
    auto space = dynamic_pointer_cast<IfcSpace>(rel->m_RelatingSpace);
    if (!space) continue;
    raw.space_boundaries.push_back({globalId(space), globalId(rel->m_RelatedBuildingElement)});
  }
  raw.geometry_s = secondsSince(t_geometry);
  return raw;
}

}  // namespace bimloc::bim::detail
