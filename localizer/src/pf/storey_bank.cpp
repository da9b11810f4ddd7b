#include <bimloc/pf/storey_bank.hpp>

#include "filter_access.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace bimloc::pf {
namespace {

using detail::FilterAccess;
using detail::PathEvidence;
using detail::Pose2;

// A storey with little room area still gets enough particles for a room: the proportional
// share alone would leave a small storey (a basement of two rooms) almost empty.
constexpr int kMinShareDivisor = 20;
// Farther than this from the filter's estimate, the path's best place is not where the filter
// converged: its estimate is weighed instead (the bounds of a false convergence).
constexpr double kSamePlaceM = 0.5;
constexpr double kSamePlaceRad = 10.0 * M_PI / 180.0;

double roomArea(const bim::Storey& storey) {
  double area = 0;
  for (const auto& r : storey.rooms) area += std::max(0.0, r.area_m2);
  return area;
}

// The margin of place P (one storey) over place Q (another), counted by the path evidence's
// per-face rule (detail::FaceMargin). The faces of the two storeys are different faces: Q's
// are keyed apart.
double crossMargin(const PathEvidence::WindowFit& p, const PathEvidence::WindowFit& q, double gate) {
  detail::FaceMargin margin;  // Q's faces keyed apart from P's (FaceMargin::kRivalKeys)
  const std::size_t scans = std::min(p.matches.size(), q.matches.size());
  for (std::size_t k = 0; k < scans; ++k) {
    margin.addScan(p.out_of_rooms[k], q.out_of_rooms[k]);
    for (std::size_t o = 0; o < p.matches[k].size() && o < q.matches[k].size(); ++o) margin.add(p.matches[k][o], q.matches[k][o]);
  }
  return margin.total(gate, static_cast<double>(scans));
}

}  // namespace

struct StoreyBank::Impl {
  struct Entry;
  static Entry entry(std::size_t storey, int particles, std::unique_ptr<ParticleFilter> filter);
  struct Entry {
    std::size_t storey = 0;
    int particles = 0;
    std::unique_ptr<ParticleFilter> filter;
    std::optional<Eigen::Vector3d> best;                 // the path evidence's best place, last weighing
    std::vector<Eigen::Vector3d> rivals;                 // and the places nearly as good
    double log_likelihood = -std::numeric_limits<double>::infinity();
  };
  ParticleFilterConfig config;
  std::vector<Entry> entries;
  std::size_t leader = 0;  // index into entries
  bool decided = false;
  std::optional<double> margin;
  std::vector<double> storey_ll;  // setStoreyLogLikelihoods(), by Building storey index

  // The evidence from outside the walls on an entry's storey (0 without any).
  double storeyLogLikelihood(std::size_t k) const {
    const std::size_t s = entries[k].storey;
    return s < storey_ll.size() ? storey_ll[s] : 0.0;
  }

  // The leader's place to weigh against the other storeys: the path's best place where the
  // filter converged, else the filter's estimate.
  Pose2 leaderPlace() const {
    const Entry& e = entries[leader];
    const Pose2 estimate = planarPose(e.filter->T_map_base());
    return e.best && detail::near(*e.best, estimate, kSamePlaceM, kSamePlaceRad) ? *e.best : estimate;
  }
  // The margin of the leader's place over the best places of every other storey: the walls'
  // (crossMargin) plus the altitude's log-likelihood ratio between the two storeys (one
  // reading, counted once: its error is mostly an offset the window's scans share).
  double marginOverOthers() const {
    const PathEvidence::WindowFit here = FilterAccess::windowFit(*entries[leader].filter, leaderPlace());
    double margin = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < entries.size(); ++j) {
      if (j == leader || !entries[j].best) continue;
      const double storey_ratio = storeyLogLikelihood(leader) - storeyLogLikelihood(j);
      std::vector<Eigen::Vector3d> places{*entries[j].best};
      places.insert(places.end(), entries[j].rivals.begin(), entries[j].rivals.end());
      for (const auto& q : places)
        margin = std::min(margin, crossMargin(here, FilterAccess::windowFit(*entries[j].filter, q), config.gate_mahalanobis2) +
                                      storey_ratio);
    }
    return margin;
  }
};

