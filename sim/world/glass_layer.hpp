// The glazed elements of a storey as the lidar sees them: a second Embree geometry whose hits
// an intersection filter lets through for a fraction of the rays. Whether a ray passes an
// element is a hash of the ray (origin and direction bits), the element and the site's seed:
// the same ray always gets the same answer, on any thread, in any packet, and both faces of a
// pane agree, so an element passes exactly its fraction of independent rays.
#pragma once

#include <bimloc/bim/building.hpp>

#include <cstdint>
#include <vector>

namespace bimloc::sim {

struct GlassLayer {
  bim::TriangleMesh mesh;
  std::vector<std::uint32_t> element_of_triangle;  // index into pass_fraction
  std::vector<float> pass_fraction;                // per element
  std::uint64_t seed = 0;
};

// Does `ray` (origin, unit direction) pass element `element` of the layer?
bool glassPasses(const GlassLayer& layer, std::uint32_t element, const float origin[3], const float dir[3]);

// Attaches the layer to the Embree scene (geometry with the filter); the layer must outlive it.
void attachGlass(void* device, void* scene, const GlassLayer& layer);

}  // namespace bimloc::sim
