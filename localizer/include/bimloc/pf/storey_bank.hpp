// Global localization when the storey is not known: one ParticleFilter per storey that could
// hold the robot, every scan to all of them, and the storey decided only when one storey's
// filter has converged and the path fits its place better than the best place of every other
// storey, by the same bar and counted the same way (once per wall face) as the filter's own
// decision between places of one storey. Until then the candidates are reported.
//
// What is not used: the odometry's height. The robot's start height is unknown, so a storey's
// elevation cannot be matched to it. An altitude (a barometer) is: its log-likelihood per
// storey (setStoreyLogLikelihoods) enters the choice of the leader and the margin over the
// other storeys, in the same units as the walls' (a log-likelihood ratio).
#pragma once

#include <bimloc/pf/particle_filter.hpp>

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

namespace bimloc::pf {

struct StoreyCandidate {
  std::size_t storey = 0;  // index into Building::storeys
  int particles = 0;       // at the start
  bool converged = false;  // its filter converged (on its storey)
  std::optional<Eigen::Vector3d> path_best;  // its best place now (map x, y, yaw), if any yet
  double path_log_likelihood = 0;            // the window's log-likelihood there
};

struct StoreyBankReport {
  UpdateReport filter;        // of the leading storey's filter (the decided one, once decided)
  std::size_t leader = 0;     // storey index of the leading (or decided) storey
  bool decided = false;       // the storey is decided (on this update or before)
  // How much better the path fits the leader's place than the best place of any other storey
  // (per distinct face, as UpdateReport::path_margin, plus the storey evidence's log-likelihood
  // ratio): +inf with one storey left, unset while the leader's filter has not converged (not asked).
  std::optional<double> storey_margin;
  std::vector<StoreyCandidate> candidates;  // the storeys still considered, leader first
};

class StoreyBank {
 public:
  // The storeys that can hold the robot: those with walls (the landmarks) and rooms (where
  // the filter spreads its particles).
  static std::vector<std::size_t> candidateStoreys(const bim::Building& building);

  // A filter per storey of `storeys` (indices into building.storeys, which must outlive the
  // bank). With one storey, exactly the ParticleFilter of that storey with `config`. With
  // several, config.particles is split between them in proportion to their room area (the
  // same density everywhere), each with its own seed; a storey holding none of
  // config.prior_rooms is left out. Throws std::invalid_argument when no storey is left.
  StoreyBank(const bim::Building& building, const std::vector<std::size_t>& storeys, const Eigen::Isometry3d& T_base_lidar,
             const ParticleFilterConfig& config);
  ~StoreyBank();
  StoreyBank(StoreyBank&&) noexcept;

  // Evidence on the storey from outside the walls (the altitude): a log-likelihood per storey,
  // indexed as Building::storeys (up to a common constant). It is added to each storey's path
  // log-likelihood where the leader is chosen, and the leader's less a rival's to the margin
  // over that rival. Empty (the default): the walls alone.
  void setStoreyLogLikelihoods(std::vector<double> by_storey);

  void predict(const Eigen::Isometry3d& T_odom_base);
  bool wantsObservations() const;
  StoreyBankReport update(const std::vector<planes::ObservedPlane>& walls, const RangeProfile* profile = nullptr);

  // Converged: the storey is decided and its filter converged.
  bool converged() const;
  std::optional<std::size_t> storey() const;  // the decided storey
  std::size_t leader() const;                 // the decided storey, else the leading one
  const ParticleFilter& filter() const;       // the leader's filter
  std::optional<Eigen::Isometry3d> T_map_odom() const;  // once converged
  Eigen::Isometry3d T_map_base() const;                  // the leader's estimate
  int estimateRoom() const;                              // in the leader's storey
  std::vector<std::size_t> storeys() const;              // still considered

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bimloc::pf
