// The files `bimloc extract --out DIR` writes: building.json, walls.csv, one mesh per storey.
#pragma once

#include <bimloc/bim/building.hpp>

#include <string>
#include <vector>

namespace bimloc::sim {

// File name of storey `index`'s mesh, e.g. "storey_00_Erdgeschoss.ply".
std::string storeyMeshName(const bim::Building& building, std::size_t index);

// walls.csv: one row per wall face in the paper's form (id, start point, normal, length,
// thickness, d), plus the storey, the face index and its x / y class.
std::string wallsCsv(const bim::Building& building);

// Writes everything into `dir`, all or nothing: the files are staged under a temporary
// directory and renamed into place only when every one of them was written.
std::vector<std::string> exportPlan(const bim::Building& building, const std::string& dir);

}  // namespace bimloc::sim
