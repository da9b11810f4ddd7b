// Issue 28, Speed (h28speed5): faster ways to the same numbers, each held to the bit against the
// straightforward computation it replaces, written out here:
// - the guide's fan of rays (RayFan) against castRay over every segment;
// - the guide's walk (a bucket queue, stopped at its targets) against a binary-heap Dijkstra;
// - the de-skew's kept odometry samples against a fresh look-up and slerp per firing;
// - fitPlane's six moments against the nine of q q^T;
// - the guide's room test through a grid against storey.roomAt;
// - the guide's walls near a point through a grid against segmentsNear.
#include "guide/ray_fan.hpp"
#include "guide/walk_grid.hpp"
#include "guide/wall_slice.hpp"
#include "planes/plane_steps.hpp"
#include "sim/dataset/deskew.hpp"

#include <bimloc/bim/building.hpp>

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <queue>
#include <random>
#include <utility>
#include <vector>

using namespace bimloc;
using guide::detail::Segment2;

namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Segments of every awkward kind: a grid of Manhattan walls (rays from grid points at headings
// of whole degrees pass exactly through their ends), random ones, a few millimetres long, and
// collinear runs.
std::vector<Segment2> awkwardSegments(std::mt19937& rng) {
  std::vector<Segment2> s;
  int wall = 0;
  for (int i = 0; i <= 6; ++i) {
    s.push_back({{i * 2.0, 0.0}, {i * 2.0, 1.5}, wall++});
    s.push_back({{i * 2.0, 2.5}, {i * 2.0, 12.0}, wall++});
    s.push_back({{0.0, i * 2.0}, {5.0, i * 2.0}, wall++});
    s.push_back({{5.0, i * 2.0}, {12.0, i * 2.0}, wall++});  // collinear with the one before
  }
  std::uniform_real_distribution<double> xy(-2.0, 14.0), len(0.002, 6.0), ang(-M_PI, M_PI);
  for (int k = 0; k < 60; ++k) {
    const Eigen::Vector2d a(xy(rng), xy(rng));
    const double t = ang(rng), l = k % 10 == 0 ? 0.003 : len(rng);
    s.push_back({a, a + l * Eigen::Vector2d(std::cos(t), std::sin(t)), wall++});
  }
  return s;
}

// The walk over the grid as it was before the bucket queue: a binary heap of (distance, cell).
// The grid's cells are read through WalkGrid::free at their centres (origin as the constructor
// puts it: the walls' least corner less two cells).
guide::detail::WalkGrid::Distances heapWalk(const guide::detail::WalkGrid& grid, const Eigen::Vector2d& origin, double cell_m,
                                            int nx, int ny, const Eigen::Vector2d& p, double max_m, double snap_m) {
  guide::detail::WalkGrid::Distances d;
  const auto freeCell = [&](int ix, int iy) {
    return ix >= 0 && iy >= 0 && ix < nx && iy < ny && grid.free(origin + cell_m * Eigen::Vector2d(ix + 0.5, iy + 0.5));
  };
  const int sx = static_cast<int>(std::floor((p.x() - origin.x()) / cell_m)), sy = static_cast<int>(std::floor((p.y() - origin.y()) / cell_m));
  if (sx < 0 || sy < 0 || sx >= nx || sy >= ny) return d;
  const int reach = static_cast<int>(std::ceil(max_m / cell_m)) + 1;
  d.x0 = std::max(0, sx - reach), d.y0 = std::max(0, sy - reach);
  d.nx = std::min(nx, sx + reach + 1) - d.x0, d.ny = std::min(ny, sy + reach + 1) - d.y0;
  d.metres.assign(static_cast<std::size_t>(d.nx * d.ny), std::numeric_limits<float>::infinity());
  const auto index = [&](int ix, int iy) { return static_cast<std::size_t>((iy - d.y0) * d.nx + (ix - d.x0)); };
  const auto inside = [&](int ix, int iy) { return ix >= d.x0 && iy >= d.y0 && ix < d.x0 + d.nx && iy < d.y0 + d.ny; };
  using Entry = std::pair<float, std::pair<int, int>>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  const int snap = static_cast<int>(std::ceil(snap_m / cell_m));
  for (int iy = sy - snap; iy <= sy + snap; ++iy)
    for (int ix = sx - snap; ix <= sx + snap; ++ix) {
      if (!inside(ix, iy) || !freeCell(ix, iy)) continue;
      const double r = cell_m * std::hypot(ix - sx, iy - sy);
      if (r > snap_m && !(ix == sx && iy == sy)) continue;
      d.metres[index(ix, iy)] = static_cast<float>(r);
      open.push({static_cast<float>(r), {ix, iy}});
    }
  while (!open.empty()) {
    const auto [dist, at] = open.top();
    open.pop();
    if (dist > d.metres[index(at.first, at.second)]) continue;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int ix = at.first + dx, iy = at.second + dy;
        if ((dx == 0 && dy == 0) || !inside(ix, iy) || !freeCell(ix, iy)) continue;
        if (dx != 0 && dy != 0 && (!freeCell(at.first + dx, at.second) || !freeCell(at.first, at.second + dy))) continue;
        const float next = dist + static_cast<float>(cell_m * ((dx != 0 && dy != 0) ? M_SQRT2 : 1.0));
        if (next > max_m || next >= d.metres[index(ix, iy)]) continue;
        d.metres[index(ix, iy)] = next;
        open.push({next, {ix, iy}});
      }
  }
  return d;
}

}  // namespace

