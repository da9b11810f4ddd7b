// Guards IFC++'s geometry converter against a cycle in the spatial structure. The converter
// walks the structure from the project down (GeometryConverter::resolveProjectStructure:
// IfcRelAggregates, then IfcRelContainedInSpatialStructure) and recurses into every related
// object; its guard against revisiting an ancestor (ProductShapeData::isContainedInParentsList)
// drops its own recursive answer. So a storey that "contains" its own site (one damaged
// reference in the storey's list of elements) recursed without end: a stack overflow, a
// segfault in every command that reads the plan (found by scripts/damage_probe.py).
// Before the conversion, each link that closes a cycle (an edge back to an ancestor in a
// depth-first walk from the projects, then from every other object, in entity order) is
// removed from its relation, with a warning naming the relation and both objects. A plan
// without such a cycle is left exactly as it was.
// Header-only on purpose: included by ifc_geometry.cpp alone, the one IFC++ translation unit.
#pragma once

#include <ifcpp/IFC4/include/IfcObjectDefinition.h>
#include <ifcpp/IFC4/include/IfcProduct.h>
#include <ifcpp/IFC4/include/IfcProject.h>
#include <ifcpp/IFC4/include/IfcRelAggregates.h>
#include <ifcpp/IFC4/include/IfcRelContainedInSpatialStructure.h>
#include <ifcpp/model/BuildingModel.h>

#include <algorithm>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace bimloc::bim::detail {

inline std::vector<std::string> breakSpatialCycles(BuildingModel& model) {
  struct Link {
    int rel = 0;        // the relation's entity id
    std::size_t at = 0;  // the related object's place in the relation's list
    int child = 0;
  };
  std::map<int, std::vector<Link>> children;  // by relating object, in entity order
  for (const auto& [id, entity] : model.getMapIfcEntities()) {
    if (auto agg = dynamic_pointer_cast<IfcRelAggregates>(entity); agg && agg->m_RelatingObject) {
      auto& links = children[agg->m_RelatingObject->m_entity_id];
      for (std::size_t k = 0; k < agg->m_RelatedObjects.size(); ++k)
        if (const auto& c = agg->m_RelatedObjects[k]) links.push_back({id, k, c->m_entity_id});
    } else if (auto rel = dynamic_pointer_cast<IfcRelContainedInSpatialStructure>(entity); rel && rel->m_RelatingStructure) {
      auto& links = children[rel->m_RelatingStructure->m_entity_id];
      for (std::size_t k = 0; k < rel->m_RelatedElements.size(); ++k)
        if (const auto& c = rel->m_RelatedElements[k]) links.push_back({id, k, c->m_entity_id});
    }
  }
  // Depth-first, iterative (a broken file may nest deeper than a stack allows): the projects
  // first, so that the cut is the link that turns back up towards them.
  std::vector<int> roots;
  for (const auto& [id, entity] : model.getMapIfcEntities())
    if (dynamic_pointer_cast<IfcProject>(entity)) roots.push_back(id);
  for (const auto& [id, links] : children) roots.push_back(id);
  enum : char { kNew = 0, kOpen, kDone };
  std::map<int, char> state;
  std::vector<Link> cut;
  std::vector<std::pair<int, std::size_t>> work;  // (object, next link to follow)
  for (const int root : roots) {
    if (state[root] != kNew) continue;
    state[root] = kOpen;
    work.emplace_back(root, 0);
    while (!work.empty()) {
      auto& [node, next] = work.back();
      const auto it = children.find(node);
      if (it == children.end() || next >= it->second.size()) {
        state[node] = kDone;
        work.pop_back();
        continue;
      }
      const Link link = it->second[next++];
      char& s = state[link.child];
      if (s == kOpen) {
        cut.push_back(link);
      } else if (s == kNew) {
        s = kOpen;
        work.emplace_back(link.child, 0);
      }
    }
  }
  std::vector<std::string> warnings;
  if (cut.empty()) return warnings;
  // Removed from the back of each list, so that the places of the others stay valid.
  std::sort(cut.begin(), cut.end(), [](const Link& a, const Link& b) { return a.rel != b.rel ? a.rel < b.rel : a.at > b.at; });
  const auto& entities = model.getMapIfcEntities();
  // The class names only for the warnings, which are rare: looked up here, not kept for every object.
  const auto named = [&](int id) {
    const auto it = entities.find(id);
    return "#" + std::to_string(id) + (it != entities.end() && it->second ? std::string(" ") + it->second->className() : std::string());
  };
  for (const Link& link : cut) {
    const auto& entity = entities.at(link.rel);
    int parent = 0;
    if (auto agg = dynamic_pointer_cast<IfcRelAggregates>(entity)) {
      parent = agg->m_RelatingObject->m_entity_id;
      agg->m_RelatedObjects.erase(agg->m_RelatedObjects.begin() + static_cast<std::ptrdiff_t>(link.at));
    } else if (auto rel = dynamic_pointer_cast<IfcRelContainedInSpatialStructure>(entity)) {
      parent = rel->m_RelatingStructure->m_entity_id;
      rel->m_RelatedElements.erase(rel->m_RelatedElements.begin() + static_cast<std::ptrdiff_t>(link.at));
    }
    warnings.push_back(std::string(entity->className()) + " #" + std::to_string(link.rel) + " relates " + named(link.child) +
                       ", which contains or aggregates its relating " + named(parent) +
                       ": that link is ignored (a cycle in the spatial structure)");
  }
  return warnings;
}

}  // namespace bimloc::bim::detail
