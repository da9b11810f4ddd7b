// Reads a product's body straight from its IFC attributes (placement, extruded profile),
// for the bodies IFC++'s geometry converter leaves empty: ExampleHOM's walls are extrusions
// of IfcArbitraryClosedProfileDef over an IfcIndexedPolyCurve, which it skips.
// Header-only on purpose: included by ifc_geometry.cpp alone, the one IFC++ translation unit.
#pragma once

#include "raw_model.hpp"

#include <ifcpp/IFC4/include/IfcArbitraryClosedProfileDef.h>
#include <ifcpp/IFC4/include/IfcAxis2Placement2D.h>
#include <ifcpp/IFC4/include/IfcAxis2Placement3D.h>
#include <ifcpp/IFC4/include/IfcBooleanResult.h>
#include <ifcpp/IFC4/include/IfcCartesianPoint.h>
#include <ifcpp/IFC4/include/IfcCartesianPointList2D.h>
#include <ifcpp/IFC4/include/IfcCartesianPointList3D.h>
#include <ifcpp/IFC4/include/IfcDirection.h>
#include <ifcpp/IFC4/include/IfcExtrudedAreaSolid.h>
#include <ifcpp/IFC4/include/IfcIndexedPolyCurve.h>
#include <ifcpp/IFC4/include/IfcLabel.h>
#include <ifcpp/IFC4/include/IfcLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcMappedItem.h>
#include <ifcpp/IFC4/include/IfcPolyline.h>
#include <ifcpp/IFC4/include/IfcPositiveLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcProduct.h>
#include <ifcpp/IFC4/include/IfcProductRepresentation.h>
#include <ifcpp/IFC4/include/IfcReal.h>
#include <ifcpp/IFC4/include/IfcRectangleProfileDef.h>
#include <ifcpp/IFC4/include/IfcRepresentation.h>
#include <ifcpp/IFC4/include/IfcRepresentationMap.h>
#include <ifcpp/IFC4/include/IfcCartesianTransformationOperator.h>
#include <ifcpp/geometry/Carve/PlacementConverter.h>

#include <optional>
#include <string>

namespace bimloc::bim::detail {

class ProfileReader {
 public:
  ProfileReader(shared_ptr<PlacementConverter> placements, double length_unit_m)
      : placements_(std::move(placements)), unit_m_(length_unit_m) {}

  // World transform of an object placement (translation in metres).
  carve::math::Matrix placementMatrix(const shared_ptr<IfcObjectPlacement>& placement) const {
    if (!placement) return carve::math::Matrix();
    shared_ptr<ProductShapeData> holder(new ProductShapeData(0));
    std::unordered_set<IfcObjectPlacement*> applied;
    placements_->convertIfcObjectPlacement(placement, holder, applied, false);
    return holder->getTransform();
  }

  Eigen::Vector3d placementOrigin(const shared_ptr<IfcObjectPlacement>& placement) const {
    const auto o = placementMatrix(placement) * carve::geom::VECTOR(0.0, 0.0, 0.0);
    return {o.x, o.y, o.z};
  }

  // Whether the product's 'Body' representation is exactly one extruded solid, directly (no
  // boolean clipping, no mapped item, no other item): then bodyExtrusion is the whole body.
  bool bodyIsOneExtrusion(const shared_ptr<IfcProduct>& product) const {
    if (!product->m_Representation) return false;
    std::size_t items = 0;
    bool solid = false;
    for (const auto& rep : product->m_Representation->m_Representations) {
      if (!rep || !rep->m_RepresentationIdentifier || rep->m_RepresentationIdentifier->m_value != L"Body") continue;
      for (const auto& item : rep->m_Items) {
        ++items;
        solid = static_cast<bool>(dynamic_pointer_cast<IfcExtrudedAreaSolid>(item));
      }
    }
    return items == 1 && solid;
  }