TEST(SameBits, TheRayFanCastsAsEveryRayAgainstEverySegment) {
  std::mt19937 rng(2811);
  const std::vector<Segment2> segments = awkwardSegments(rng);
  std::uniform_real_distribution<double> xy(-1.0, 13.0), yaw(-M_PI, M_PI);
  std::vector<Eigen::Vector3d> poses;
  for (int i = 0; i <= 6; ++i)
    for (int j = 0; j <= 6; ++j) poses.emplace_back(2.0 * i, 2.0 * j, (i * 7 + j) * M_PI / 180.0);  // on corners, whole degrees
  for (int k = 0; k < 300; ++k) poses.emplace_back(xy(rng), xy(rng), yaw(rng));
  poses.emplace_back(2.0, 0.75, 0.0);                   // on a wall's line, between its pieces
  poses.emplace_back(2.0005, 5.0, M_PI / 2);            // half a millimetre from a wall, along it
  poses.emplace_back(segments[40].a.x(), segments[40].a.y(), 0.3);  // on a segment's end
  int hits = 0, misses = 0;
  for (const int rays : {90, 7, 1}) {
    for (const auto& pose : poses) {
      const double max_m = 10.0;
      const guide::detail::RayFan fan(segments, pose.head<2>(), pose.z(), rays, max_m);
      for (int k = 0; k < rays; ++k) {
        const double a = pose.z() + 2.0 * M_PI * k / rays;
        const Eigen::Vector2d dir(std::cos(a), std::sin(a));
        int wall_all = -2, wall_fan = -2;
        const double all = guide::detail::castRay(segments, pose.head<2>(), dir, max_m, &wall_all);
        const double fanned = fan.cast(k, pose.head<2>(), dir, max_m, &wall_fan);
        ASSERT_TRUE(sameBits(all, fanned)) << "pose " << pose.transpose() << " ray " << k << " of " << rays << ": " << all << " vs " << fanned;
        ASSERT_EQ(wall_all, wall_fan) << "pose " << pose.transpose() << " ray " << k;
        (wall_all >= 0 ? hits : misses)++;
      }
    }
  }
  EXPECT_GT(hits, 10000);  // the comparison covers hits and rays that meet nothing
  EXPECT_GT(misses, 100);
}

