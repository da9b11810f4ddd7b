// Pose hypotheses straight from the data ("sensor resetting", Lenser & Veloso 2000): two
// observed wall planes that are not parallel, matched to two faces of a room at the same
// relative angle, fix the pose (x, y, yaw) exactly. Scored like particles. They seed the
// filter where a uniform spread has almost no particle near the truth, and bring it back
// when the particles explain the scan worse than the plan can.
#pragma once

#include "measurement.hpp"

#include <limits>
#include <vector>

namespace bimloc::pf::detail {

struct Hypothesis {
  double x = 0, y = 0, yaw = 0;
  int room = -1;
  double log_likelihood = 0;
  int associated = 0;
};

// How far two faces may turn from the turn between two observed planes and still be solved as
// their pair; and how far apart in heading two hypotheses within 0.2 m may be and still be one
// (the merge of near-duplicates, pose_sets.cpp).
constexpr double kHypothesisAngleRad = 5.0 * M_PI / 180.0;

// A pose's room: any room (-1), or anywhere, in a room or not (kAnywhere: the rival search).
constexpr int kAnywhere = -2;

// Where a scan's planes all run one way (positionFixedByPlanes is false), the poses at which one
// of them lies on a face of `marks` with its standing span's end at an end of the face's wall
// line (end_hypotheses.cpp), appended to `poses`; in `room` (>= 0), any room (-1) or anywhere
// (kAnywhere).
void posesFromEnds(const std::vector<Observation>& obs, double z, const std::vector<Landmark>& marks, int room,
                   const RoomIndex& rooms, double margin_m, std::vector<Particle>& poses);

// A share of the storey's rooms for one search (the filter's seeds after its first weighing):
// rooms in turn from `next_room`, until `poses` poses are solved (0: every room). The search
// sets `next_room` to where the next one goes on and `rooms_searched` to how many it took.
struct RoomShare {
  std::size_t poses = 0;
  int next_room = 0;
  int rooms_searched = 0;
};

// Hypotheses over every room (best first, near-duplicates merged, at most max_count), or over
// the rooms of `share` (with rooms).
// With a finite `wanted_within`, the caller only wants those within it of the best: a pose
// whose scan already scores below the best found so far less that is not scored to the end
// (matchObservations' floor). Every hypothesis within it of the best is still there, with the
// same bits, and so are the merges among them; only some below it are missing. With
// `outside_rooms`, also poses in no room (a search for rivals: rooms are a prior, and a
// corridor the plan has no space for is a place too); the particles' seeds stay in rooms.
std::vector<Hypothesis> poseHypotheses(const std::vector<Observation>& observations, double z_base,
                                       const RoomIndex& rooms, const ParticleFilterConfig& config, std::size_t max_count,
                                       double wanted_within = std::numeric_limits<double>::infinity(),
                                       bool outside_rooms = false, RoomShare* share = nullptr);

}  // namespace bimloc::pf::detail
