// Reads an IFC plan (IFC2X3 or IFC4, STEP physical file) into a Building.
#pragma once

#include <bimloc/bim/building.hpp>
#include <bimloc/bim/room_inference.hpp>

#include <stdexcept>
#include <string>

namespace bimloc::bim {

// Every failure to read a plan: the message names the file and the problem, on one line.
class BimError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ExtractOptions {
  // A wall face lies on a room's boundary when it is this close to a footprint edge.
  double adjacency_tolerance_m = 0.05;
  // ... and parallel to it within this angle, overlapping it over at least this length.
  double adjacency_angle_deg = 5.0;
  double adjacency_min_overlap_m = 0.2;
  bool build_meshes = true;  // storey meshes for the simulator
  // Door leaves (IfcDoor) in the storey meshes. The simulator leaves them out: a building under
  // construction has doorways before it has doors, and closed leaves would wall every room in.
  bool door_leaves = true;
  // Rooms of a storey that has walls and no IfcSpace are inferred from its walls. With
  // infer_rooms, every storey's rooms are inferred, its IfcSpace rooms dropped (to compare).
  bool infer_rooms = false;
  RoomInferenceConfig room_inference;
};

// Throws BimError for a file that cannot be read, is not IFC, is truncated, or has no
// storey or no wall. Elements it cannot use become warnings, never errors.
Building readIfc(const std::string& path, const ExtractOptions& options = {});

}  // namespace bimloc::bim
