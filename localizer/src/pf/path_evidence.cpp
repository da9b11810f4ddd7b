#include "path_evidence.hpp"

#include "hypotheses.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bimloc::pf::detail {

Pose2 compose(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.z()), s = std::sin(a.z());
  return {a.x() + c * b.x() - s * b.y(), a.y() + s * b.x() + c * b.y(), wrapAngle(a.z() + b.z())};
}

Pose2 inverse(const Pose2& a) {
  const double c = std::cos(a.z()), s = std::sin(a.z());
  return {-c * a.x() - s * a.y(), s * a.x() - c * a.y(), -a.z()};
}

namespace {

// Farther than this from the best, a candidate is another place: the false-convergence bounds.
constexpr double kOtherPlaceM = 0.5;
constexpr double kOtherPlaceRad = 10.0 * M_PI / 180.0;
// Closer than this to a candidate, a proposal is that candidate.
constexpr double kSamePlaceM = 0.2;
constexpr double kSamePlaceRad = 3.0 * M_PI / 180.0;

}  // namespace

bool near(const Pose2& a, const Pose2& b, double metres, double radians) {
  return std::hypot(a.x() - b.x(), a.y() - b.y()) < metres && std::abs(wrapAngle(a.z() - b.z())) < radians;
}

double PathEvidence::scoreOn(const Pose2& T_map_odom, const Scan& scan) const {
  const Pose2 pose = compose(T_map_odom, scan.odom);
  Particle p;
  p.x = pose.x(), p.y = pose.y(), p.yaw = pose.z(), p.room = rooms_.roomAt(pose.x(), pose.y());
  return matchObservations(p, scan.z_base, scan.observations, rooms_, config_).log_likelihood;
}

bool PathEvidence::addScan(const Pose2& odom, double z_base, const std::vector<Observation>& observations) {
  if (has_last_odom_) travelled_m_ += std::hypot(odom.x() - last_odom_.x(), odom.y() - last_odom_.y());
  has_last_odom_ = true;
  last_odom_ = odom;
  if (!scans_.empty()) {
    const Pose2& last = scans_.back().odom;
    const bool moved = std::hypot(odom.x() - last.x(), odom.y() - last.y()) >= config_.evidence_spacing_m ||
                       std::abs(wrapAngle(odom.z() - last.z())) >= config_.evidence_spacing_deg * M_PI / 180.0;
    if (!moved) return false;
  }
  scans_.push_back({odom, z_base, observations, travelled_m_});
  for (auto& c : candidates_) {
    const double s = scoreOn(c.T_map_odom, scans_.back());
    c.per_scan.push_back(s);
    c.log_likelihood += s;
  }
  dropOldScans();
  return true;
}

void PathEvidence::dropOldScans() {
  // The window is a stretch of path, not of time: odometry drifts with distance, and standing
  // still adds no new view of the building.
  while (scans_.size() > 1 && (travelled_m_ - scans_.front().travelled_m > config_.evidence_window_m ||
                               static_cast<int>(scans_.size()) > config_.evidence_max_scans)) {
    scans_.pop_front();
    for (auto& c : candidates_) {
      c.log_likelihood -= c.per_scan.front();
      c.per_scan.pop_front();
    }
  }
}

PathEvidence::Candidate PathEvidence::scored(const Pose2& T_map_odom) const {
  Candidate c;
  c.T_map_odom = T_map_odom;
  for (const auto& scan : scans_) {
    const double s = scoreOn(T_map_odom, scan);
    c.per_scan.push_back(s);
    c.log_likelihood += s;
  }
  return c;
}

void PathEvidence::propose(const Pose2& map_pose, const Pose2& odom) {
  if (!map_pose.allFinite()) return;
  Candidate fresh = scored(compose(map_pose, inverse(odom)));
  for (auto& c : candidates_)
    if (near(compose(c.T_map_odom, odom), map_pose, kSamePlaceM, kSamePlaceRad)) {
      if (fresh.log_likelihood > c.log_likelihood) c = std::move(fresh);
      return;
    }
  candidates_.push_back(std::move(fresh));
  const auto max = static_cast<std::size_t>(std::max(2, config_.evidence_max_candidates));
  if (candidates_.size() > max) {
    // The pool keeps the best: drop the one the path fits worst.
    const auto worst = std::min_element(candidates_.begin(), candidates_.end(), [](const Candidate& a, const Candidate& b) {
      return a.log_likelihood < b.log_likelihood;
    });
    candidates_.erase(worst);
  }
}

