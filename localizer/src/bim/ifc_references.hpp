// Guards IFC++'s geometry converter against references of the wrong type. IFC++ reads a
// reference to an entity of another type than the attribute's (a polyline point that is a
// polyline, a profile or an IfcSpace) as a null pointer, and its converters dereference such
// pointers unchecked: a segfault in CurveConverter, reached from every command. So before the
// conversion, every instance is checked against the text (scanStep): one with fewer resolved
// references than its text names is broken, and so is everything that reaches it. So is one the
// text shows to be unusable (stepProblems: a duplicate id, a non-finite number, a cycle of
// references, on which the converter recurses without end) and an extrusion that is not
// positive (its faces would start below the placement).
// Products lose the representations (or, for their body or placement, all geometry) that
// reach a broken instance, and say why.
// Header-only on purpose: included by ifc_geometry.cpp alone, the one IFC++ translation unit.
#pragma once

#include "step_references.hpp"
#include "utf8.hpp"

#include <ifcpp/IFC4/include/IfcExtrudedAreaSolid.h>
#include <ifcpp/IFC4/include/IfcLabel.h>
#include <ifcpp/IFC4/include/IfcObjectPlacement.h>
#include <ifcpp/IFC4/include/IfcProduct.h>
#include <ifcpp/IFC4/include/IfcPositiveLengthMeasure.h>
#include <ifcpp/IFC4/include/IfcProductRepresentation.h>
#include <ifcpp/IFC4/include/IfcRepresentation.h>
#include <ifcpp/model/AttributeObject.h>
#include <ifcpp/model/BuildingModel.h>

#include <cmath>
#include <cstdio>
#include <deque>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

namespace bimloc::bim::detail {

inline std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

class ReferenceCheck {
 public:
  ReferenceCheck(const BuildingModel& model, const StepScan& scan) {
    const auto& entities = model.getMapIfcEntities();
    for (const auto& line : scan.malformed) report(line);
    for (const auto& [id, why] : stepProblems(scan)) {
      report(why);
      if (entities.count(id)) broken_.emplace(id, why);
    }
    // Instances IFC++ dropped: their type is unknown, or their arguments do not fit it.
    for (std::size_t i = 0; i < scan.instances.size(); ++i) {
      const StepInstance& instance = scan.instances[i];
      if ((i > 0 && scan.instances[i - 1].id == instance.id) || entities.count(instance.id)) continue;
      report("#" + std::to_string(instance.id) + " " + instance.type + " (line " + std::to_string(instance.line) +
             ") could not be read (an unknown entity type, or arguments that do not fit it)");
    }
    std::vector<std::pair<std::string, shared_ptr<BuildingObject>>> attributes;
    auto named = scan.instances.begin();
    for (const auto& [id, entity] : entities) {
      if (!entity) continue;
      if (auto solid = dynamic_pointer_cast<IfcExtrudedAreaSolid>(entity)) {
        const double depth = solid->m_Depth ? solid->m_Depth->m_value : 0.0;
        if (!(depth > 0.0) || !std::isfinite(depth)) {  // IFC: a positive length
          const std::string why = "#" + std::to_string(id) + " IfcExtrudedAreaSolid has the depth " +
                                  number(depth) + ", which is not positive";
          if (broken_.emplace(id, why).second) report(why);
        }
      }
      // Instances whose text names no reference cannot have lost one (most: points, directions).
      while (named != scan.instances.end() && named->id < id) ++named;
      if (named == scan.instances.end() || named->id != id || named->refs.empty()) continue;
      attributes.clear();
      entity->getAttributes(attributes);
      int resolved = 0;
      for (const auto& attribute : attributes) collect(id, attribute.second, resolved, nullptr, 0);
      const int lost = static_cast<int>(named->refs.size()) - resolved;
      if (lost <= 0) continue;
      std::string what = std::to_string(lost) + " entit" + (lost == 1 ? "y" : "ies") +
                         " it cannot use (of a type its attribute does not take)";
      for (const int ref : named->refs)
        if (!entities.count(ref)) {
          what = "#" + std::to_string(ref) + ", which is missing or could not be read";
          break;
        }
      const std::string why = "#" + std::to_string(id) + " " + entity->className() + " names " + what;
      if (broken_.emplace(id, why).second) report(why);
    }
    if (broken_.empty()) return;
    // Everything that reaches a broken instance, with the first one it reaches (by id order).
    std::vector<std::pair<int, int>> edges;  // (referencing, referenced)
    for (const auto& [id, entity] : entities) {
      if (!entity) continue;
      attributes.clear();
      entity->getAttributes(attributes);
      int resolved = 0;
      for (const auto& attribute : attributes) collect(id, attribute.second, resolved, &edges, 0);
    }
    std::unordered_map<int, std::vector<int>> referenced_by;
    for (const auto& [from, to] : edges) referenced_by[to].push_back(from);
    for (const auto& [id, why] : broken_) {
      if (tainted_.count(id)) continue;
      std::deque<int> queue{id};
      tainted_.emplace(id, why);
      while (!queue.empty()) {
        const int at = queue.front();
        queue.pop_front();
        for (int parent : referenced_by[at])
          if (tainted_.emplace(parent, why).second) queue.push_back(parent);
      }
    }
  }

