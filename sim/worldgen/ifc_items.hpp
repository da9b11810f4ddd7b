// The IFC4 geometric items the writer builds products from: points, directions, placements,
// polylines, profiles, extrusions and shape representations. Each call appends the entity
// (and the items it needs) to the file and returns its id. Header-only: used by
// ifc4_writer.cpp alone.
#pragma once

#include "sim/worldgen/step_file.hpp"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace bimloc::worldgen::ifc {

using Eigen::Vector2d;
using Eigen::Vector3d;
using step::real;
using step::ref;
using step::refs;
using step::str;

// IfcRoot's first four attributes: GlobalId, OwnerHistory ($, allowed in IFC4), Name,
// Description.
inline std::vector<std::string> root(const std::string& quoted_id, const std::string& name,
                                     const std::string& description = {}) {
  return {quoted_id, step::unset(), name.empty() ? step::unset() : str(name),
          description.empty() ? step::unset() : str(description)};
}

inline std::vector<std::string> operator+(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// The file under construction and the items every product shares.
struct ItemWriter {
  step::File file;
  int dir_z = 0, dir_x = 0, origin_axes = 0;  // +z, +x, and the identity axes at the origin
  int body_context = 0, axis_context = 0;     // the 'Body' and 'Axis' subcontexts
};

inline int point2(ItemWriter& w, const Vector2d& p) {
  return w.file.add("IFCCARTESIANPOINT", {step::reals({p.x(), p.y()})});
}

inline int point3(ItemWriter& w, const Vector3d& p) {
  return w.file.add("IFCCARTESIANPOINT", {step::reals({p.x(), p.y(), p.z()})});
}

inline int direction(ItemWriter& w, const Vector3d& d) {
  return w.file.add("IFCDIRECTION", {step::reals({d.x(), d.y(), d.z()})});
}

// Axes at `location` with local z along `z` and local x along `x`.
inline int axes(ItemWriter& w, const Vector3d& location, const Vector3d& z, const Vector3d& x) {
  const int zd = z == Vector3d::UnitZ() ? w.dir_z : direction(w, z);
  const int xd = x == Vector3d::UnitX() ? w.dir_x : direction(w, x);
  return w.file.add("IFCAXIS2PLACEMENT3D", {ref(point3(w, location)), ref(zd), ref(xd)});
}

inline int translation(ItemWriter& w, const Vector3d& location) {
  return axes(w, location, Vector3d::UnitZ(), Vector3d::UnitX());
}

inline int localPlacement(ItemWriter& w, int relative_to, int axes_id) {
  return w.file.add("IFCLOCALPLACEMENT",
                    {relative_to ? ref(relative_to) : step::unset(), ref(axes_id)});
}

inline int polyline(ItemWriter& w, const std::vector<Vector2d>& points, bool closed) {
  std::vector<int> ids;
  for (const Vector2d& p : points) ids.push_back(point2(w, p));
  if (closed) ids.push_back(ids.front());  // IFC closes a polyline by repeating the start
  return w.file.add("IFCPOLYLINE", {refs(ids)});
}

inline int polygonProfile(ItemWriter& w, const std::vector<Vector2d>& polygon) {
  return w.file.add("IFCARBITRARYCLOSEDPROFILEDEF",
                    {".AREA.", step::unset(), ref(polyline(w, polygon, true))});
}

// Rectangle xdim × ydim centred on `centre` of the profile plane.
inline int rectangleProfile(ItemWriter& w, const Vector2d& centre, double xdim, double ydim) {
  const int position =
      w.file.add("IFCAXIS2PLACEMENT2D", {ref(point2(w, centre)), step::unset()});
  return w.file.add("IFCRECTANGLEPROFILEDEF",
                    {".AREA.", step::unset(), ref(position), real(xdim), real(ydim)});
}

inline int extrusion(ItemWriter& w, int profile, int position, double depth) {
  return w.file.add("IFCEXTRUDEDAREASOLID",
                    {ref(profile), ref(position), ref(w.dir_z), real(depth)});
}

inline int representation(ItemWriter& w, int context, const char* identifier, const char* type,
                   int item) {
  return w.file.add("IFCSHAPEREPRESENTATION",
                    {ref(context), str(identifier), str(type), refs({item})});
}

inline int bodyShape(ItemWriter& w, int solid) {
  const int body = representation(w, w.body_context, "Body", "SweptSolid", solid);
  return w.file.add("IFCPRODUCTDEFINITIONSHAPE", {step::unset(), step::unset(), refs({body})});
}

}  // namespace bimloc::worldgen::ifc
