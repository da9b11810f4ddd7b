#include <bimloc/bim/building_json.hpp>

#include "extraction.hpp"

#include <stdexcept>

namespace bimloc::bim {
namespace {

using nlohmann::json;

json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }
json vec(const Eigen::Vector2d& v) { return json::array({v.x(), v.y()}); }

const json& field(const json& j, const char* key, const std::string& where) {
  if (!j.is_object() || !j.contains(key)) throw std::runtime_error(where + ": missing field '" + key + "'");
  return j.at(key);
}

// A point of the plan (or a unit normal): a number (how far is checked per element, below).
template <typename V>
V inPlan(const V& v, const std::string& where) {
  if (!v.allFinite()) throw std::runtime_error(where + ": a coordinate that is not a number");
  return v;
}

Eigen::Vector3d vec3(const json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3) throw std::runtime_error(where + ": expected [x, y, z]");
  return inPlan(Eigen::Vector3d(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()), where);
}

Eigen::Vector2d vec2(const json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 2) throw std::runtime_error(where + ": expected [x, y]");
  return inPlan(Eigen::Vector2d(j[0].get<double>(), j[1].get<double>()), where);
}

json faceJson(const WallFace& f) {
  json openings = json::array();
  for (const auto& o : f.openings) openings.push_back({{"along_m", {o.along_min_m, o.along_max_m}}, {"z_m", {o.z_min_m, o.z_max_m}}});
  return {{"n", vec(f.plane.n)}, {"d", f.plane.d},       {"axis", toString(f.axis)},
          {"start", vec(f.start)}, {"end", vec(f.end)}, {"openings", openings}};
}

FaceOpening openingFromJson(const json& j, const std::string& where) {
  const json& along = field(j, "along_m", where);
  const json& z = field(j, "z_m", where);
  if (!along.is_array() || along.size() != 2 || !z.is_array() || z.size() != 2)
    throw std::runtime_error(where + ": expected along_m: [min, max] and z_m: [min, max]");
  return {along[0].get<double>(), along[1].get<double>(), z[0].get<double>(), z[1].get<double>()};
}

WallFace faceFromJson(const json& j, const std::string& where) {
  WallFace f;
  f.plane.n = vec3(field(j, "n", where), where + ".n");
  f.plane.d = field(j, "d", where).get<double>();
  f.axis = field(j, "axis", where).get<std::string>() == "x" ? WallAxis::X : WallAxis::Y;
  f.start = vec3(field(j, "start", where), where + ".start");
  f.end = vec3(field(j, "end", where), where + ".end");
  if (j.contains("openings")) {  // absent in files written before openings were extracted
    const json& openings = j.at("openings");
    if (!openings.is_array()) throw std::runtime_error(where + ".openings: expected an array");
    for (std::size_t i = 0; i < openings.size(); ++i)
      f.openings.push_back(openingFromJson(openings[i], where + ".openings[" + std::to_string(i) + "]"));
  }
  return f;
}

json wallJson(const Wall& w) {
  return {{"id", w.id}, {"name", w.name}, {"ifc_type", w.ifc_type}, {"start", vec(w.start)}, {"end", vec(w.end)},
          {"length_m", w.length_m()}, {"height_m", w.height_m}, {"thickness_m", w.thickness_m},
          {"source", w.source}, {"approximated", w.approximated},
          {"faces", json::array({faceJson(w.faces[0]), faceJson(w.faces[1])})}};
}

Wall wallFromJson(const json& j, const std::string& where) {
  Wall w;
  w.id = field(j, "id", where).get<std::string>();
  w.name = j.value("name", "");
  w.ifc_type = j.value("ifc_type", "");
  w.start = vec3(field(j, "start", where), where + ".start");
  w.end = vec3(field(j, "end", where), where + ".end");
  w.height_m = field(j, "height_m", where).get<double>();
  w.thickness_m = field(j, "thickness_m", where).get<double>();
  w.source = j.value("source", "");
  w.approximated = j.value("approximated", false);
  const json& faces = field(j, "faces", where);
  if (!faces.is_array() || faces.size() != 2) throw std::runtime_error(where + ".faces: expected two faces");
  for (std::size_t f = 0; f < 2; ++f) w.faces[f] = faceFromJson(faces[f], where + ".faces[" + std::to_string(f) + "]");
  return w;
}

