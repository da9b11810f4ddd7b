// AMCL, the paper's first baseline (localizer/src/peers/amcl), against independent truths: its
// likelihood field against brute-force nearest-obstacle distances, its KLD particle bound
// against Fox's formula, and, in a small world whose lidar returns are computed analytically
// (ray against boxes), tracking from a known pose, global localization, determinism and bad input.
#include "peers/amcl/amcl.hpp"
#include "peers/amcl/particles.hpp"
#include "peers/amcl/scan.hpp"
#include "sim_fixtures.hpp"

#include <bimloc/localizer.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <set>

namespace {

using namespace bimloc;
using namespace bimloc::peers;

// --- A small world: a 10 x 6 x 3 m room (floor and ceiling included) with a 1 x 1 m pillar
// off its centre, so that it has one pose for each view.
struct Box {
  Eigen::Vector3d lo, hi;
};
const Box kRoom{{0, 0, 0}, {10, 6, 3}};
const Box kPillar{{6.5, 1.5, 0}, {7.5, 2.5, 3}};

void append(bim::TriangleMesh& mesh, const Box& b) {
  const auto box = test::boxRoom((b.hi - b.lo).cast<float>());
  const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
  for (const auto& v : box.vertices) mesh.vertices.push_back(v + b.lo.cast<float>());
  for (auto t : box.triangles) mesh.triangles.push_back({t[0] + first, t[1] + first, t[2] + first});
}

bim::Building smallWorld(bool pillar = true, bool walls = true) {
  bim::Building b;
  bim::Storey s;
  s.name = "small";
  if (walls) append(s.mesh, kRoom);
  if (pillar) append(s.mesh, kPillar);
  if (!walls) {  // only a floor and a ceiling: nothing in the band
    for (double z : {0.0, 3.0}) {
      const auto first = static_cast<std::uint32_t>(s.mesh.vertices.size());
      for (int i = 0; i < 4; ++i) s.mesh.vertices.emplace_back(i & 1 ? 10.f : 0.f, i & 2 ? 6.f : 0.f, static_cast<float>(z));
      s.mesh.triangles.push_back({first, first + 1, first + 3});
      s.mesh.triangles.push_back({first, first + 3, first + 2});
    }
  }
  bim::Room room;
  room.name = "R";
  room.footprint = {{0, 0}, {10, 0}, {10, 6}, {0, 6}};
  s.rooms.push_back(room);
  b.storeys.push_back(std::move(s));
  return b;
}

// Distance along a ray to the room's inside or the pillar's outside (slab method).
double castRay(const Eigen::Vector3d& o, const Eigen::Vector3d& d, bool pillar) {
  double t = test::boxRange(kRoom.hi - kRoom.lo, o - kRoom.lo, d);
  if (!pillar) return t;
  double t0 = 0, t1 = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-12) {
      if (o[a] < kPillar.lo[a] || o[a] > kPillar.hi[a]) return t;
      continue;
    }
    double u = (kPillar.lo[a] - o[a]) / d[a], v = (kPillar.hi[a] - o[a]) / d[a];
    if (u > v) std::swap(u, v);
    t0 = std::max(t0, u), t1 = std::min(t1, v);
  }
  return t0 <= t1 ? std::min(t, t0) : t;
}

const Eigen::Isometry3d kMount = test::pose(0, 0, 0, 0.25);  // the default VLP-16 mount
constexpr double kBaseHeight = 0.5;                           // base_link above the floor

