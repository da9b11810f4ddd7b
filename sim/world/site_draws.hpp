// The site's random choices, drawn from the seed before any geometry is made: each wall's
// shift, turn and whether it is built, each door's state; then the edits by GlobalId or name.
// Every wall (door) draws the same numbers whatever the fractions, so a fraction changed or an
// edit added leaves every other wall's draw as it was.
#pragma once

#include "sim/world/site_truth.hpp"
#include "sim/world/world_impl.hpp"

#include <Eigen/Geometry>

namespace bimloc::sim {

// The walls of `building` named by `id`: its GlobalId, or its name when no GlobalId matches
// (every wall of that name). Empty when none.
std::vector<const bim::Wall*> wallsNamed(const bim::Building& building, const std::string& id);
// Every GlobalId and name of the building's walls (doors: IfcDoor parts), for suggestions.
std::vector<std::string> wallWords(const bim::Building& building);
std::vector<std::string> doorWords(const std::vector<PlanStorey>& plan);

// walls and doors of the truth (partitions are placed later, on the geometry). Throws
// std::invalid_argument for an edit naming no wall or door.
SiteTruth drawSite(const bim::Building& building, const std::vector<PlanStorey>& plan, const SiteConfig& config,
                   std::uint64_t seed);

// The rigid motion of a wall's points from the plan to the site (identity for an exact wall).
Eigen::Affine3d wallMotion(const bim::Wall& wall, const WallTruth& truth);

// The wall of the storey that hosts an element (door, window) whose part this is: the wall
// whose body holds the centre of the part's bounding box; -1 when none.
Eigen::Vector2d partCentre(const PlanStorey& plan, const bim::MeshPart& part);  // of its XY bounding box
int hostWall(const bim::Storey& storey, const PlanStorey& plan, const bim::MeshPart& part);

}  // namespace bimloc::sim