json roomJson(const Room& r) {
  json footprint = json::array(), walls = json::array();
  for (const auto& p : r.footprint) footprint.push_back(vec(p));
  for (const auto& w : r.walls) walls.push_back({{"wall", w.wall_id}, {"face", w.face}});
  return {{"id", r.id}, {"name", r.name}, {"long_name", r.long_name}, {"source", r.source}, {"footprint", footprint},
          {"area_m2", r.area_m2}, {"centre", vec(r.centre)}, {"floor_z_m", r.floor_z}, {"height_m", r.height_m},
          {"walls", walls}, {"topology_source", r.topology_source}};
}

Room roomFromJson(const json& j, const std::string& where) {
  Room r;
  r.id = field(j, "id", where).get<std::string>();
  r.name = j.value("name", "");
  r.long_name = j.value("long_name", "");
  r.source = j.value("source", "IfcSpace");  // written since rooms can be inferred; older files had only IfcSpace
  for (const auto& p : field(j, "footprint", where)) r.footprint.push_back(vec2(p, where + ".footprint"));
  r.area_m2 = field(j, "area_m2", where).get<double>();
  r.centre = vec2(field(j, "centre", where), where + ".centre");
  r.floor_z = j.value("floor_z_m", 0.0);
  r.height_m = j.value("height_m", 0.0);
  for (const auto& w : field(j, "walls", where))
    r.walls.push_back({field(w, "wall", where + ".walls").get<std::string>(), w.value("face", -1)});
  r.topology_source = j.value("topology_source", "");
  return r;
}

json flightJson(const StairFlight& f) {
  return {{"id", f.id}, {"name", f.name}, {"ifc_type", f.ifc_type}, {"stair_id", f.stair_id},
          {"bottom", vec(f.bottom)}, {"top", vec(f.top)}, {"width_m", f.width_m}, {"risers", f.risers},
          {"riser_height_m", f.riser_height_m}, {"going_m", f.going_m}, {"rise_m", f.rise_m()}, {"run_m", f.run_m()},
          {"bottom_storey", f.bottom_storey}, {"top_storey", f.top_storey}, {"source", f.source}};
}

StairFlight flightFromJson(const json& j, const std::string& where, int storeys) {
  StairFlight f;
  f.id = field(j, "id", where).get<std::string>();
  f.name = j.value("name", "");
  f.ifc_type = j.value("ifc_type", "");
  f.stair_id = j.value("stair_id", "");
  f.bottom = vec3(field(j, "bottom", where), where + ".bottom");
  f.top = vec3(field(j, "top", where), where + ".top");
  f.width_m = field(j, "width_m", where).get<double>();
  f.risers = field(j, "risers", where).get<int>();
  f.riser_height_m = field(j, "riser_height_m", where).get<double>();
  f.going_m = field(j, "going_m", where).get<double>();
  f.bottom_storey = field(j, "bottom_storey", where).get<int>();
  f.top_storey = field(j, "top_storey", where).get<int>();
  for (const int s : {f.bottom_storey, f.top_storey})
    if (s < -1 || s >= storeys)
      throw std::runtime_error(where + ": storey index " + std::to_string(s) + " is not -1 or one of the " +
                               std::to_string(storeys) + " storeys");
  f.source = j.value("source", "");
  return f;
}

}  // namespace

nlohmann::json toJson(const Building& building) {
  json storeys = json::array();
  for (const auto& s : building.storeys) {
    json walls = json::array(), rooms = json::array();
    for (const auto& w : s.walls) walls.push_back(wallJson(w));
    for (const auto& r : s.rooms) rooms.push_back(roomJson(r));
    storeys.push_back({{"id", s.id}, {"name", s.name}, {"elevation_m", s.elevation_m},
                       {"elevation_source", s.elevation_source}, {"mesh_triangles", s.mesh.triangles.size()},
                       {"walls", walls}, {"rooms", rooms}});
  }
  json stairs = json::array();
  for (const auto& f : building.stairs) stairs.push_back(flightJson(f));
  json doc = {{"format", "bimloc.building"}, {"version", kBuildingJsonVersion}, {"units", "m"},
              {"frame", "map (the plan's world frame, z up)"}, {"file", building.file}, {"schema", building.schema},
              {"storeys", storeys}, {"stairs", stairs}, {"warnings", building.warnings}};
  // Only where the plan was moved near the origin (map_origin.hpp): every other document stays as it was.
  if (!building.map_origin_in_plan_m.isZero()) {
    doc["frame"] = "map (the plan's world frame less map_origin_in_plan_m, z up)";
    doc["map_origin_in_plan_m"] = {building.map_origin_in_plan_m.x(), building.map_origin_in_plan_m.y()};
  }
  return doc;
}