// A VLP-16-like turn (16 rings, -15..15 deg, every 1 deg of azimuth) from base pose (x, y, yaw),
// in the lidar frame.
std::vector<Eigen::Vector3f> scanFrom(const PlanarPose& p, bool pillar = true) {
  const Eigen::Isometry3d T_map_lidar = test::pose(p.x(), p.y(), p.z(), kBaseHeight) * kMount;
  std::vector<Eigen::Vector3f> points;
  for (int ring = 0; ring < 16; ++ring) {
    const double el = (-15.0 + 2.0 * ring) * M_PI / 180.0;
    for (int az = 0; az < 360; ++az) {
      const double a = az * M_PI / 180.0;
      const Eigen::Vector3d d_l(std::cos(el) * std::cos(a), std::cos(el) * std::sin(a), std::sin(el));
      const double r = castRay(T_map_lidar.translation(), T_map_lidar.linear() * d_l, pillar);
      if (std::isfinite(r) && r < 100) points.push_back((r * d_l).cast<float>());
    }
  }
  return points;
}

// The truth: a loop round the room, 0.5 m/s, 10 turns a second; odometry with a little noise.
struct Walk {
  std::vector<PlanarPose> truth, odom;
};
Walk walkRound(double duration_s, std::uint64_t seed) {
  const std::vector<Eigen::Vector2d> corners{{2, 4.5}, {8.5, 4.5}, {8.5, 0.8}, {1.5, 0.8}, {2, 4.5}};
  Walk w;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  PlanarPose odom = PlanarPose::Zero();
  double s = 0;
  std::vector<double> cum{0};
  for (std::size_t i = 1; i < corners.size(); ++i) cum.push_back(cum.back() + (corners[i] - corners[i - 1]).norm());
  for (int k = 0; k < static_cast<int>(duration_s * 10); ++k, s += 0.05) {
    const double u = std::fmod(s, cum.back());
    std::size_t i = 1;
    while (cum[i] < u) ++i;
    const Eigen::Vector2d dir = (corners[i] - corners[i - 1]).normalized();
    const Eigen::Vector2d xy = corners[i - 1] + (u - cum[i - 1]) * dir;
    const PlanarPose truth(xy.x(), xy.y(), std::atan2(dir.y(), dir.x()));
    if (!w.truth.empty()) {
      PlanarPose step = between(w.truth.back(), truth);
      step.x() *= 1.0 + 0.02 * n(rng), step.z() += 0.005 * n(rng);  // about 2 % of distance
      odom = compose(odom, step);
    }
    w.truth.push_back(truth);
    w.odom.push_back(odom);
  }
  return w;
}

Eigen::Isometry3d odomPose(const PlanarPose& p) { return test::pose(p.x(), p.y(), p.z(), kBaseHeight); }

struct Outcome {
  std::vector<LocalizationResult> results;
  std::vector<double> errors;  // xy error of T_map_base
};

Outcome run(const bim::Building& building, const Walk& w, const AmclConfig& amcl, bool pillar = true,
            const std::function<void(std::vector<Eigen::Vector3f>&, std::size_t)>& spoil = {}) {
  LocalizerConfig config;
  config.method = LocalizerMethod::Amcl;
  config.storey = "0";
  config.seed = 7;
  config.amcl = amcl;
  Localizer localizer(building, kMount, config);
  Outcome out;
  for (std::size_t k = 0; k < w.truth.size(); ++k) {
    const auto points = [&] {
      auto p = scanFrom(w.truth[k], pillar);
      if (spoil) spoil(p, k);
      return p;
    };
    out.results.push_back(localizer.step(0.1 * static_cast<double>(k), odomPose(w.odom[k]), Localizer::PointSource(points)));
    out.errors.push_back((out.results.back().T_map_base.translation().head<2>() - w.truth[k].head<2>()).norm());
  }
  return out;
}

// The bench's odometry is good: the ROS documentation's "expected noise" (see the README).
AmclConfig tuned() {
  AmclConfig c;
  c.odom_alpha1 = c.odom_alpha2 = c.odom_alpha3 = c.odom_alpha4 = 0.02;
  return c;
}

}  // namespace

