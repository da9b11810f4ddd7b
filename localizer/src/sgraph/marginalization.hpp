// Sliding the window (cost per keyframe bounded by the window, not by the walk).
//
// The oldest keyframe leaves by marginalization: its factors (the window's prior, its odometry
// link to the next keyframe, its plane factors) are linearized at the current optimum (robust
// kernels as iteratively reweighted least squares), and the keyframe is eliminated by the
// Schur complement. What is left is the new prior (marginal_prior.hpp), a Gaussian over the
// next keyframe and every wall node it or the earlier keyframes saw, with their correlations:
// what the robot learned of a wall stays relative to the robot, and the plan's priors, which
// stay in the window as factors of their own, keep anchoring both.
//
// The prior's walls are bounded (SGraphConfig::prior_max_walls): beyond it, walls the window no
// longer sees are eliminated too, least recently seen first, without their plan prior (what
// the keyframes said of them is forgotten, which is conservative, and the plan prior is not
// counted twice when the robot comes back).
#pragma once

#include "graph.hpp"

namespace bimloc::sgraph::detail {

// Removes g.window.front() (needs at least two keyframes), moving the prior onto the next
// keyframe, and freezes its pose in g.history.
void marginalizeOldest(Graph& g, const SGraphConfig& config);

}  // namespace bimloc::sgraph::detail
