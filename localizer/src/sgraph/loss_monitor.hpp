// Loss of track: whether the newest keyframe, once optimized, still agrees with the plan, and
// the tracking state from a run of keyframes (config: lost_after_keyframes bad ones in a row
// -> lost; recover_after_keyframes good ones -> tracking again).
#pragma once

#include "association.hpp"
#include "graph.hpp"

#include <string>
#include <vector>

namespace bimloc::sgraph::detail {

// Why the keyframe disagrees with the plan, or "" when it agrees.
std::string keyframeDoubt(const Graph& g, const Keyframe& kf, const std::vector<ScanObservation>& observed, bool solve_usable,
                          const SGraphConfig& config);

class LossMonitor {
 public:
  explicit LossMonitor(const SGraphConfig& config) : config_(config) {}
  // The state after this keyframe; a change of state is added to `warnings`.
  TrackingState update(const std::string& doubt, std::vector<std::string>& warnings);
  TrackingState state() const { return state_; }

 private:
  SGraphConfig config_;
  TrackingState state_ = TrackingState::Tracking;
  int bad_streak_ = 0, good_streak_ = 0;
};

}  // namespace bimloc::sgraph::detail