TEST(Amcl, LikelihoodFieldIsTheBruteForceDistanceToTheNearestObstacleCapped) {
  amcl::Grid grid({-1.0, 2.0}, {2.0, 4.25}, 0.05);
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> ci(0, grid.width - 1), cj(0, grid.height - 1);
  for (int k = 0; k < 25; ++k) grid.occupied[grid.index(ci(rng), cj(rng))] = 1;
  grid.markSegment({-0.5, 2.3}, {1.2, 3.9});  // and a diagonal wall
  const double cap = 0.6;
  const amcl::LikelihoodField field(grid, cap);
  int capped = 0;
  for (int j = 0; j < grid.height; ++j)
    for (int i = 0; i < grid.width; ++i) {
      double best = std::numeric_limits<double>::infinity();
      for (int q = 0; q < grid.height; ++q)
        for (int p = 0; p < grid.width; ++p)
          if (grid.occupied[grid.index(p, q)]) best = std::min(best, (grid.centre(i, j) - grid.centre(p, q)).norm());
      capped += best >= cap;
      ASSERT_NEAR(field.distance(i, j), std::min(best, cap), 1e-5) << i << "," << j;
    }
  EXPECT_GT(capped, 0) << "the cap was exercised";
  EXPECT_EQ(field.distance(-1, 3), cap) << "off the map counts as the cap (ROS max_occ_dist)";
  // No obstacle at all: the cap everywhere.
  amcl::Grid empty({0, 0}, {1, 1}, 0.1);
  const amcl::LikelihoodField none(empty, 2.0);
  for (float d : none.distances()) EXPECT_EQ(d, 2.0f);
}

TEST(Amcl, KldBoundIsFoxsFormulaAndResamplingStopsThere) {
  // Fox (2003), eq. 12: n = (k-1)/(2 eps) (1 - 2/(9(k-1)) + sqrt(2/(9(k-1))) z)^3.
  for (double z : {0.99, 2.326}) {
    for (int k : {2, 3, 5, 10, 37, 100, 1000}) {
      const double km1 = k - 1;
      const double fox = km1 / (2 * 0.01) * std::pow(1 - 2 / (9 * km1) + std::sqrt(2 / (9 * km1)) * z, 3);
      EXPECT_EQ(amcl::kldLimit(k, 0.01, z, 1, 1000000), static_cast<int>(std::ceil(fox))) << "k=" << k << " z=" << z;
    }
  }
  EXPECT_EQ(amcl::kldLimit(1, 0.01, 0.99, 100, 5000), 5000) << "ROS: max_particles for one bin";
  EXPECT_EQ(amcl::kldLimit(2, 0.01, 0.99, 100, 5000), 100) << "at least min_particles";
  EXPECT_EQ(amcl::kldLimit(1000, 0.01, 0.99, 100, 5000), 5000) << "at most max_particles";
  // Resampling: particles over 20 bins, equal weights: the draw stops one past the bound for
  // the bins it has filled.
  std::vector<amcl::Particle> set;
  for (int b = 0; b < 20; ++b)
    for (int k = 0; k < 50; ++k) set.push_back({PlanarPose(0.5 * b + 0.25, 0.25, 0.01), 1.0 / 1000});
  AmclConfig c;
  std::mt19937_64 rng(1);
  const auto out = amcl::resampleKld(set, c, 0.0, [](std::mt19937_64&) { return PlanarPose::Zero(); }, rng);
  std::set<std::array<int, 3>> bins;
  for (const auto& p : out) bins.insert(amcl::binOf(p.pose));
  EXPECT_EQ(static_cast<int>(out.size()), amcl::kldLimit(static_cast<int>(bins.size()), c.kld_err, c.kld_z, c.min_particles, c.max_particles) + 1);
}

