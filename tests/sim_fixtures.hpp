// Worlds with known geometry for the simulator tests.
#pragma once

#include <bimloc/bim/building.hpp>
#include <bimloc/planes/plane_extraction.hpp>

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace bimloc::sim {
class World;
}

namespace bimloc::test {

// The default world, loaded once.
const sim::World& officeWorld();

// A base pose in the plane at height z.
Eigen::Isometry3d pose(double x, double y, double yaw, double z = 0.5);

// The wall planes a VLP-16 on the base at T_map_base sees in the default world.
std::vector<planes::ObservedPlane> wallsSeenFrom(const Eigen::Isometry3d& T_map_base, const Eigen::Isometry3d& T_base_lidar);

// A closed box room [0, size.x] x [0, size.y] x [0, size.z], as a triangle mesh.
bim::TriangleMesh boxRoom(const Eigen::Vector3f& size);

// Distance from `origin` (inside the box) along unit `dir` to the box's surface.
double boxRange(const Eigen::Vector3d& size, const Eigen::Vector3d& origin, const Eigen::Vector3d& dir);

// Writes the box room to a PLY in a fresh temporary directory and returns the path.
std::string boxRoomFile(const Eigen::Vector3f& size);

}  // namespace bimloc::test