Building buildingFromJson(const nlohmann::json& doc) {
  if (!doc.is_object() || doc.value("format", "") != "bimloc.building")
    throw std::runtime_error("not a bimloc building document (format is not 'bimloc.building')");
  const int version = doc.value("version", 0);
  if (version < 1 || version > kBuildingJsonVersion)
    throw std::runtime_error("building document version " + std::to_string(version) + " is not supported (this bimloc reads versions 1 to " +
                             std::to_string(kBuildingJsonVersion) + ")");
  Building b;
  b.file = doc.value("file", "");
  b.schema = doc.value("schema", "");
  b.warnings = doc.value("warnings", std::vector<std::string>{});
  if (const auto origin = doc.find("map_origin_in_plan_m"); origin != doc.end()) {
    if (!origin->is_array() || origin->size() != 2 || !(*origin)[0].is_number() || !(*origin)[1].is_number())
      throw std::runtime_error("building.map_origin_in_plan_m: expected [x, y] in metres");
    b.map_origin_in_plan_m = Eigen::Vector2d((*origin)[0].get<double>(), (*origin)[1].get<double>());
    if (!b.map_origin_in_plan_m.allFinite()) throw std::runtime_error("building.map_origin_in_plan_m: not finite");
  }
  const json& storeys = field(doc, "storeys", "building");
  for (std::size_t i = 0; i < storeys.size(); ++i) {
    const std::string where = "storeys[" + std::to_string(i) + "]";
    const json& sj = storeys[i];
    Storey s;
    s.id = sj.value("id", "");
    s.name = field(sj, "name", where).get<std::string>();
    s.elevation_m = field(sj, "elevation_m", where).get<double>();
    s.elevation_source = sj.value("elevation_source", "");
    const json& walls = field(sj, "walls", where);
    for (std::size_t k = 0; k < walls.size(); ++k)
      s.walls.push_back(wallFromJson(walls[k], where + ".walls[" + std::to_string(k) + "]"));
    const json& rooms = field(sj, "rooms", where);
    for (std::size_t k = 0; k < rooms.size(); ++k)
      s.rooms.push_back(roomFromJson(rooms[k], where + ".rooms[" + std::to_string(k) + "]"));
    b.storeys.push_back(std::move(s));
  }
  // Every wall and room within kFarthestElementM of the middle of the walls, as the extraction
  // keeps them (extraction.hpp): one beyond overflowed the grids sized by a storey's extent.
  std::vector<Eigen::Vector2d> wall_points;
  for (const auto& storey : b.storeys)
    for (const auto& w : storey.walls) wall_points.push_back(w.start.head<2>());
  const Eigen::Vector2d middle = detail::planMiddle(wall_points);
  for (std::size_t i = 0; i < b.storeys.size(); ++i) {
    const std::string where = "storeys[" + std::to_string(i) + "]";
    for (std::size_t k = 0; k < b.storeys[i].walls.size(); ++k)
      if (const auto far = detail::farFromPlan(b.storeys[i].walls[k], middle); !far.empty())
        throw std::runtime_error(where + ".walls[" + std::to_string(k) + "]: " + far);
    for (std::size_t k = 0; k < b.storeys[i].rooms.size(); ++k)
      if (const auto far = detail::farFromPlan(b.storeys[i].rooms[k], middle); !far.empty())
        throw std::runtime_error(where + ".rooms[" + std::to_string(k) + "]: " + far);
  }
  if (version >= 2) {  // version 1 had no stairs
    const json& stairs = field(doc, "stairs", "building");
    if (!stairs.is_array()) throw std::runtime_error("building.stairs: expected an array");
    for (std::size_t i = 0; i < stairs.size(); ++i)
      b.stairs.push_back(flightFromJson(stairs[i], "stairs[" + std::to_string(i) + "]", static_cast<int>(b.storeys.size())));
  }
  return b;
}

nlohmann::json extractionSummary(const Building& building, double seconds) {
  json storeys = json::array();
  for (const auto& s : building.storeys)
    storeys.push_back({{"name", s.name}, {"elevation", s.elevation_m}, {"rooms", s.rooms.size()},
                       {"walls", s.walls.size()}, {"wall_planes", s.wallPlaneCount()},
                       {"mesh_triangles", s.mesh.triangles.size()}});
  json stairs = json::array();
  for (const auto& f : building.stairs) stairs.push_back(flightJson(f));
  return {{"file", building.file}, {"schema", building.schema}, {"seconds", seconds},
          {"storeys", storeys}, {"stairs", stairs}, {"warnings", building.warnings}};
}

}  // namespace bimloc::bim