TEST(Amcl, SliceHasTheWallsAndPillarNotTheFloorOrCeilingAndFreeSpaceIsInside) {
  const auto building = smallWorld();
  amcl::Amcl a(building.storeys[0], kMount, AmclConfig{}, 1);
  const auto& g = a.grid();
  // A face on a cell boundary may fall in the cell on either side.
  const auto occupied = [&](double x, double y) {
    for (double dx : {-0.02, 0.0, 0.02})
      for (double dy : {-0.02, 0.0, 0.02}) {
        const auto c = g.cellOf(x + dx, y + dy);
        if (g.occupied[g.index(c.x(), c.y())]) return true;
      }
    return false;
  };
  EXPECT_TRUE(occupied(0, 3)) << "west wall";
  EXPECT_TRUE(occupied(5, 6)) << "north wall";
  EXPECT_TRUE(occupied(6.5, 2)) << "pillar";
  EXPECT_FALSE(occupied(3, 3)) << "the floor and ceiling are outside the band";
  EXPECT_FALSE(occupied(7, 2)) << "the pillar's inside is not drawn (its faces are)";
  // The free space: in the room, clear of the walls by free_clearance_m.
  ASSERT_FALSE(a.freeSpace().cells.empty());
  for (std::uint32_t c : a.freeSpace().cells) {
    const Eigen::Vector2d p = g.centre(static_cast<int>(c % g.width), static_cast<int>(c / g.width));
    ASSERT_TRUE(p.x() > 0.2 && p.x() < 9.8 && p.y() > 0.2 && p.y() < 5.8) << p.transpose();
    // Off the pillar's faces (its inside, enclosed by them, may hold particles: README).
    const Eigen::Vector2d lo = kPillar.lo.head<2>(), hi = kPillar.hi.head<2>();
    const Eigen::Vector2d nearest = p.cwiseMax(lo).cwiseMin(hi);
    const bool inside = nearest == p;
    const double to_faces = inside ? std::min((p - lo).minCoeff(), (hi - p).minCoeff()) : (p - nearest).norm();
    ASSERT_GT(to_faces, 0.2) << "by the pillar " << p.transpose();
  }
}

TEST(Amcl, TracksFromAKnownPose) {
  const auto building = smallWorld();
  const Walk w = walkRound(40, 2);
  AmclConfig c = tuned();
  c.use_initial_pose = true;
  c.initial_pose_x_m = w.truth[0].x() + 0.3, c.initial_pose_y_m = w.truth[0].y() - 0.2;  // a start guess off by 0.36 m
  c.initial_pose_yaw_deg = w.truth[0].z() * 180 / M_PI + 5;
  const Outcome o = run(building, w, c);
  std::optional<std::size_t> converged;
  double sum_sq = 0, worst = 0;
  for (std::size_t k = 0; k < o.results.size(); ++k) {
    if (!converged && o.results[k].state == LocalizationState::Converged) converged = k;
    if (k >= 50) sum_sq += o.errors[k] * o.errors[k], worst = std::max(worst, o.errors[k]);
  }
  ASSERT_TRUE(converged) << "never declared convergence";
  EXPECT_LT(*converged, 100u) << "within 10 s";
  EXPECT_LT(std::sqrt(sum_sq / static_cast<double>(o.results.size() - 50)), 0.1);
  EXPECT_LT(worst, 0.3);
  EXPECT_EQ(o.results.back().state, LocalizationState::Tracking);
  EXPECT_EQ(o.results.back().losses, 0);
  ASSERT_TRUE(o.results.back().peer);
  EXPECT_EQ(o.results.back().peer->method, "amcl");
  EXPECT_EQ(o.results.back().peer->poses.size(), static_cast<std::size_t>(o.results.back().peer->particles));
  EXPECT_LT(o.results.back().peer->particles, 5000) << "KLD shrank the set";
}