TEST(SameBits, TheBucketWalkIsTheHeapWalk) {
  std::mt19937 rng(2812);
  std::vector<Segment2> walls = awkwardSegments(rng);
  const double cell_m = 0.1, clearance_m = 0.4;
  const guide::detail::WalkGrid grid(walls, clearance_m, cell_m);
  Eigen::Vector2d lo = walls.front().a, hi = lo;
  for (const auto& s : walls) lo = lo.cwiseMin(s.a).cwiseMin(s.b), hi = hi.cwiseMax(s.a).cwiseMax(s.b);
  const Eigen::Vector2d origin = lo - Eigen::Vector2d::Constant(2.0 * cell_m);
  const int nx = static_cast<int>(std::ceil((hi.x() - origin.x()) / cell_m)) + 3;
  const int ny = static_cast<int>(std::ceil((hi.y() - origin.y()) / cell_m)) + 3;
  std::uniform_real_distribution<double> xy(lo.x() - 1.0, hi.x() + 1.0);
  int reached = 0;
  for (int k = 0; k < 40; ++k) {
    const Eigen::Vector2d p(xy(rng), xy(rng));
    const double max_m = k % 4 == 0 ? 3.0 : 10.0;
    const auto want = heapWalk(grid, origin, cell_m, nx, ny, p, max_m, 0.5);
    const auto got = grid.from(p, max_m);
    ASSERT_EQ(want.x0, got.x0);
    ASSERT_EQ(want.y0, got.y0);
    ASSERT_EQ(want.nx, got.nx);
    ASSERT_EQ(want.ny, got.ny);
    ASSERT_EQ(want.metres.size(), got.metres.size());
    for (std::size_t i = 0; i < want.metres.size(); ++i) {
      ASSERT_EQ(std::memcmp(&want.metres[i], &got.metres[i], sizeof(float)), 0) << "start " << p.transpose() << " cell " << i;
      reached += std::isfinite(want.metres[i]) ? 1 : 0;
    }
    // One target: the walk stopped when it is settled gives the same distance; and so do many,
    // at each of them.
    std::vector<Eigen::Vector2d> targets;
    for (int t = 0; t < 25; ++t) {
      const Eigen::Vector2d q(xy(rng), xy(rng));
      ASSERT_TRUE(sameBits(grid.distance(got, q), grid.distanceBetween(p, q, max_m))) << p.transpose() << " -> " << q.transpose();
      targets.push_back(t % 2 ? q : p + Eigen::Vector2d(0.3 * t - 3.0, 0.2 * t - 2.0));  // near ones too
    }
    const auto stopped = grid.from(p, targets, max_m);
    for (const auto& q : targets)
      ASSERT_TRUE(sameBits(grid.distance(got, q), grid.distance(stopped, q))) << p.transpose() << " -> " << q.transpose();
  }
  EXPECT_GT(reached, 10000);
}

TEST(SameBits, TheDeskewWithKeptSamplesIsAFreshLookUpPerFiring) {
  // Odometry at 50 Hz along a curve with a turn, a turn of 1800 firings of 16 points.
  std::vector<sim::StampedPose> odometry;
  for (int k = 0; k <= 60; ++k) {
    sim::StampedPose s;
    s.stamp_s = 10.0 + 0.02 * k;
    s.pose = Eigen::Translation3d(0.5 * s.stamp_s, 0.1 * std::sin(s.stamp_s), 0.0) * Eigen::AngleAxisd(0.3 * s.stamp_s, Eigen::Vector3d::UnitZ());
    odometry.push_back(s);
  }
  const Eigen::Isometry3d T_base_lidar = Eigen::Translation3d(0.1, 0.0, 0.5) * Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitX());
  std::vector<Eigen::Vector3f> points;
  std::vector<double> time_s;
  std::mt19937 rng(2813);
  std::uniform_real_distribution<float> u(-8.0f, 8.0f);
  for (int f = 0; f < 1800; ++f)
    for (int l = 0; l < 16; ++l) points.emplace_back(u(rng), u(rng), 0.2f * u(rng)), time_s.push_back(-0.05 + f * (0.1 / 1800));
  time_s.back() = 5.0;  // past the last sample
  time_s.front() = -5.0;  // before the first
  const double stamp_s = 10.6, reference_s = 10.6;
  // The former interpolatePose, written out: look-up, then slerp of freshly made quaternions.
  const auto fresh = [&](double t) {
    const auto after = std::lower_bound(odometry.begin(), odometry.end(), t, [](const sim::StampedPose& s, double v) { return s.stamp_s < v; });
    if (after == odometry.begin()) return odometry.front().pose;
    if (after == odometry.end()) return odometry.back().pose;
    const auto& a = *std::prev(after);
    const auto& b = *after;
    const double f = (t - a.stamp_s) / (b.stamp_s - a.stamp_s);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = (1 - f) * a.pose.translation() + f * b.pose.translation();
    T.linear() = Eigen::Quaterniond(a.pose.linear()).slerp(f, Eigen::Quaterniond(b.pose.linear())).toRotationMatrix();
    return T;
  };
  const Eigen::Isometry3d T_ref_odom = (fresh(reference_s) * T_base_lidar).inverse();
  std::vector<Eigen::Vector3f> want = points;
  for (std::size_t i = 0; i < want.size(); ++i)
    want[i] = (T_ref_odom * fresh(stamp_s + time_s[i]) * T_base_lidar).cast<float>() * want[i];
  sim::deskew(points, time_s, stamp_s, reference_s, odometry, T_base_lidar);
  ASSERT_EQ(points.size(), want.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    ASSERT_EQ(std::memcmp(points[i].data(), want[i].data(), 3 * sizeof(float)), 0) << "point " << i;
  for (const double t : {9.0, 10.0, 10.01, 10.02, 10.55, 11.2, 12.0}) {
    const Eigen::Isometry3d a = sim::interpolatePose(odometry, t), b = fresh(t);
    ASSERT_EQ(std::memcmp(a.matrix().data(), b.matrix().data(), 16 * sizeof(double)), 0) << t;
  }
}

