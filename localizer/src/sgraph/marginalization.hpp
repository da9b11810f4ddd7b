// Sliding the window (cost per keyframe bounded by the window, not by the walk).
//
// The oldest keyframe leaves by marginalization, approximated so that the graph stays sparse:
//  - its factors (its own prior, its odometry link to the next keyframe, its plane factors)
//    are linearized at the current optimum (robust kernels as iteratively reweighted least
//    squares), and the keyframe is eliminated by the Schur complement onto the next keyframe,
//    with the wall nodes held at their optimum (conditioned rather than marginalized: exact
//    marginalization would tie the next keyframe to every wall ever seen). The result is the
//    next keyframe's prior: the previous optimum with the covariance of what was eliminated
//    (not a fixed pose: the window can still correct it when the walls disagree).
//  - each of its plane factors also goes into the evidence of its wall node (information
//    form), with the keyframe's uncertainty added to the measurement's, so that a wall seen
//    long ago keeps what was learned of it when the robot comes back.
// An observation thus informs both the next keyframe's prior and its wall's evidence: the
// price of dropping the correlations, a bounded overconfidence (wall evidence is capped).
#pragma once

#include "graph.hpp"

namespace bimloc::sgraph::detail {

// Removes g.window.front() (needs at least two keyframes), updating the anchor and the
// evidence of the walls it saw, and freezes its pose in g.history.
void marginalizeOldest(Graph& g, const SGraphConfig& config);

}  // namespace bimloc::sgraph::detail
