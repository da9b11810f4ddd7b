// Openings IFC++ need not cut. IFC++ subtracts an element's openings one at a time with Carve
// (RepresentationConverter::subtractOpenings), each subtraction re-meshing the whole body cut
// so far: the cost grows with the square of one wall's openings. A 600-room office floor,
// whose corridor walls hold 150 doors each, took 52 s to read, 88 % of it in those cuts;
// its 300-room half, 5.4 s; a 100-room floor, 0.7 s.
// Where the body is one box extrusion and every opening a box along it, rebuiltBodies
// (openings.hpp) replaces IFC++'s cut by its own exact one anyway (IFC++'s changes from run to
// run on some plans), so IFC++'s was thrown away. Before the conversion, such an element's
// openings are detached from it (its inverse list of IfcRelVoidsElement emptied, what IFC++
// reads them from) when cutOpenings cuts every one of them; they are put back after. The
// element's IFC++ mesh is then the uncut box: its convex hull, from which wallFromGeometry
// reads the wall, is the same box. An element decomposed into parts keeps IFC++'s cut (IFC++
// cuts the parent's openings from its parts too).
// Header-only on purpose: included by ifc_geometry.cpp alone, the one IFC++ translation unit.
#pragma once

#include "ifc_profile.hpp"
#include "openings.hpp"

#include <ifcpp/IFC4/include/IfcElement.h>
#include <ifcpp/IFC4/include/IfcFeatureElement.h>
#include <ifcpp/IFC4/include/IfcFeatureElementSubtraction.h>
#include <ifcpp/IFC4/include/IfcRelVoidsElement.h>
#include <ifcpp/IFC4/include/IfcVirtualElement.h>
#include <ifcpp/model/BuildingModel.h>

#include <string>
#include <utility>
#include <vector>

namespace bimloc::bim::detail {

class OwnOpeningCuts {
 public:
  OwnOpeningCuts(BuildingModel& model, const ProfileReader& profiles) {
    for (const auto& [id, entity] : model.getMapIfcEntities()) {
      auto element = dynamic_pointer_cast<IfcElement>(entity);
      if (!element || element->m_HasOpenings_inverse.empty() || !element->m_IsDecomposedBy_inverse.empty() ||
          dynamic_pointer_cast<IfcFeatureElement>(element) || dynamic_pointer_cast<IfcVirtualElement>(element))
        continue;
      if (cutsAll(element, profiles)) {
        detached_.emplace_back(element, std::move(element->m_HasOpenings_inverse));
        element->m_HasOpenings_inverse.clear();
        ids_.push_back(id);
      }
    }
  }
  ~OwnOpeningCuts() {
    for (auto& [element, rels] : detached_) element->m_HasOpenings_inverse = std::move(rels);
  }
  OwnOpeningCuts(const OwnOpeningCuts&) = delete;
  OwnOpeningCuts& operator=(const OwnOpeningCuts&) = delete;

  // The entity ids of the elements detached, ascending.
  const std::vector<int>& elements() const { return ids_; }

 private:
  // rebuiltBodies' rule for an element with an IFC++ mesh: a sole extrusion as its body, every
  // opening a sole extrusion, and every one of them cut.
  static bool cutsAll(const shared_ptr<IfcElement>& element, const ProfileReader& profiles) {
    std::string unread;
    if (!profiles.bodyIsOneExtrusion(element)) return false;
    const auto body = profiles.bodyExtrusion(element, unread);
    if (!body) return false;
    std::vector<Extrusion> solids;
    for (const auto& weak : element->m_HasOpenings_inverse) {
      // The relation as the reader lists it for rebuiltBodies (ifc_geometry.cpp): whole, and
      // naming this element (a damaged file may leave one in the list that names another).
      const auto rel = weak.lock();
      if (!rel || !rel->m_RelatedOpeningElement || rel->m_RelatingBuildingElement != element) return false;
      const auto& opening = rel->m_RelatedOpeningElement;
      if (!profiles.bodyIsOneExtrusion(opening)) return false;
      auto solid = profiles.bodyExtrusion(opening, unread);
      if (!solid) return false;
      solids.push_back(std::move(*solid));
    }
    const OpeningCut cut = cutOpenings(*body, solids);
    return cut.not_cut.empty() && cut.cut == solids.size();
  }

  std::vector<std::pair<shared_ptr<IfcElement>, std::vector<weak_ptr<IfcRelVoidsElement>>>> detached_;
  std::vector<int> ids_;
};

}  // namespace bimloc::bim::detail
