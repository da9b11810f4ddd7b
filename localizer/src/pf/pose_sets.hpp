// The bookkeeping of the place search's poses (hypotheses.cpp): repeats dropped, the poses most
// pairs of faces agree on put first, and the best hypotheses kept without near-duplicates. Each
// in time linear in the poses, through flat hash tables (issue 28, Speed: sorting and node-based
// maps cost the seeds, which go over every room at every weighing, as much as solving the poses).
// The same results as the definitions they replace (tests/test_pose_sets.cpp holds those).
#pragma once

#include "hypotheses.hpp"

#include <cstddef>
#include <vector>

namespace bimloc::pf::detail {

// The first of each run of poses with the same bits of (x, y, yaw) kept, in order.
void dropRepeatedPoses(std::vector<Particle>& poses);

// The poses ordered by how many share their cell of (x, y, yaw) (0.25 m, 0.25 m, 5 deg; the
// cells' hash keys: cells whose keys collide count as one), most first, ties in list order.
void mostAgreedFirst(std::vector<Particle>& poses);

// Hypotheses sorted best first: the first max_count of them that lie no closer than 0.2 m and
// the angle tolerance (5 deg) to a better one kept.
std::vector<Hypothesis> distinctBest(const std::vector<Hypothesis>& sorted, std::size_t max_count);

}  // namespace bimloc::pf::detail
