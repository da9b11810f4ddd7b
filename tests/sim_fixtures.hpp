// Worlds with known geometry for the simulator tests.
#pragma once

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <string>

namespace bimloc::test {

// A closed box room [0, size.x] x [0, size.y] x [0, size.z], as a triangle mesh.
bim::TriangleMesh boxRoom(const Eigen::Vector3f& size);

// Distance from `origin` (inside the box) along unit `dir` to the box's surface.
double boxRange(const Eigen::Vector3d& size, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir);

// Writes the box room to a PLY in a fresh temporary directory and returns the path.
std::string boxRoomFile(const Eigen::Vector3f& size);

}  // namespace bimloc::test
