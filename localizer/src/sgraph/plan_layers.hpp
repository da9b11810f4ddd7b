// The top two layers of the S-Graph from the plan (paper, "Topological and Metric-Semantic
// Layer Generation"): a wall node per plan wall, a room node per room whose walls give a pair
// of opposite faces (a corridor) or two pairs (a room).
#pragma once

#include "graph.hpp"

#include <bimloc/bim/building.hpp>

#include <string>
#include <vector>

namespace bimloc::sgraph::detail {

// Fills g.nodes (one per storey wall, inactive when unusable) and g.rooms; names every wall
// and room left out, and why, in `warnings`.
void buildPlanLayers(const bim::Storey& storey, Graph& g, std::vector<std::string>& warnings);

}  // namespace bimloc::sgraph::detail