TEST(SameBits, TheDeskewsSlerpIsEigensStandingStillAndPastAHalfTurn) {
  // The slerp's branches: two samples of one rotation (|dot| = 1, Eigen's linear blend), and
  // yaws past +-180 deg, whose quaternions (w >= 0 from a rotation matrix) have a negative dot.
  std::vector<sim::StampedPose> odometry;
  for (int k = 0; k <= 40; ++k) {
    sim::StampedPose s;
    s.stamp_s = 3.0 + 0.02 * k;
    const double yaw = k < 10 ? 0.4 : 0.4 + 0.35 * (k - 10);  // still, then several half turns
    s.pose = Eigen::Translation3d(0.1 * k, 0.0, 0.2) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
             Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitX());
    odometry.push_back(s);
  }
  const auto fresh = [&](double t) {
    const auto after = std::lower_bound(odometry.begin(), odometry.end(), t, [](const sim::StampedPose& s, double v) { return s.stamp_s < v; });
    if (after == odometry.begin()) return odometry.front().pose;
    if (after == odometry.end()) return odometry.back().pose;
    const double f = (t - std::prev(after)->stamp_s) / (after->stamp_s - std::prev(after)->stamp_s);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = (1 - f) * std::prev(after)->pose.translation() + f * after->pose.translation();
    T.linear() = Eigen::Quaterniond(std::prev(after)->pose.linear()).slerp(f, Eigen::Quaterniond(after->pose.linear())).toRotationMatrix();
    return T;
  };
  int negative_dots = 0, still = 0;
  for (std::size_t k = 1; k < odometry.size(); ++k) {
    const double dot = Eigen::Quaterniond(odometry[k - 1].pose.linear()).dot(Eigen::Quaterniond(odometry[k].pose.linear()));
    negative_dots += dot < 0 ? 1 : 0;
    still += std::abs(dot) >= 1.0 - Eigen::NumTraits<double>::epsilon() ? 1 : 0;
  }
  ASSERT_GT(negative_dots, 0);
  ASSERT_GT(still, 0);
  const Eigen::Isometry3d T_base_lidar = Eigen::Isometry3d::Identity();
  std::vector<Eigen::Vector3f> points;
  std::vector<double> time_s;
  for (int f = 0; f < 4000; ++f) points.emplace_back(1.0f + 0.001f * f, -2.0f, 0.5f), time_s.push_back(-0.1 + f * 2e-4);
  const double stamp_s = 3.1, reference_s = 3.5;
  const Eigen::Isometry3d T_ref_odom = (fresh(reference_s) * T_base_lidar).inverse();
  std::vector<Eigen::Vector3f> want = points;
  for (std::size_t i = 0; i < want.size(); ++i)
    want[i] = (T_ref_odom * fresh(stamp_s + time_s[i]) * T_base_lidar).cast<float>() * want[i];
  sim::deskew(points, time_s, stamp_s, reference_s, odometry, T_base_lidar);
  for (std::size_t i = 0; i < points.size(); ++i)
    ASSERT_EQ(std::memcmp(points[i].data(), want[i].data(), 3 * sizeof(float)), 0) << "point " << i;
}

TEST(SameBits, FitPlaneSumsTheSecondMomentsAsTheOuterProducts) {
  std::mt19937 rng(2814);
  std::normal_distribution<float> noise(0.0f, 0.01f);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  for (int trial = 0; trial < 50; ++trial) {
    planes::detail::Cloud cloud;
    const Eigen::Vector3f n = Eigen::Vector3f(u(rng), u(rng), 0.3f * u(rng)).normalized();
    const Eigen::Vector3f e1 = n.unitOrthogonal(), e2 = n.cross(e1);
    const Eigen::Vector3f at(5.0f + u(rng), u(rng), 1.0f);
    for (int k = 0; k < 200 + 37 * trial; ++k) cloud.push_back(at + u(rng) * e1 + 0.5f * u(rng) * e2 + noise(rng) * n);
    planes::detail::Indices support;
    for (int k = 0; k < static_cast<int>(cloud.size()); k += 1 + trial % 3) support.push_back(k);
    // The former sums: q q^T, all nine entries.
    const Eigen::Vector3d origin = cloud[support.front()].cast<double>();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d sum2 = Eigen::Matrix3d::Zero();
    for (const int i : support) {
      const Eigen::Vector3d q = cloud[i].cast<double>() - origin;
      sum += q;
      sum2 += q * q.transpose();
    }
    const double count = double(support.size());
    const Eigen::Vector3d centroid = origin + sum / count;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(sum2 - sum * sum.transpose() / count);
    const Eigen::Vector3d normal = eig.eigenvectors().col(0).normalized();
    const planes::detail::PlaneFit fit = planes::detail::fitPlane(cloud, support);
    for (int c = 0; c < 3; ++c) {
      ASSERT_TRUE(sameBits(fit.normal[c], normal[c])) << trial;
      ASSERT_TRUE(sameBits(fit.centroid[c], centroid[c])) << trial;
    }
    ASSERT_TRUE(sameBits(fit.d, -normal.dot(centroid))) << trial;
  }
}