StoreyBank::Impl::Entry StoreyBank::Impl::entry(std::size_t storey, int particles, std::unique_ptr<ParticleFilter> filter) {
  Entry e;
  e.storey = storey, e.particles = particles, e.filter = std::move(filter);
  return e;
}

std::vector<std::size_t> StoreyBank::candidateStoreys(const bim::Building& building) {
  std::vector<std::size_t> out;
  for (std::size_t s = 0; s < building.storeys.size(); ++s)
    if (!building.storeys[s].walls.empty() && !building.storeys[s].rooms.empty()) out.push_back(s);
  return out;
}

StoreyBank::StoreyBank(const bim::Building& building, const std::vector<std::size_t>& storeys,
                       const Eigen::Isometry3d& T_base_lidar, const ParticleFilterConfig& config)
    : impl_(std::make_unique<Impl>()) {
  auto& m = *impl_;
  m.config = config;
  const auto entry = &Impl::entry;
  if (storeys.size() == 1) {
    // One storey: the filter as it always was, every particle and the seed as given.
    const std::size_t s = storeys.front();
    m.entries.push_back(entry(s, config.particles, std::make_unique<ParticleFilter>(building.storeys.at(s), T_base_lidar, config)));
    return;
  }
  // Several: only storeys where the prior's rooms are (each filter told the ones it holds).
  std::vector<std::pair<std::size_t, std::vector<std::string>>> kept;
  double total_area = 0;
  for (const std::size_t s : storeys) {
    const bim::Storey& storey = building.storeys.at(s);
    std::vector<std::string> prior;
    for (const auto& name : config.prior_rooms)
      if (storey.findRoom(name)) prior.push_back(name);
    if (!config.prior_rooms.empty() && prior.empty()) continue;
    kept.emplace_back(s, prior);
    total_area += roomArea(storey);
  }
  if (kept.empty()) throw std::invalid_argument("no storey to localize on (none has walls, rooms and the prior's rooms)");
  for (const auto& [s, prior] : kept) {
    const bim::Storey& storey = building.storeys[s];
    ParticleFilterConfig c = config;
    c.prior_rooms = prior;
    const double share = total_area > 0 ? roomArea(storey) / total_area : 1.0 / static_cast<double>(kept.size());
    c.particles = std::max(config.particles / kMinShareDivisor, static_cast<int>(std::lround(share * config.particles)));
    c.seed = config.seed + 0x9E3779B97F4A7C15ull * (s + 1);
    m.entries.push_back(entry(s, c.particles, std::make_unique<ParticleFilter>(storey, T_base_lidar, c)));
  }
}

StoreyBank::~StoreyBank() = default;
StoreyBank::StoreyBank(StoreyBank&&) noexcept = default;

void StoreyBank::setStoreyLogLikelihoods(std::vector<double> by_storey) { impl_->storey_ll = std::move(by_storey); }

void StoreyBank::predict(const Eigen::Isometry3d& T_odom_base) {
  for (auto& e : impl_->entries) e.filter->predict(T_odom_base);
}

bool StoreyBank::wantsObservations() const {
  for (const auto& e : impl_->entries)
    if (e.filter->wantsObservations()) return true;
  return false;
}

