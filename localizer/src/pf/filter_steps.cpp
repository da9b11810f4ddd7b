// The steps of ParticleFilter::update (particle_filter.cpp), each one concept, in its order.
#include "filter_impl.hpp"
#include "pose_settled.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bimloc::pf {

using detail::near;
using detail::wrapAngle;

std::vector<detail::Hypothesis> ParticleFilter::Impl::seedHypotheses(const std::vector<detail::Observation>& observations,
                                                                     double z, UpdateReport& report) {
  std::vector<detail::Hypothesis> hyps;
  if (!config.use_hypotheses) return hyps;
  // Between two of the window's scans, the seeds would propose the last one's places again
  // (ParticleFilterConfig::seeds_on_window_scans); the first weighing always seeds.
  if (config.seeds_on_window_scans && weighed_once && !evidence.wouldJoin(planarPose(odom))) return hyps;
  // The first weighing searches every room (its seeds place most particles); later ones a share
  // of them in turn, seed_poses_per_weighing poses' worth.
  detail::RoomShare share;
  share.poses = weighed_once ? static_cast<std::size_t>(std::max(0, config.seed_poses_per_weighing)) : 0;
  share.next_room = next_seed_room;
  hyps = detail::poseHypotheses(observations, z, rooms, config, static_cast<std::size_t>(config.max_hypotheses),
                                std::numeric_limits<double>::infinity(), false, &share);
  next_seed_room = share.next_room;
  report.seed_rooms = share.rooms_searched;
  if (prior.active())  // no pose the prior rules out, not even as a seed
    hyps.erase(std::remove_if(hyps.begin(), hyps.end(), [&](const detail::Hypothesis& h) { return !admitted({h.x, h.y, h.yaw}); }),
               hyps.end());
  report.hypotheses = static_cast<int>(hyps.size());
  const double n = static_cast<double>(particles.size());
  if (!weighed_once) report.injected = inject(hyps, static_cast<std::size_t>(config.initial_hypothesis_fraction * n));
  if (report.injected > 0) agreeing_updates = 0;
  return hyps;
}

double ParticleFilter::Impl::weigh(const std::vector<detail::Observation>& observations, double z, bool& annealing) {
  // Each particle's observations against its room's walls (paper, "Update"), with the sigmas
  // annealed at first.
  ParticleFilterConfig annealed = config;
  annealed.sigma_azimuth_deg *= anneal, annealed.sigma_elevation_deg *= anneal, annealed.sigma_d_m *= anneal;
  annealed.segment_margin_m *= anneal;
  annealing = anneal > 1.0;
  anneal = std::max(1.0, anneal * config.anneal_rate);
  double best_raw = -1e300;  // the best fit of any particle, at the final (unannealed) sigmas
  for (auto& p : particles) {
    const auto match = detail::matchObservations(p, z, observations, rooms, annealed);
    if (!annealing) best_raw = std::max(best_raw, match.log_likelihood);
    p.log_weight += config.likelihood_power * match.log_likelihood;
    if (prior.active() && !admitted({p.x, p.y, p.yaw})) p.log_weight -= config.likelihood_power * config.outside_rooms_penalty;
  }
  return best_raw;
}

detail::PathVerdict ParticleFilter::Impl::askThePath(const std::vector<detail::Observation>& observations,
                                                     const std::vector<detail::Hypothesis>& hyps, double z,
                                                     UpdateReport& report) {
  // This scan joins the window; the scan's best poses and the filter's best particle become
  // candidates.
  const detail::Pose2 now = planarPose(odom);
  evidence.addScan(now, z, observations, profile);
  for (std::size_t k = 0; k < hyps.size() && static_cast<int>(k) < config.evidence_proposals; ++k)
    evidence.propose({hyps[k].x, hyps[k].y, hyps[k].yaw}, now);
  const Particle& top = particles[heaviest()];
  evidence.propose({top.x, top.y, top.yaw}, now);
  detail::PathVerdict path = evidence.verdict(now);
  countSettled(path, report);
  report.path_margin = path.margin;
  if (path.has_best) report.path_best = path.best;
  report.path_candidates = path.candidates;
  report.path_rivals = path.rivals;
  return path;
}

void ParticleFilter::Impl::countSettled(const detail::PathVerdict& path, UpdateReport& report) const {
  const double bar = config.evidenceMargin();
  report.path_bound_held += path.loop_margin < bar && path.margin >= bar ? 1 : 0;
  report.path_fit_lowered += path.loop_margin >= bar && path.margin < bar ? 1 : 0;
}

