// A triangle mesh as an Embree geometry: the one place the vertex and index buffers are
// filled, for the world's storeys, its glass layer and the map-RMSE distance queries.
#pragma once

#include <bimloc/bim/building.hpp>

#include <embree3/rtcore.h>

namespace bimloc::sim {

// A new, uncommitted triangle geometry holding `mesh` (the caller sets filters or user data,
// commits, attaches and releases it).
RTCGeometry newTriangleGeometry(RTCDevice device, const bim::TriangleMesh& mesh);

}  // namespace bimloc::sim