StoreyBankReport StoreyBank::update(const std::vector<planes::ObservedPlane>& walls, const RangeProfile* profile) {
  auto& m = *impl_;
  std::vector<UpdateReport> reports;
  for (auto& e : m.entries) reports.push_back(e.filter->update(walls, profile));
  // Every filter gets the same scans and odometry, so they weigh together.
  const bool weighed = reports.front().weighed;
  if (!m.decided && m.entries.size() == 1) {
    m.decided = m.entries.front().filter->converged();
    if (m.decided) m.margin = std::numeric_limits<double>::infinity();
  } else if (!m.decided && weighed) {
    // Who leads: a converged filter before one that has not, then the better fit of the path.
    for (std::size_t k = 0; k < m.entries.size(); ++k) {
      auto& e = m.entries[k];
      e.best = reports[k].path_best;
      e.rivals.clear();
      for (const auto& [pose, margin] : reports[k].path_rivals) e.rivals.push_back(pose);
      e.log_likelihood = e.best ? e.filter->pathScore(e.best->x(), e.best->y(), e.best->z())
                                : -std::numeric_limits<double>::infinity();
    }
    const auto ahead = [&](std::size_t a, std::size_t b) {
      const bool ca = m.entries[a].filter->converged(), cb = m.entries[b].filter->converged();
      return ca != cb ? ca
                      : m.entries[a].log_likelihood + m.storeyLogLikelihood(a) > m.entries[b].log_likelihood + m.storeyLogLikelihood(b);
    };
    for (std::size_t k = 0; k < m.entries.size(); ++k)
      if (ahead(k, m.leader)) m.leader = k;
    m.margin.reset();
    if (m.entries[m.leader].filter->converged()) {
      double margin = m.marginOverOthers();
      if (margin >= m.config.evidenceMargin()) {
        // About to decide: first make sure no storey's best place is missing from its
        // candidates (as the filter does before its own convergence counts), then ask again.
        for (std::size_t j = 0; j < m.entries.size(); ++j) {
          if (j == m.leader) continue;
          const detail::PathVerdict v = FilterAccess::everyFitVerdict(*m.entries[j].filter, walls);
          if (!v.has_best) continue;
          m.entries[j].best = v.best;
          m.entries[j].rivals.clear();
          for (const auto& [pose, rm] : v.rivals) m.entries[j].rivals.push_back(pose);
        }
        margin = m.marginOverOthers();
      }
      m.margin = margin;
      m.decided = margin >= m.config.evidenceMargin();
    }
  }
  StoreyBankReport out;
  out.filter = reports[m.leader];
  out.leader = m.entries[m.leader].storey;
  out.storey_margin = m.margin;
  for (std::size_t k = 0; k < m.entries.size(); ++k) {
    const auto& e = m.entries[k];
    StoreyCandidate c{e.storey, e.particles, e.filter->converged(), e.best, e.log_likelihood};
    out.candidates.push_back(c);
  }
  std::stable_sort(out.candidates.begin(), out.candidates.end(), [&](const StoreyCandidate& a, const StoreyCandidate& b) {
    if ((a.storey == out.leader) != (b.storey == out.leader)) return a.storey == out.leader;
    return a.path_log_likelihood > b.path_log_likelihood;
  });
  if (m.decided && m.entries.size() > 1) {
    // The other storeys are done with: only the decided one is tracked on.
    Impl::Entry kept = std::move(m.entries[m.leader]);
    m.entries.clear();
    m.entries.push_back(std::move(kept));
    m.leader = 0;
  }
  out.decided = m.decided;
  return out;
}

bool StoreyBank::converged() const { return impl_->decided && impl_->entries[impl_->leader].filter->converged(); }
std::optional<std::size_t> StoreyBank::storey() const {
  return impl_->decided ? std::optional<std::size_t>(impl_->entries[impl_->leader].storey) : std::nullopt;
}
std::size_t StoreyBank::leader() const { return impl_->entries[impl_->leader].storey; }
const ParticleFilter& StoreyBank::filter() const { return *impl_->entries[impl_->leader].filter; }
std::optional<Eigen::Isometry3d> StoreyBank::T_map_odom() const {
  return converged() ? filter().T_map_odom() : std::nullopt;
}
Eigen::Isometry3d StoreyBank::T_map_base() const { return filter().T_map_base(); }
int StoreyBank::estimateRoom() const { return filter().estimateRoom(); }
std::vector<std::size_t> StoreyBank::storeys() const {
  std::vector<std::size_t> out;
  for (const auto& e : impl_->entries) out.push_back(e.storey);
  return out;
}

}  // namespace bimloc::pf