void ParticleFilter::Impl::resetFromTheScan(const std::vector<detail::Hypothesis>& hyps, double best_raw, bool annealing,
                                            const detail::PathVerdict& path, bool decisive, UpdateReport& report) {
  // Sensor resetting: the particles explain the scan clearly worse than the plan can.
  // After convergence the filter tracks (paper: the S-Graph takes over): no more jumps. While
  // the path evidence is decisive, the scan's poses elsewhere are places it has refuted (each
  // was a candidate): only those at its best place may be drawn. A few particles 15 m away,
  // drawn at the heaviest weight, kept the cloud's spread above the convergence radius.
  if (!weighed_once || T_map_odom || hyps.empty() || annealing || hyps[0].log_likelihood <= best_raw + config.injection_margin)
    return;
  std::vector<detail::Hypothesis> reset;
  for (const auto& h : hyps)
    if (!decisive || atPathBest({h.x, h.y, h.yaw}, path)) reset.push_back(h);
  const double n = static_cast<double>(particles.size());
  report.injected += inject(reset, static_cast<std::size_t>(config.injection_fraction * n));
  if (!reset.empty() && !decisive) agreeing_updates = 0;  // drawn at the best place: no jump
}

void ParticleFilter::Impl::followThePath(const detail::PathVerdict& path, UpdateReport& report) {
  // The path fits one place decisively better than any other: a share of the particles goes
  // to its pose, heavier than any (their evidence is the whole window, not one scan). Where
  // the particles are elsewhere, that moves them; where they are already around it, the
  // window's fitted pose tightens the cloud (one scan's planes alone leave it wide).
  const Eigen::Vector3d before = mean(normalisedWeights());
  detail::Hypothesis h;
  h.x = path.best.x(), h.y = path.best.y(), h.yaw = path.best.z();
  const double n = static_cast<double>(particles.size());
  report.injected += inject({h}, static_cast<std::size_t>(config.evidence_injection_fraction * n),
                            config.likelihood_power * config.evidenceMargin());
  // The path fits every other place worse by at least the bar: particles elsewhere (a
  // look-alike the scans alone keep alive) pay the bar, tempered as a scan is, at each
  // decisive weighing. They fade over a few weighings instead of holding the cloud's spread,
  // and the convergence test, open for as long, waited on them for up to 13 s.
  for (auto& p : particles)
    if (!atPathBest({p.x, p.y, p.yaw}, path)) p.log_weight -= config.likelihood_power * config.evidenceMargin();
  if (!near(before, path.best, config.converged_position_m, yawTolerance())) agreeing_updates = 0;
}

bool ParticleFilter::Impl::checkConvergence(const std::vector<detail::Observation>& observations, double z,
                                            detail::PathVerdict& path, bool decisive, const std::vector<double>& w,
                                            const Eigen::Vector3d& mean, UpdateReport& report) {
  // Paper: the best particle close to the weighted mean, for several updates in a row; and
  // (beyond the paper) the path decisively better explained there than anywhere else.
  const bool tracking = T_map_odom.has_value();
  const double yaw_tol = yawTolerance();
  const Particle& top = particles[best];
  report.associated = detail::matchObservations(top, z, observations, rooms, config).associated;
  double var_xy = 0, var_yaw = 0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    const auto& p = particles[i];
    var_xy += w[i] * ((p.x - mean.x()) * (p.x - mean.x()) + (p.y - mean.y()) * (p.y - mean.y()));
    var_yaw += w[i] * wrapAngle(p.yaw - mean.z()) * wrapAngle(p.yaw - mean.z());
  }
  const bool clustered = near({top.x, top.y, top.yaw}, mean, config.converged_position_m, yaw_tol) &&
                         std::sqrt(var_xy) < config.converged_position_m && std::sqrt(var_yaw) < yaw_tol;
  // Where the cloud says the robot is: its weighted mean once it has gathered (the paper's
  // test). While the path evidence is decisive, this weighing has just moved a share of the
  // particles to its best place, heavier than any, and made every particle elsewhere pay the
  // bar (followThePath): what is still elsewhere is a place the evidence refuted, which the
  // next weighings would only fade out. Waiting for that adds no evidence, only a weighing
  // (0.4-1 s; on a start decided by its first scan, all of the delay), so the top particle,
  // one of those moved, stands for the cloud, and a convergence drops the refuted particles
  // (below): the cloud then is where the paper's test would have found it.
  const Eigen::Vector3d where = clustered ? mean : Eigen::Vector3d(top.x, top.y, top.yaw);
  bool agrees = tracking ? clustered : decisive && near(where, path.best, config.converged_position_m, yaw_tol);
  bool searched = true;
  std::optional<detail::Pose2> fine;  // the pose within the place, refined (and settled)
  if (agrees && !tracking) {
    // About to count towards convergence: first make sure no look-alike is missing from the
    // candidates, then ask again; and then whether the pose within the place is settled.
    const detail::Pose2 now = planarPose(odom);
    searched = evidence.proposeEveryFit(observations, z, now, path.best);
    path = evidence.verdict(now);
    countSettled(path, report);
    report.path_margin = path.margin, report.path_best = path.best, report.path_candidates = path.candidates;
    report.path_rivals = path.rivals;
    agrees = searched && path.pose_fixed && path.margin >= config.evidenceMargin() &&
             near(where, path.best, config.converged_position_m, yaw_tol);
    if (agrees) {
      fine = settledPose(top, report);
      agrees = fine.has_value();
    }
  }
  // A scan whose search could not vouch for the rivals checked the verdict against nothing: it
  // neither counts towards convergence nor breaks the run of agreeing ones.
  if (searched) agreeing_updates = agrees ? agreeing_updates + 1 : 0;
  bool dropped = false;  // declared now, the cloud not gathered: the refuted particles dropped
  if (agreeing_updates >= config.converged_updates) {
    // Paper Eq.: map <- odom = best particle (+) inverse of the odometry pose. After that it
    // follows the filter's weighted mean (tracking, until an S-Graph takes over): smoother
    // than the best particle, which the roughening keeps shaking.
    Particle at = top;
    if (T_map_odom) {
      at.x = mean.x(), at.y = mean.y(), at.yaw = mean.z();
    } else {
      // The place is decided, and the pose within it fitted again with the sensor's own noise
      // (settledPose, this update: the run of agreeing updates ends with this one, so `fine`
      // is set; the top particle's own pose would stand otherwise).
      const detail::Pose2 pose = fine.value_or(detail::Pose2(top.x, top.y, top.yaw));
      at.x = pose.x(), at.y = pose.y(), at.yaw = pose.z();
    }
    dropped = !T_map_odom && !clustered;
    T_map_odom = poseOf(at) * odom.inverse();
    if (dropped)
      for (auto& p : particles)
        if (!atPathBest({p.x, p.y, p.yaw}, path)) p.log_weight = -std::numeric_limits<double>::infinity();
  }
  report.converged = T_map_odom.has_value();
  return dropped;
}