TEST(SameBits, TheRoomGridAnswersAsEveryRoomsBox) {
  // Rooms of every kind: a row of offices, L shapes, a room far off, one with a non-finite
  // corner (a box over everything), one with no outline.
  bim::Storey storey;
  std::mt19937 rng(2815);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 40; ++i) {
    bim::Room r;
    const double x = (i % 10) * 4.0, y = (i / 10) * 6.0, w = 2.0 + 2.0 * u(rng), h = 3.0 + 3.0 * u(rng);
    if (i % 3 == 0)
      r.footprint = {{x, y}, {x + w, y}, {x + w, y + 1.0}, {x + 1.0, y + 1.0}, {x + 1.0, y + h}, {x, y + h}};
    else
      r.footprint = {{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}};
    storey.rooms.push_back(r);
  }
  storey.rooms.push_back(bim::Room{});
  storey.rooms.back().footprint = {{500.0, 500.0}, {503.0, 500.0}, {503.0, 504.0}};
  const guide::detail::RoomBoxes without_odd(storey);
  bim::Storey odd = storey;
  odd.rooms.push_back(bim::Room{});  // no outline
  odd.rooms.push_back(bim::Room{});
  odd.rooms.back().footprint = {{60.0, 60.0}, {std::numeric_limits<double>::infinity(), 60.0}, {61.0, 62.0}};
  const guide::detail::RoomBoxes with_odd(odd);
  std::uniform_real_distribution<double> xy(-3.0, 45.0);
  int inside = 0;
  for (int k = 0; k < 20000; ++k) {
    Eigen::Vector2d p(xy(rng), xy(rng));
    if (k % 50 == 0) p = storey.rooms[static_cast<std::size_t>(k / 50 % 40)].footprint[static_cast<std::size_t>(k % 4)];  // on corners
    if (k == 7) p = {501.0, 500.5};
    if (k == 9) p = {std::nan(""), 3.0};
    ASSERT_EQ(without_odd.inAnyRoom(p), storey.roomAt(p) != nullptr) << p.transpose();
    ASSERT_EQ(with_odd.inAnyRoom(p), odd.roomAt(p) != nullptr) << p.transpose();
    inside += storey.roomAt(p) != nullptr ? 1 : 0;
  }
  EXPECT_GT(inside, 2000);  // the rooms cover about a fifth of the square
  EXPECT_LT(inside, 19000);
}

TEST(SameBits, TheSegmentGridListsWhatSegmentsNearLists) {
  std::mt19937 rng(2816);
  std::vector<Segment2> segments = awkwardSegments(rng);
  segments.push_back({{1.0, 1.0}, {std::numeric_limits<double>::infinity(), 1.0}, 999});  // tested always
  const guide::detail::SegmentGrid grid(segments);
  std::uniform_real_distribution<double> xy(-20.0, 35.0), r(0.0, 18.0);
  std::size_t listed = 0;
  for (int k = 0; k < 3000; ++k) {
    const Eigen::Vector2d c(xy(rng), xy(rng));
    const double radius = k == 0 ? std::numeric_limits<double>::infinity() : k % 100 == 1 ? 0.0 : r(rng);
    const auto want = guide::detail::segmentsNear(segments, c, radius);
    const auto got = grid.near(c, radius);
    ASSERT_EQ(want.size(), got.size()) << c.transpose() << " r " << radius;
    for (std::size_t i = 0; i < want.size(); ++i) {
      ASSERT_EQ(want[i].wall, got[i].wall);
      ASSERT_TRUE(want[i].a == got[i].a && want[i].b == got[i].b);
    }
    listed += want.size();
  }
  EXPECT_GT(listed, 20000u);
  EXPECT_TRUE(guide::detail::SegmentGrid().near({0.0, 0.0}, 5.0).empty());
}
