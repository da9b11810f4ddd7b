// Poses outside every room that a scan fits: the hall the plan has no space for, a doorway,
// the street in front of the facade. The per-room pose hypotheses never propose them (a pose
// must be in the room whose faces explain it), nor does the path evidence's global search,
// which keeps poses in some room. But rooms are a prior, not a measurement: a start outside
// every room must be a candidate of the path evidence, or the margin between the wrong places
// that are candidates means nothing, and the filter converges on one of them.
#pragma once

#include "hypotheses.hpp"
#include "room_index.hpp"

#include <bimloc/bim/building.hpp>

#include <memory>
#include <vector>

namespace bimloc::pf::detail {

class OutsideFits {
 public:
  OutsideFits(const bim::Storey& storey, const ParticleFilterConfig& config);
  struct Fits {
    std::size_t anywhere = 0;         // poses the scan fits, in rooms or not: 0, it fixes none
    std::vector<Hypothesis> outside;  // those in no room, best first
  };
  // The poses the scan fits (two observed planes on two faces, three planes explained), and
  // of them those in no room of the storey within 1.5 clutter planes of the best fit anywhere
  // (as PathEvidence::proposeEveryFit keeps them).
  Fits fits(const std::vector<Observation>& observations, double z_base) const;

 private:
  // The storey's walls with one room covering all of it and 5 m around: the global pose search
  // then keeps every pose, and matches it against every face near it, unpenalised.
  std::unique_ptr<bim::Storey> everywhere_;
  RoomIndex every_face_;
  RoomIndex real_;  // the real rooms, to tell which fits lie in none
  ParticleFilterConfig config_;
};

}  // namespace bimloc::pf::detail