std::optional<detail::Pose2> ParticleFilter::Impl::settledPose(const Particle& top, UpdateReport& report) const {
  // The pose within the decided place, fitted again with the sensor's own noise on the latest
  // scans (pose_refinement.hpp): the wide sigmas let furniture before a wall pull it.
  const detail::Pose2 now = planarPose(odom);
  const auto scans = evidence.latestScans(refinement.window_m);
  const auto model = detail::refinementModel(config, refinement);
  const detail::Pose2 fine = detail::refinePose({top.x, top.y, top.yaw}, now, scans, evidence.everyFace(), model, refinement);
  if (!config.settle_pose) return fine;
  // Settled when the scans explain it better than every pose beyond the convergence radius,
  // by the bar the places must pass, counted per face (pose_settled.hpp): furniture can fake
  // one wall, as between places.
  const detail::LocalMargin local =
      detail::localMargin(fine, now, scans, evidence.everyFace(), model, refinement, config.converged_position_m, config.evidenceMargin());
  report.pose_margin = local.margin;
  if (local.margin < config.evidenceMargin()) return std::nullopt;
  return fine;
}

void ParticleFilter::Impl::fitPlaces(UpdateReport& report) const {
  // Each place the path leaves, fitted within itself as settledPose fits the converged one:
  // what the path evidence ranks is which place, and its wide model (drift over the whole
  // window) lets furniture before a wall pull the pose within the place.
  if (T_map_odom || !report.path_best) return;
  const detail::Pose2 now = planarPose(odom);
  const auto scans = evidence.latestScans(refinement.window_m);
  const auto model = detail::refinementModel(config, refinement);
  // The grid at twice the step: the pattern search after it starts at half the grid's step, so
  // a fit's basin (sigma_d about 0.07 m each way) is still reached from the nearest cell, at a
  // quarter of the cost (this runs at every weighing while searching, for every place).
  detail::PoseRefinementConfig listing = refinement;
  listing.grid_step_m = 2.0 * refinement.grid_step_m;
  std::vector<std::pair<Eigen::Vector3d, double>> coarse{{*report.path_best, 0.0}};
  coarse.insert(coarse.end(), report.path_rivals.begin(), report.path_rivals.end());
  std::vector<std::pair<Eigen::Vector3d, double>> fitted;
  for (const auto& [pose, margin] : coarse) {
    const detail::Pose2 fine = detail::refinePose(pose, now, scans, evidence.everyFace(), model, listing);
    // Two candidates of one place (within the bounds that make another place) are listed once.
    const bool listed = std::any_of(fitted.begin(), fitted.end(), [&](const auto& p) {
      return near(p.first, fine, detail::kOtherPlaceM, detail::kOtherPlaceRad);
    });
    if (!listed) fitted.emplace_back(fine, margin);
  }
  report.path_best = fitted.front().first;
  report.path_rivals.assign(fitted.begin() + 1, fitted.end());
  report.places_fitted = true;
}

void ParticleFilter::Impl::resampleAfter(const std::vector<double>& w, UpdateReport& report) {
  const auto tracking_count = static_cast<std::size_t>(std::max(1, config.tracking_particles));
  const double n = static_cast<double>(particles.size());
  if (T_map_odom && particles.size() > tracking_count) {
    resample(w, tracking_count);
    report.resampled = true;
  } else if (report.ess < config.resample_ess_fraction * n) {
    resample(w, particles.size());
    report.resampled = true;
  } else {
    // Keep the weights bounded: only their differences matter.
    const double top = particles[best].log_weight;
    for (auto& p : particles) p.log_weight -= top;
  }
}

}  // namespace bimloc::pf