TEST(Amcl, GlobalLocalizationConvergesToTheTruthSameSeedSameBytes) {
  const auto building = smallWorld();
  const Walk w = walkRound(40, 3);
  const Outcome a = run(building, w, tuned());
  std::optional<std::size_t> converged;
  for (std::size_t k = 0; k < a.results.size(); ++k) {
    const auto& r = a.results[k];
    if (!converged && r.state == LocalizationState::Converged) converged = k;
    if (!converged) {
      EXPECT_EQ(r.state, LocalizationState::Searching);
    }
    if (converged && r.state != LocalizationState::Lost) {
      EXPECT_LT(a.errors[k], 0.5) << "declared converged 0.5 m off at step " << k;
      EXPECT_LT(std::abs(wrapAngle(planarPose(r.T_map_base).z() - w.truth[k].z())), 10 * M_PI / 180) << "step " << k;
    }
  }
  ASSERT_TRUE(converged) << "never converged";
  EXPECT_LT(a.errors.back(), 0.2);
  const Outcome b = run(building, w, tuned());
  for (std::size_t k = 0; k < a.results.size(); ++k)
    ASSERT_TRUE(a.results[k].T_map_base.matrix() == b.results[k].T_map_base.matrix()) << "step " << k;
}

TEST(Amcl, NoObstacleInTheSliceIsWarnedAndNeverConverges) {
  const auto building = smallWorld(false, false);
  const Walk w = walkRound(10, 4);
  const Outcome o = run(building, w, tuned(), false);
  bool warned = false;
  for (const auto& r : o.results) {
    EXPECT_EQ(r.state, LocalizationState::Searching);
    EXPECT_FALSE(r.T_map_odom);
    EXPECT_TRUE(r.T_map_base.matrix().allFinite());
    for (const auto& m : r.warnings) warned = warned || m.find("no obstacle") != std::string::npos;
  }
  EXPECT_TRUE(warned);
}

TEST(Amcl, EmptyScanBandAndNaNPointsAreWarnedOnceNeverACrash) {
  const auto building = smallWorld();
  const Walk w = walkRound(10, 5);
  // Only the floor and ceiling returns: nothing in the band.
  const Outcome empty = run(building, w, tuned(), true, [](std::vector<Eigen::Vector3f>& p, std::size_t) {
    std::vector<Eigen::Vector3f> kept;
    for (const auto& q : p)
      if (q.z() < -0.5 || q.z() > 1.5) kept.push_back(q);
    p = kept;
  });
  int warnings = 0;
  for (const auto& r : empty.results) {
    EXPECT_EQ(r.state, LocalizationState::Searching);
    for (const auto& m : r.warnings) warnings += m.find("no lidar return") != std::string::npos;
  }
  EXPECT_EQ(warnings, 1);
  // A third of each scan NaN or inf: dropped, one warning, and the tracking is unharmed.
  AmclConfig c = tuned();
  c.use_initial_pose = true;
  c.initial_pose_x_m = w.truth[0].x(), c.initial_pose_y_m = w.truth[0].y(), c.initial_pose_yaw_deg = w.truth[0].z() * 180 / M_PI;
  const Outcome nan = run(building, w, c, true, [](std::vector<Eigen::Vector3f>& p, std::size_t) {
    for (std::size_t i = 0; i < p.size(); i += 3) p[i] = Eigen::Vector3f(NAN, i % 2 ? INFINITY : 0.f, 1.f);
  });
  warnings = 0;
  for (const auto& r : nan.results)
    for (const auto& m : r.warnings) warnings += m.find("non-finite") != std::string::npos;
  EXPECT_EQ(warnings, 1);
  EXPECT_LT(nan.errors.back(), 0.3);
  // A non-finite odometry pose: skipped, the estimate stays finite.
  LocalizerConfig config;
  config.method = LocalizerMethod::Amcl;
  config.storey = "0";
  Localizer localizer(building, kMount, config);
  Eigen::Isometry3d bad = odomPose(PlanarPose::Zero());
  bad.translation().x() = NAN;
  for (int k = 0; k < 5; ++k) {
    const auto r = localizer.step(0.1 * k, k % 2 ? bad : odomPose(PlanarPose(0.3 * k, 0, 0)), scanFrom(PlanarPose(2 + 0.3 * k, 3, 0)));
    EXPECT_TRUE(r.T_map_base.matrix().allFinite());
  }
}