void PathEvidence::refine(Candidate& c, const Pose2& odom) const {
  // Pattern search on the pose now (x, y, yaw), halving the steps: the association is
  // discrete, so the likelihood has no useful gradient.
  Pose2 pose = compose(c.T_map_odom, odom);
  double step_m = 0.08, step_rad = 1.0 * M_PI / 180.0;
  for (int level = 0; level < 3; ++level, step_m *= 0.5, step_rad *= 0.5) {
    for (bool improved = true; improved;) {
      improved = false;
      for (const Pose2& delta : {Pose2(step_m, 0, 0), Pose2(-step_m, 0, 0), Pose2(0, step_m, 0), Pose2(0, -step_m, 0),
                                 Pose2(0, 0, step_rad), Pose2(0, 0, -step_rad)}) {
        const Pose2 moved = pose + delta;
        Candidate trial = scored(compose(moved, inverse(odom)));
        if (trial.log_likelihood > c.log_likelihood + 1e-9) {
          c = std::move(trial);
          pose = moved;
          improved = true;
        }
      }
    }
  }
}

double PathEvidence::logLikelihoodOf(const Pose2& map_pose, const Pose2& odom) const {
  const Pose2 T_map_odom = compose(map_pose, inverse(odom));
  double sum = 0;
  for (const auto& scan : scans_) sum += scoreOn(T_map_odom, scan);
  return sum;
}

void PathEvidence::proposeEveryFit(const std::vector<Observation>& observations, double z_base, const Pose2& odom) {
  ParticleFilterConfig every = config_;
  every.use_rooms = false;  // rooms_ holds every face for every room
  const auto fits = poseHypotheses(observations, z_base, rooms_, every, std::numeric_limits<std::size_t>::max());
  // Those that fit the scan within three clutter planes of the best fit.
  for (const auto& h : fits) {
    if (h.log_likelihood < fits.front().log_likelihood - 1.5 * config_.gate_mahalanobis2) break;
    propose({h.x, h.y, h.yaw}, odom);
  }
}

PathVerdict PathEvidence::verdict(const Pose2& odom) {
  PathVerdict v;
  v.candidates = static_cast<int>(candidates_.size());
  v.scans = static_cast<int>(scans_.size());
  v.window_m = scans_.empty() ? 0.0 : travelled_m_ - scans_.front().travelled_m;
  if (candidates_.empty() || scans_.empty()) return v;
  const auto by_score = [](const Candidate& a, const Candidate& b) { return a.log_likelihood < b.log_likelihood; };
  auto best = std::max_element(candidates_.begin(), candidates_.end(), by_score);
  refine(*best, odom);
  // The strongest rival elsewhere, fitted too; should it now beat the best, the roles swap.
  for (int round = 0; round < 3; ++round) {
    const Pose2 here = compose(best->T_map_odom, odom);
    auto rival = candidates_.end();
    for (auto it = candidates_.begin(); it != candidates_.end(); ++it)
      if (!near(compose(it->T_map_odom, odom), here, kOtherPlaceM, kOtherPlaceRad) &&
          (rival == candidates_.end() || it->log_likelihood > rival->log_likelihood))
        rival = it;
    if (rival == candidates_.end()) break;
    refine(*rival, odom);
    if (rival->log_likelihood <= best->log_likelihood) break;
    best = rival;
  }
  v.has_best = true;
  v.best = compose(best->T_map_odom, odom);
  v.best_log_likelihood = best->log_likelihood;
  double other = -std::numeric_limits<double>::infinity();
  for (const auto& c : candidates_)
    if (!near(compose(c.T_map_odom, odom), v.best, kOtherPlaceM, kOtherPlaceRad)) other = std::max(other, c.log_likelihood);
  v.margin = best->log_likelihood - other;
  return v;
}

}  // namespace bimloc::pf::detail