  // The file's inconsistencies, each once, whether or not a product loses anything by them.
  const std::vector<std::string>& warnings() const { return warnings_; }
  bool clean() const { return broken_.empty(); }
  // Why an entity's graph cannot be converted, or nullptr when it can.
  const std::string* problem(const BuildingEntity* entity) const {
    if (!entity) return nullptr;
    const auto it = tainted_.find(entity->m_entity_id);
    return it == tainted_.end() ? nullptr : &it->second;
  }
  const std::string* brokenItself(int id) const {
    const auto it = broken_.find(id);
    return it == broken_.end() ? nullptr : &it->second;
  }

 private:
  static void collect(int from, const shared_ptr<BuildingObject>& object, int& resolved,
                      std::vector<std::pair<int, int>>* edges, int depth) {
    if (!object || depth > 8) return;
    if (auto entity = dynamic_cast<const BuildingEntity*>(object.get())) {
      ++resolved;
      if (edges) edges->emplace_back(from, entity->m_entity_id);
    } else if (auto list = dynamic_cast<const AttributeObjectVector*>(object.get())) {
      for (const auto& item : list->m_vec) collect(from, item, resolved, edges, depth + 1);
    }
  }

  void report(const std::string& why) {
    constexpr std::size_t kMax = 50;  // a file broken everywhere still gets a readable list
    if (warnings_.size() < kMax) warnings_.push_back(why);
    else if (warnings_.size() == kMax) warnings_.push_back("more inconsistencies of the file not listed");
  }

  std::map<int, std::string> broken_;  // by id: the same order in every run
  std::vector<std::string> warnings_;
  std::unordered_map<int, std::string> tainted_;
};

// What was removed from a product before the conversion.
struct GeometryDrop {
  bool all = false;    // its body or placement: the product has no usable geometry
  std::string reason;  // names the representation and the broken instance
};

// Removes from every product the geometry that reaches a broken instance: the representations
// that do (all of them when one is the body, or when the placement or the product itself is
// broken). Returns what was removed, by product entity id.
inline std::map<int, GeometryDrop> dropUnreadableGeometry(const BuildingModel& model, const ReferenceCheck& check) {
  std::map<int, GeometryDrop> drops;
  if (check.clean()) return drops;
  for (const auto& [id, entity] : model.getMapIfcEntities()) {
    auto product = dynamic_pointer_cast<IfcProduct>(entity);
    if (!product) continue;
    const std::string* whole = check.brokenItself(id);
    std::string where = "itself";
    if (!whole && (whole = check.problem(product->m_ObjectPlacement.get()))) where = "its placement";
    const auto& shape = product->m_Representation;
    if (!whole && shape && check.brokenItself(shape->m_entity_id)) whole = check.brokenItself(shape->m_entity_id),
                                                                     where = "its representation list";
    if (whole) {
      product->m_Representation.reset();
      product->m_ObjectPlacement.reset();
      drops[id] = {true, where + ": " + *whole};
      continue;
    }
    if (!shape) continue;
    std::vector<shared_ptr<IfcRepresentation>> kept;
    std::string dropped;
    bool body = false;
    for (const auto& rep : shape->m_Representations) {
      const std::string* why = rep ? check.problem(rep.get()) : nullptr;
      if (rep && !why) {
        kept.push_back(rep);
        continue;
      }
      if (!rep) continue;
      const std::wstring identifier = rep->m_RepresentationIdentifier ? rep->m_RepresentationIdentifier->m_value : L"";
      const bool is_body = identifier == L"Body" || identifier.empty();
      // Name the body when it is among them: it is what the product loses.
      if (dropped.empty() || (is_body && !body)) dropped = "its '" + utf8(identifier) + "' representation: " + *why;
      body |= is_body;
    }
    if (dropped.empty()) continue;
    if (body) {
      product->m_Representation.reset();
      drops[id] = {true, dropped};
    } else {
      shape->m_Representations = kept;
      drops[id] = {false, dropped};
    }
  }
  return drops;
}

}  // namespace bimloc::bim::detail