  // The first extruded solid of the product's 'Body' representation, in world coordinates.
  // Returns nothing and says why in `problem` when there is none it can read.
  std::optional<Extrusion> bodyExtrusion(const shared_ptr<IfcProduct>& product, std::string& problem) const {
    carve::math::Matrix item_transform;  // of a mapped item (BlenderBIM's openings), else identity
    shared_ptr<IfcExtrudedAreaSolid> solid = findBodySolid(product, item_transform);
    if (!solid) {
      problem = "no extruded solid in its Body representation";
      return std::nullopt;
    }
    std::vector<Eigen::Vector2d> profile = profilePoints(solid->m_SweptArea);
    if (profile.size() < 3) {
      problem = "unsupported or empty profile in its Body extrusion";
      return std::nullopt;
    }
    if (!solid->m_Depth || !solid->m_ExtrudedDirection || solid->m_ExtrudedDirection->m_DirectionRatios.size() < 3) {
      problem = "extrusion without depth or direction";
      return std::nullopt;
    }
    const auto& ratios = solid->m_ExtrudedDirection->m_DirectionRatios;
    carve::geom::vector<3> dir = carve::geom::VECTOR(value(ratios[0]), value(ratios[1]), value(ratios[2]));
    if (dir.length() < 1e-9) {
      problem = "extrusion direction of zero length";
      return std::nullopt;
    }
    dir.normalize();
    const double depth = solid->m_Depth->m_value * unit_m_;

    carve::math::Matrix T = placementMatrix(product->m_ObjectPlacement) * item_transform;
    if (solid->m_Position) {
      shared_ptr<TransformData> position;
      placements_->convertIfcAxis2Placement3D(solid->m_Position, position);
      if (position) T = T * position->m_matrix;
    }
    Extrusion out;
    out.z_min = std::numeric_limits<double>::infinity();
    out.z_max = -out.z_min;
    for (const auto& p : profile) {
      const auto bottom = T * carve::geom::VECTOR(p.x(), p.y(), 0.0);
      const auto top = T * (carve::geom::VECTOR(p.x(), p.y(), 0.0) + dir * depth);
      out.footprint.emplace_back(bottom.x, bottom.y);
      out.corners.emplace_back(bottom.x, bottom.y, bottom.z);
      out.corners.emplace_back(top.x, top.y, top.z);
      out.z_min = std::min({out.z_min, bottom.z, top.z});
      out.z_max = std::max({out.z_max, bottom.z, top.z});
    }
    const auto up = T * dir - T * carve::geom::VECTOR(0.0, 0.0, 0.0);
    out.vertical = std::abs(up.z) > 0.999 * up.length();
    return out;
  }

 private:
  static double value(const shared_ptr<IfcReal>& r) { return r ? r->m_value : 0.0; }
  static double value(const shared_ptr<IfcLengthMeasure>& r) { return r ? r->m_value : 0.0; }

  // The extruded solid of a representation item; `transform` accumulates the mapping of
  // mapped items (IFC++'s convention: MappingTarget * MappingOrigin).
  shared_ptr<IfcExtrudedAreaSolid> unwrap(const shared_ptr<IfcRepresentationItem>& item, carve::math::Matrix& transform,
                                          int depth = 0) const {
    if (!item || depth > 16) return nullptr;  // bounded: a broken file may hold a cycle
    if (auto solid = dynamic_pointer_cast<IfcExtrudedAreaSolid>(item)) return solid;
    // Clipped walls (under a roof) keep their extrusion as the first operand.
    if (auto boolean = dynamic_pointer_cast<IfcBooleanResult>(item))
      return unwrap(dynamic_pointer_cast<IfcRepresentationItem>(boolean->m_FirstOperand), transform, depth + 1);
    if (auto mapped = dynamic_pointer_cast<IfcMappedItem>(item)) {
      const auto& source = mapped->m_MappingSource;
      if (!source || !source->m_MappedRepresentation) return nullptr;
      carve::math::Matrix mapping;
      if (mapped->m_MappingTarget) {
        shared_ptr<TransformData> target;
        placements_->convertTransformationOperator(mapped->m_MappingTarget, target);
        if (target) mapping = target->m_matrix;
      }
      if (auto origin = dynamic_pointer_cast<IfcPlacement>(source->m_MappingOrigin)) {
        shared_ptr<TransformData> placement;
        placements_->convertIfcPlacement(origin, placement);
        if (placement) mapping = mapping * placement->m_matrix;
      }
      for (const auto& inner : source->m_MappedRepresentation->m_Items) {
        carve::math::Matrix inner_transform = transform * mapping;
        if (auto solid = unwrap(inner, inner_transform, depth + 1)) {
          transform = inner_transform;
          return solid;
        }
      }
    }
    return nullptr;
  }

