#include "path_evidence.hpp"

#include "hypotheses.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>

namespace bimloc::pf::detail {

bool near(const Pose2& a, const Pose2& b, double metres, double radians) {
  const double dx = a.x() - b.x(), dy = a.y() - b.y();
  return dx * dx + dy * dy < metres * metres && std::abs(wrapAngle(a.z() - b.z())) < radians;
}

namespace {

// The sigmas of the window's error model (beyond the scan's own): the scans are placed by
// odometry, which drifts, and the transform fitted to the whole window splits that drift,
// so each scan may be off by the drift over half the window's path (`path_m`); and a wall
// stands within its as-built tolerance of the plan.
ParticleFilterConfig windowModel(ParticleFilterConfig c, double path_m) {
  const double half = 0.5 * path_m;
  const double drift_m = c.evidence_drift_fraction * half, yaw_rad = c.evidence_yaw_drift_rad_per_m * half;
  c.sigma_d_m = std::sqrt(c.sigma_d_m * c.sigma_d_m + drift_m * drift_m +
                          c.evidence_plan_tolerance_m * c.evidence_plan_tolerance_m);
  const double az = c.sigma_azimuth_deg * M_PI / 180.0;
  c.sigma_azimuth_deg = std::sqrt(az * az + yaw_rad * yaw_rad) * 180.0 / M_PI;
  return c;
}

// The path the window's model is made for: the whole window, or with evidence_drift_of_window
// the path the window covers, rounded up to window / 2^k (k <= 4: at least 0.94 m of a 15 m
// window), so that a candidate's scores are remade only when the model's path doubles.
double modelPath(const ParticleFilterConfig& c, double covered_m) {
  double path = c.evidence_window_m;
  if (!c.evidence_drift_of_window) return path;
  for (int k = 0; k < 4 && 0.5 * path >= covered_m; ++k) path *= 0.5;
  return path;
}

}  // namespace

PathEvidence::PathEvidence(const bim::Storey& storey, const ParticleFilterConfig& config)
    : rooms_(storey, /*use_rooms=*/false),
      base_config_(config),
      model_path_m_(modelPath(config, 0.0)),
      config_(windowModel(config, model_path_m_)) {
  if (config.free_space_evidence) {
    free_space_map_ = std::make_shared<const FreeSpaceMap>(storey);
    // A ray's range is off by the scan's placement along the window (drift, as the planes'),
    // not by the planes' own fitting noise.
    free_space_walls_ = storey.walls.size();
    free_space_ = FreeSpaceParams::of(config, config.evidence_drift_fraction * 0.5 * config.evidence_window_m);
  }
  for (const auto& l : rooms_.landmarks(0)) {
    if (l.id >= static_cast<int>(faces_.size())) faces_.resize(static_cast<std::size_t>(l.id) + 1);
    faces_[static_cast<std::size_t>(l.id)] = {l.normal.head<2>(), l.start, l.direction, l.line_lo_m, l.line_hi_m};
  }
}

PathEvidence::ScanScore PathEvidence::scoreOn(const Pose2& T_map_odom, const Scan& scan, bool detailed) const {
  return scoreOn(T_map_odom, std::cos(T_map_odom.z()), std::sin(T_map_odom.z()), scan, detailed);
}

PathEvidence::ScanScore PathEvidence::scoreOn(const Pose2& T_map_odom, double c, double s_yaw, const Scan& scan, bool detailed,
                                              const FaceShortlist* shortlist) const {
  const Pose2 pose = compose(T_map_odom, c, s_yaw, scan.odom);
  Particle p;
  p.x = pose.x(), p.y = pose.y(), p.yaw = pose.z(), p.room = rooms_.roomAt(pose.x(), pose.y());
  // A list that does not hold this pose is not asked (the index is): the same match either way.
  if (shortlist && !shortlist->holds(p)) shortlist = nullptr;
  ScanScore s;
  s.out_of_rooms = p.room < 0;
  s.matched = matchObservations(p, scan.z_base, scan.observations, rooms_, config_, detailed ? &s.per_observation : nullptr,
                                /*out_of_rooms_penalised=*/false, -std::numeric_limits<double>::infinity(), -1.0, shortlist)
                  .log_likelihood;
  return s;
}

std::vector<FaceShortlist> PathEvidence::shortlists(const Pose2& pose_now, const Pose2& odom) const {
  // The refinement's lists (windowShortlists) over the whole window, kRefineShortlistM about
  // the pose, the faces whole (opening margin -1: the path evidence's association ignores holes).
  std::vector<RefinementScan> window;
  window.reserve(scans_.size());
  for (const auto& scan : scans_) window.push_back({scan.odom, scan.z_base, &scan.observations});
  PoseRefinementConfig around;
  around.search_m = kRefineShortlistM;
  around.opening_margin_m = -1.0;
  return windowShortlists(pose_now, odom, window, rooms_, config_, around);
}

double PathEvidence::total(double matched_sum, int out_of_rooms) const {
  const double n = std::max<double>(1.0, static_cast<double>(scans_.size()));
  return matched_sum - 0.5 * config_.gate_mahalanobis2 * static_cast<double>(out_of_rooms) / n;
}

bool PathEvidence::addScan(const Pose2& odom, double z_base, const std::vector<Observation>& observations,
                           const RangeProfile* profile) {
  if (has_last_odom_) travelled_m_ += std::hypot(odom.x() - last_odom_.x(), odom.y() - last_odom_.y());
  has_last_odom_ = true;
  last_odom_ = odom;
  if (!wouldJoin(odom)) return false;
  scans_.push_back({odom, z_base, observations, travelled_m_, free_space_map_ && profile ? *profile : RangeProfile{}});
  const double path = modelPath(base_config_, std::min(base_config_.evidence_window_m, travelled_m_ - scans_.front().travelled_m));
  if (path > model_path_m_) {
    // The window now covers a longer path: its drift is larger, and every candidate is scored
    // again under it (at most four times a run), the new scan with them.
    model_path_m_ = path;
    config_ = windowModel(base_config_, path);
    for (auto& c : candidates_) c = scored(c.T_map_odom);
  } else {
    for (auto& c : candidates_) {
      ScanScore s = scoreOn(c.T_map_odom, scans_.back(), true);
      c.matched_sum += s.matched;
      c.out_of_rooms += s.out_of_rooms ? 1 : 0;
      c.per_scan.push_back(std::move(s));
    }
  }
  dropOldScans();
  for (auto& c : candidates_) c.log_likelihood = total(c.matched_sum, c.out_of_rooms);
  return true;
}

bool PathEvidence::wouldJoin(const Pose2& odom) const {
  if (scans_.empty()) return true;
  const Pose2& last = scans_.back().odom;
  return std::hypot(odom.x() - last.x(), odom.y() - last.y()) >= config_.evidence_spacing_m ||
         std::abs(wrapAngle(odom.z() - last.z())) >= config_.evidence_spacing_deg * M_PI / 180.0;
}

void PathEvidence::dropOldScans() {
  // The window is a stretch of path, not of time: odometry drifts with distance, and standing
  // still adds no new view of the building.
  while (scans_.size() > 1 && (travelled_m_ - scans_.front().travelled_m > config_.evidence_window_m ||
                               static_cast<int>(scans_.size()) > config_.evidence_max_scans)) {
    scans_.pop_front();
    for (auto& c : candidates_) {
      c.matched_sum -= c.per_scan.front().matched;
      c.out_of_rooms -= c.per_scan.front().out_of_rooms ? 1 : 0;
      c.per_scan.pop_front();
    }
  }
}

PathEvidence::Candidate PathEvidence::scored(const Pose2& T_map_odom, bool detailed, const std::vector<FaceShortlist>* shortlists) const {
  return *scoredAbove(T_map_odom, detailed, -std::numeric_limits<double>::infinity(), false, shortlists);
}

std::optional<PathEvidence::Candidate> PathEvidence::scoredAbove(const Pose2& T_map_odom, bool detailed, double floor, bool or_equal,
                                                                 const std::vector<FaceShortlist>* shortlists) const {
  Candidate c;
  c.T_map_odom = T_map_odom;
  const double cos_yaw = std::cos(T_map_odom.z()), sin_yaw = std::sin(T_map_odom.z());  // one transform, every scan
  if (shortlists && shortlists->size() != scans_.size()) shortlists = nullptr;
  for (std::size_t k = 0; k < scans_.size(); ++k) {
    const Scan& scan = scans_[k];
    ScanScore s = scoreOn(T_map_odom, cos_yaw, sin_yaw, scan, detailed, shortlists ? &(*shortlists)[k] : nullptr);
    c.matched_sum += s.matched;
    c.out_of_rooms += s.out_of_rooms ? 1 : 0;
    if (detailed) c.per_scan.push_back(std::move(s));
    const double so_far = total(c.matched_sum, c.out_of_rooms);
    if (so_far < floor || (or_equal && so_far == floor)) return std::nullopt;
  }
  c.log_likelihood = total(c.matched_sum, c.out_of_rooms);
  return c;
}

void PathEvidence::propose(const Pose2& map_pose, const Pose2& odom) {
  if (!map_pose.allFinite()) return;
  const Pose2 T_map_odom = compose(map_pose, inverse(odom));
  if (!admitted(T_map_odom)) return;
  // Near a candidate, the proposal replaces it only when it fits the path better.
  for (auto& c : candidates_)
    if (near(compose(c.T_map_odom, odom), map_pose, kSamePlaceM, kSamePlaceRad)) {
      if (auto fresh = scoredAbove(T_map_odom, true, c.log_likelihood, /*or_equal=*/true)) c = std::move(*fresh);
      return;
    }
  // Elsewhere it joins the pool; a full pool then drops the candidate the path fits worst,
  // the first of equals: the proposal itself only when it is worse than all of them.
  const auto max = static_cast<std::size_t>(std::max(2, config_.evidence_max_candidates));
  double floor = -std::numeric_limits<double>::infinity();
  const auto by_fit = [](const Candidate& a, const Candidate& b) { return a.log_likelihood < b.log_likelihood; };
  if (candidates_.size() >= max && !candidates_.empty())
    floor = std::min_element(candidates_.begin(), candidates_.end(), by_fit)->log_likelihood;
  auto fresh = scoredAbove(T_map_odom, true, floor, /*or_equal=*/false);
  if (!fresh) return;
  candidates_.push_back(std::move(*fresh));
  if (candidates_.size() > max) candidates_.erase(std::min_element(candidates_.begin(), candidates_.end(), by_fit));
}

bool PathEvidence::admitted(const Pose2& T_map_odom) const {
  return !prior_ || prior_->admits(compose(T_map_odom, odom_start_));
}

void PathEvidence::refine(Candidate& c, const Pose2& odom) const {
  // Pattern search on the pose now (x, y, yaw), halving the steps: the association is
  // discrete, so the likelihood has no useful gradient. Trials are scored without detail;
  // the pose kept is scored in full once. A trial whose start the prior rules out is no
  // place: a turn of a few degrees now moves the start by as many tenths of a metre at 8 m,
  // and the Duplex's 180 deg twin, proposed with its start just inside the prior's flat,
  // walked out of it by such steps and stayed a rival of margin 0 (A203, 90 s undecided).
  Pose2 pose = compose(c.T_map_odom, odom);
  double best = c.log_likelihood;
  bool moved_at_all = false;
  // Each scan's faces near the pose, found once for the search's region: a trial there is
  // matched from the lists, one beyond through the index, with the same result (FaceShortlist).
  const std::vector<FaceShortlist> lists = shortlists(pose, odom);
  double step_m = 0.08, step_rad = 1.0 * M_PI / 180.0;
  for (int level = 0; level < 3; ++level, step_m *= 0.5, step_rad *= 0.5) {
    for (bool improved = true; improved;) {
      improved = false;
      for (const Pose2& delta : {Pose2(step_m, 0, 0), Pose2(-step_m, 0, 0), Pose2(0, step_m, 0), Pose2(0, -step_m, 0),
                                 Pose2(0, 0, step_rad), Pose2(0, 0, -step_rad)}) {
        const Pose2 moved = pose + delta;
        const Pose2 T_map_odom = compose(moved, inverse(odom));
        if (!admitted(T_map_odom)) continue;
        const auto trial = scoredAbove(T_map_odom, false, best + 1e-9, /*or_equal=*/true, &lists);
        if (trial && trial->log_likelihood > best + 1e-9) {
          best = trial->log_likelihood;
          pose = moved;
          improved = moved_at_all = true;
        }
      }
    }
  }
  if (moved_at_all) c = scored(compose(pose, inverse(odom)), true, &lists);
}

double PathEvidence::logLikelihoodOf(const Pose2& map_pose, const Pose2& odom) const {
  return scored(compose(map_pose, inverse(odom)), false).log_likelihood;
}

Observation seenFrom(const Observation& o, const Pose2& rel) {
  const double c = std::cos(rel.z()), s = std::sin(rel.z());
  Observation m = o;
  m.normal_base = Eigen::Vector3d(c * o.normal_base.x() - s * o.normal_base.y(), s * o.normal_base.x() + c * o.normal_base.y(),
                                  o.normal_base.z());
  m.azimuth_base = wrapAngle(o.azimuth_base + rel.z());
  // The plane n.p + d = 0 in the old frame is n'.p' + d - n'.t = 0 in the new one.
  m.d_offset = o.d_offset - m.normal_base.head<2>().dot(rel.head<2>());
  const auto moved = [&](const Eigen::Vector2d& q) { return Eigen::Vector2d(c * q.x() - s * q.y() + rel.x(), s * q.x() + c * q.y() + rel.y()); };
  m.centroid_base = moved(o.centroid_base);
  m.span_middle_base = moved(o.span_middle_base);  // not finite stays not finite
  const double height2 = std::max(0.0, o.range_m * o.range_m - o.centroid_base.squaredNorm());
  m.range_m = std::sqrt(m.centroid_base.squaredNorm() + height2);
  return m;
}

bool PathEvidence::proposeEveryFit(const std::vector<Observation>& observations, double z_base, const Pose2& odom,
                                   const Pose2& best_now) {
  ParticleFilterConfig every = config_;
  every.use_rooms = false;  // rooms_ holds every face for every room
  // The sources, in order: this scan; the latest scans of the window, each alone; then this
  // scan with the latest scans merged in (a robot turning in a closet sees two walls per scan,
  // never enough to fix a pose alone). The first source whose fits include the best place is
  // the search: every place it explains about as well is then among the candidates.
  // One source searched: its fits within three clutter planes of its best fit, moved on to
  // now, join the candidates. Only those are proposed: the rest need not be scored to the end
  // (the same fits, the same bits, far fewer observations matched).
  const double wanted = 1.5 * config_.gate_mahalanobis2;
  const auto search = [&](const std::vector<Observation>& source, double z, const Pose2& at) {
    const auto fits = poseHypotheses(source, z, rooms_, every, std::numeric_limits<std::size_t>::max(), wanted,
                                     /*outside_rooms=*/true);
    const Pose2 since = compose(inverse(at), odom);
    bool found_best = false;
    for (const auto& h : fits) {
      if (h.log_likelihood < fits.front().log_likelihood - wanted) break;
      const Pose2 now = compose({h.x, h.y, h.yaw}, since);
      found_best |= near(now, best_now, kOtherPlaceM, kOtherPlaceRad);
      propose(now, odom);
    }
    return found_best;
  };
  // (The latest scan of the window is often this one: skipped.)
  std::vector<const Scan*> latest;
  for (auto it = scans_.rbegin(); it != scans_.rend() && latest.size() < 3; ++it)
    if (it->odom != odom) latest.push_back(&*it);
  if (search(observations, z_base, odom)) return true;
  for (const Scan* scan : latest)
    if (search(scan->observations, scan->z_base, scan->odom)) return true;
  // Merged only when every scan alone failed (the merge copies the observations).
  std::vector<Observation> merged = observations;
  for (const Scan* scan : latest) {
    const Pose2 rel = compose(inverse(odom), scan->odom);
    for (const auto& o : scan->observations) merged.push_back(seenFrom(o, rel));
    if (search(merged, z_base, odom)) return true;
  }
  return false;
}

PathEvidence::WindowFit PathEvidence::windowFit(const Pose2& map_pose, const Pose2& odom) const {
  Candidate c = scored(compose(map_pose, inverse(odom)), true);
  WindowFit fit;
  for (auto& s : c.per_scan) fit.out_of_rooms.push_back(s.out_of_rooms), fit.matches.push_back(std::move(s.per_observation));
  return fit;
}

std::vector<RefinementScan> PathEvidence::latestScans(double path_m) const {
  std::vector<RefinementScan> out;
  for (auto it = scans_.rbegin(); it != scans_.rend(); ++it) {
    if (!out.empty() && travelled_m_ - it->travelled_m > path_m) break;
    out.push_back({it->odom, it->z_base, &it->observations});
  }
  std::reverse(out.begin(), out.end());
  return out;
}

}  // namespace bimloc::pf::detail
