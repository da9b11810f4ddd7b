// Evidence over the robot's recent path. One scan in a rectangular office fits every office of
// the same size, and the office turned by 180 degrees, equally well: no single scan can tell
// them apart, and a filter that picks one has picked by luck. The path can: a candidate
// transform map <- odom places the whole recent path in the plan, and only the true one keeps
// the robot inside rooms, through doorways, in front of the walls it saw.
//
// Candidates are transforms map <- odom, which odometry leaves fixed while the robot moves:
// pose hypotheses of any scan stay valid afterwards. Each is scored on a window of past scans
// (the sum of their log-likelihoods, as the particles are weighed), incrementally: a new scan
// is scored once per candidate, a new candidate once per scan of the window.
#pragma once

#include "measurement.hpp"

#include <deque>
#include <vector>

namespace bimloc::pf::detail {

// x, y, yaw: a planar pose or transform. The filter works in the plane; tilt and height are
// the odometry's (see ParticleFilter::poseOf).
using Pose2 = Eigen::Vector3d;
Pose2 compose(const Pose2& a, const Pose2& b);  // a (+) b
Pose2 inverse(const Pose2& a);
// Within `metres` and `radians` of each other.
bool near(const Pose2& a, const Pose2& b, double metres, double radians);

struct PathVerdict {
  bool has_best = false;
  Pose2 best = Pose2::Zero();  // map <- base now, of the best candidate
  double best_log_likelihood = 0;
  // Best minus the best candidate more than 1 m or 20 deg away from it now: how much better
  // the path fits one place than any other. +inf when no other place fits at all.
  double margin = 0;
  int candidates = 0;
  int scans = 0;
  double window_m = 0;  // path length covered by the window
};

class PathEvidence {
 public:
  // The path is scored against every wall face of the storey, each where it is (an observed
  // plane matches a face only along it): the true pose sees walls of other rooms through
  // doors and open plans, and the room graph does not say which. Room association would make
  // it pay for each of them, while a wrong pose may find such planes among its own room's
  // faces by coincidence: over a path, that bias adds up to a wrong verdict. The rooms still
  // count: a path through no room's footprint (through walls, outside) scores lowest.
  PathEvidence(const bim::Storey& storey, const ParticleFilterConfig& config)
      : rooms_(storey, /*use_rooms=*/false), config_(config) {}

  // A weighed scan at odometry pose `odom` (x, y, yaw of odom <- base): joins the window when
  // the robot moved enough since the last one that did. Returns whether it joined.
  bool addScan(const Pose2& odom, double z_base, const std::vector<Observation>& observations);
  // The map pose `map_pose` of the base, at odometry pose `odom`, as a candidate. Near an
  // existing candidate, the better of the two stays.
  void propose(const Pose2& map_pose, const Pose2& odom);
  // The best candidate and its strongest rival, each first moved to the best fit of the path
  // near it: a candidate fitted to one scan is a little off on the others (noise, drift), and
  // comparing a fitted look-alike with an unfitted truth would favour the look-alike.
  PathVerdict verdict(const Pose2& odom);
  // Before a verdict is trusted: every pose the scan `observations` fits, over every face of
  // the storey, joins the candidates, so that the best's strongest rival cannot be missing
  // (a look-alike the per-scan proposals left out would make any margin meaningless).
  void proposeEveryFit(const std::vector<Observation>& observations, double z_base, const Pose2& odom);
  // The window's log-likelihood of the base at `map_pose` now (any pose, candidate or not).
  double logLikelihoodOf(const Pose2& map_pose, const Pose2& odom) const;

 private:
  struct Scan {
    Pose2 odom;
    double z_base = 0;
    std::vector<Observation> observations;
    double travelled_m = 0;  // path length from the start to this scan
  };
  struct Candidate {
    Pose2 T_map_odom;
    double log_likelihood = 0;
    std::deque<double> per_scan;  // aligned with scans_
  };
  double scoreOn(const Pose2& T_map_odom, const Scan& scan) const;
  Candidate scored(const Pose2& T_map_odom) const;
  void refine(Candidate& c, const Pose2& odom) const;
  void dropOldScans();

  RoomIndex rooms_;
  ParticleFilterConfig config_;
  std::deque<Scan> scans_;
  std::vector<Candidate> candidates_;
  double travelled_m_ = 0;
  bool has_last_odom_ = false;
  Pose2 last_odom_ = Pose2::Zero();  // of the last odometry pose seen, for the path length
};

}  // namespace bimloc::pf::detail