  shared_ptr<IfcExtrudedAreaSolid> findBodySolid(const shared_ptr<IfcProduct>& product,
                                                 carve::math::Matrix& transform) const {
    if (!product->m_Representation) return nullptr;
    for (const auto& rep : product->m_Representation->m_Representations) {
      if (!rep || !rep->m_RepresentationIdentifier || rep->m_RepresentationIdentifier->m_value != L"Body") continue;
      for (const auto& item : rep->m_Items) {
        carve::math::Matrix item_transform;
        if (auto solid = unwrap(item, item_transform)) {
          transform = item_transform;
          return solid;
        }
      }
    }
    return nullptr;
  }

  // Profile outline in the solid's XY plane, metres. Arcs of an indexed poly curve are
  // replaced by the chords through their points (an approximation, fine for walls).
  std::vector<Eigen::Vector2d> profilePoints(const shared_ptr<IfcProfileDef>& profile) const {
    std::vector<Eigen::Vector2d> pts;
    if (auto rect = dynamic_pointer_cast<IfcRectangleProfileDef>(profile)) {
      if (!rect->m_XDim || !rect->m_YDim) return pts;
      const double hx = 0.5 * rect->m_XDim->m_value * unit_m_, hy = 0.5 * rect->m_YDim->m_value * unit_m_;
      carve::math::Matrix P;
      if (rect->m_Position) {
        shared_ptr<TransformData> position;
        placements_->convertIfcAxis2Placement2D(rect->m_Position, position);
        if (position) P = position->m_matrix;
      }
      for (const auto& c : {Eigen::Vector2d(-hx, -hy), Eigen::Vector2d(hx, -hy), Eigen::Vector2d(hx, hy), Eigen::Vector2d(-hx, hy)}) {
        const auto q = P * carve::geom::VECTOR(c.x(), c.y(), 0.0);
        pts.emplace_back(q.x, q.y);
      }
      return pts;
    }
    auto arbitrary = dynamic_pointer_cast<IfcArbitraryClosedProfileDef>(profile);
    if (!arbitrary) return pts;
    if (auto polyline = dynamic_pointer_cast<IfcPolyline>(arbitrary->m_OuterCurve)) {
      for (const auto& p : polyline->m_Points)
        if (p && p->m_Coordinates.size() >= 2)
          pts.emplace_back(value(p->m_Coordinates[0]) * unit_m_, value(p->m_Coordinates[1]) * unit_m_);
    } else if (auto indexed = dynamic_pointer_cast<IfcIndexedPolyCurve>(arbitrary->m_OuterCurve)) {
      if (auto list2 = dynamic_pointer_cast<IfcCartesianPointList2D>(indexed->m_Points)) {
        for (const auto& c : list2->m_CoordList)
          if (c.size() >= 2) pts.emplace_back(value(c[0]) * unit_m_, value(c[1]) * unit_m_);
      } else if (auto list3 = dynamic_pointer_cast<IfcCartesianPointList3D>(indexed->m_Points)) {
        for (const auto& c : list3->m_CoordList)
          if (c.size() >= 2) pts.emplace_back(value(c[0]) * unit_m_, value(c[1]) * unit_m_);
      }
    }
    // A closed curve repeats its first point at the end.
    if (pts.size() > 1 && (pts.front() - pts.back()).norm() < 1e-9) pts.pop_back();
    return pts;
  }

  shared_ptr<PlacementConverter> placements_;
  double unit_m_;
};

}  // namespace bimloc::bim::detail
