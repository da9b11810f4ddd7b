// Ground truth for the S-Graph tests: storeys built in code, and the wall planes a lidar sees
// from a known pose, computed from the walls' geometry (not by the tracker's own algebra).
#pragma once

#include <bimloc/bim/building.hpp>
#include <bimloc/planes/plane_extraction.hpp>

#include <Eigen/Geometry>
#include <random>
#include <string>
#include <vector>

namespace bimloc::test {

// A straight box wall with axis a -> b, its faces as the extraction makes them: faces[0] left
// of a -> b, faces[1] right, normals out of the wall, n·p + d = 0.
bim::Wall boxWall(const std::string& id, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double thickness_m);
// The same wall standing from z0_m up height_m (a storey's walls above another's floor).
bim::Wall liftedWall(bim::Wall wall, double z0_m, double height_m);

// A rectangular room [x0, x1] x [y0, y1] bounded by the given faces.
bim::Room boxRoom(const std::string& name, double x0, double y0, double x1, double y1, const std::vector<bim::RoomWall>& walls);

// The same storey with wall `index` moved by `offset_m` along its faces[0] normal.
bim::Storey shiftedWall(const bim::Storey& storey, std::size_t index, double offset_m);

// A doorway: where a wall has no face (rays pass, no returns), between two points of its axis.
struct Opening {
  std::size_t wall = 0;
  Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
};

// The doorways of a generated world's storey (worldgen's spec), matched to the storey's walls by name.
std::vector<Opening> worldOpenings(const std::string& world, const bim::Storey& storey);

struct SyntheticLidar {
  double range_m = 20.0;
  double min_extent_m = 1.0;   // as the plane extraction's
  double step_m = 0.1;         // sampling of the faces for visibility
  double sigma_azimuth_deg = 0.3;
  double sigma_elevation_deg = 0.1;
  double sigma_d_m = 0.01;
  bool spans = false;  // also each plane's standing span (wall_span_m, wall_span_middle): its visible run
};

// The wall faces a lidar at T_map_lidar sees (in front of it, within range, not hidden by
// another wall over at least min_extent_m), as observed planes in the lidar frame with
// Gaussian noise on (azimuth, elevation, d) and that covariance.
std::vector<planes::ObservedPlane> syntheticWalls(const bim::Storey& truth, const std::vector<Opening>& openings,
                                                  const Eigen::Isometry3d& T_map_lidar, const SyntheticLidar& lidar,
                                                  std::mt19937_64& rng);

}  // namespace bimloc::test
