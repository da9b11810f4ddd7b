#include "real_frames.hpp"

#include "sim/dataset/dataset_reader.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

namespace bimloc::test {
namespace {

constexpr double kColumn_m = 0.10;          // standingPoints: x-y column size
constexpr double kStandingHeight_m = 0.30;  // ... and the height its returns must span
constexpr double kNearRange_m = 1.5;        // the rig and the clutter round it
// alignWalls' association: loose enough for a first guess from two pairs of walls, tight
// enough that a wall 0.17 m in front of another (the room's far end has two) is not taken
// for it.
constexpr double kMatchAngle_rad = 3.0 * M_PI / 180.0;
constexpr double kMatchOffset_m = 0.10;
// Two walls proposing a translation must be this far from parallel.
constexpr double kMinCrossing = 0.5;  // |sin| of the angle between them, 30 degrees

struct Line {  // a wall in the plane: n·p + d = 0, n unit (towards the sensor)
  Eigen::Vector2d n;
  double d;
};

std::vector<Line> lines(const std::vector<planes::ObservedPlane>& walls) {
  std::vector<Line> out;
  for (const auto& w : walls) out.push_back({w.normal.head<2>().normalized(), w.d});
  return out;
}

Eigen::Matrix2d rot(double yaw) { return Eigen::Rotation2Dd(yaw).toRotationMatrix(); }

double angleBetween(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
}

// B's line in A's frame for p_A = R p_B + t: n_A = R n_B, d_A = d_B - n_A·t.
Line moved(const Line& l, double yaw, const Eigen::Vector2d& t) {
  const Eigen::Vector2d n = rot(yaw) * l.n;
  return {n, l.d - n.dot(t)};
}

struct Scored {
  std::vector<std::pair<int, int>> matches;
  double residual = 0;  // sum of |offset| over the matches
};

// Greedy one-to-one association: B's walls, nearest offset first.
Scored associate(const std::vector<Line>& a, const std::vector<Line>& b, double yaw, const Eigen::Vector2d& t) {
  struct Candidate {
    double offset;
    int i, j;
  };
  std::vector<Candidate> candidates;
  for (int j = 0; j < int(b.size()); ++j) {
    const Line m = moved(b[j], yaw, t);
    for (int i = 0; i < int(a.size()); ++i) {
      const double offset = std::abs(m.d - a[i].d);
      if (std::abs(angleBetween(a[i].n, m.n)) < kMatchAngle_rad && offset < kMatchOffset_m) candidates.push_back({offset, i, j});
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) { return x.offset < y.offset; });
  Scored s;
  std::vector<bool> used_a(a.size()), used_b(b.size());
  for (const auto& c : candidates) {
    if (used_a[c.i] || used_b[c.j]) continue;
    used_a[c.i] = used_b[c.j] = true;
    s.matches.emplace_back(c.i, c.j);
    s.residual += c.offset;
  }
  return s;
}

bool better(const Scored& x, const Scored& y) {
  return x.matches.size() != y.matches.size() ? x.matches.size() > y.matches.size() : x.residual < y.residual;
}

struct Hypothesis {
  double yaw;
  Eigen::Vector2d t;
};

// Every (yaw, t) the walls propose: a yaw per pair (A's wall i, B's wall j); a translation per
// two such pairs at that yaw that cross, or, where no two cross, the one pair's offset along
// its normal (the other axis unknown).
std::vector<Hypothesis> hypotheses(const std::vector<Line>& a, const std::vector<Line>& b) {
  std::vector<Hypothesis> out;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) {
      const double yaw = angleBetween(b[j].n, a[i].n);
      const Eigen::Vector2d n1 = rot(yaw) * b[j].n;
      out.push_back({yaw, n1 * (b[j].d - a[i].d)});
      for (std::size_t k = 0; k < a.size(); ++k)
        for (std::size_t l = 0; l < b.size(); ++l) {
          const Eigen::Vector2d n2 = rot(yaw) * b[l].n;
          if (std::abs(angleBetween(a[k].n, n2)) > kMatchAngle_rad) continue;
          if (std::abs(n1.x() * n2.y() - n1.y() * n2.x()) < kMinCrossing) continue;
          Eigen::Matrix2d m;
          m << n1.transpose(), n2.transpose();
          out.push_back({yaw, m.inverse() * Eigen::Vector2d(b[j].d - a[i].d, b[l].d - a[k].d)});
        }
    }
  return out;
}

// How well B's standing points land on A's under a hypothesis: the share of them (every
// kStride-th) in A's occupied 10 cm cells or next to one.
class Overlap {
 public:
  Overlap(const std::vector<Eigen::Vector3f>& a, const std::vector<Eigen::Vector3f>& b) {
    for (const auto& p : a)
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy) {
          const Cell c = cell(p.head<2>().cast<double>());
          cells_.insert({c.first + dx, c.second + dy});
        }
    for (std::size_t k = 0; k < b.size(); k += kStride) b_.push_back(b[k].head<2>().cast<double>());
  }
  double at(const Hypothesis& h) const {
    if (b_.empty()) return 0;
    const Eigen::Matrix2d r = rot(h.yaw);
    std::size_t on = 0;
    for (const auto& p : b_) on += cells_.count(cell(r * p + h.t));
    return double(on) / double(b_.size());
  }
  // t moved along `axis` (unit) to where the points fit best, within the room's length.
  Eigen::Vector2d bestAlong(const Hypothesis& h, const Eigen::Vector2d& axis) const {
    Eigen::Vector2d best = h.t;
    double best_overlap = -1;
    for (double s = -kSearch_m; s <= kSearch_m; s += kSearchStep_m) {
      const Eigen::Vector2d t = h.t + s * axis;
      const double o = at({h.yaw, t});
      if (o > best_overlap) best_overlap = o, best = t;
    }
    return best;
  }

 private:
  static constexpr std::size_t kStride = 4;
  static constexpr double kSearch_m = 8.0, kSearchStep_m = 0.05;
  using Cell = std::pair<int, int>;
  static Cell cell(const Eigen::Vector2d& p) { return {int(std::floor(p.x() / kColumn_m)), int(std::floor(p.y() / kColumn_m))}; }
  std::set<Cell> cells_;
  std::vector<Eigen::Vector2d> b_;
};

// The axis (in A's frame) that the matched walls leave free, when they all run one way.
std::optional<Eigen::Vector2d> freeAxis(const std::vector<Line>& a, const Scored& s) {
  if (s.matches.empty()) return std::nullopt;
  const Eigen::Vector2d n = a[s.matches.front().first].n;
  for (const auto& [i, j] : s.matches)
    if (std::abs(n.x() * a[i].n.y() - n.y() * a[i].n.x()) > kMinCrossing) return std::nullopt;
  return Eigen::Vector2d(-n.y(), n.x());
}

}  // namespace

std::string nebulaPcd(const std::string& sensor) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(BIMLOC_SHARED_REALDATA_DIR) / "nebula" / sensor;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return "";
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.path().extension() == ".pcd") return entry.path().string();
  return "";
}

std::vector<Eigen::Vector3f> standingPoints(const std::vector<Eigen::Vector3f>& points) {
  std::map<std::pair<int, int>, std::pair<float, float>> column;  // (lowest z, highest z)
  auto key = [](const Eigen::Vector3f& p) {
    return std::make_pair(int(std::floor(p.x() / kColumn_m)), int(std::floor(p.y() / kColumn_m)));
  };
  for (const auto& p : points) {
    if (!p.allFinite()) continue;
    auto& c = column.try_emplace(key(p), p.z(), p.z()).first->second;
    c.first = std::min(c.first, p.z()), c.second = std::max(c.second, p.z());
  }
  std::vector<Eigen::Vector3f> out;
  for (const auto& p : points) {
    if (!p.allFinite() || p.head<2>().norm() < kNearRange_m) continue;
    const auto& c = column.at(key(p));
    if (c.second - c.first >= kStandingHeight_m) out.push_back(p);
  }
  return out;
}

planes::PlaneExtractionConfig realFrameConfig() {
  planes::PlaneExtractionConfig c;
  c.ransac_iterations = 5000;
  c.min_inliers = 20;
  c.max_planes = 60;
  c.standing_height_m = 0;  // the points are standing already (standingPoints)
  // The same count at every range: the five lidars' rings are 2 deg apart (VLP-16) or closer,
  // and these settings and the numbers of docs/realdata_room.md were measured so.
  c.ring_spacing_deg = 0;
  return c;
}

planes::PlaneExtractionConfig wholeFrameConfig() {
  planes::PlaneExtractionConfig c = realFrameConfig();
  c.standing_height_m = 0.3;  // 10 cm columns whose returns span 0.3 m, as standingPoints()
  return c;
}

std::vector<planes::ObservedPlane> realFrameWalls(const std::vector<Eigen::Vector3f>& points) {
  return planes::extractPlanes(standingPoints(points), realFrameConfig()).walls;
}

WallAlignment alignWalls(const std::vector<planes::ObservedPlane>& wa, const std::vector<Eigen::Vector3f>& a_standing,
                         const std::vector<planes::ObservedPlane>& wb, const std::vector<Eigen::Vector3f>& b_standing) {
  const std::vector<Line> a = lines(wa), b = lines(wb);
  WallAlignment result;
  const Overlap overlap(a_standing, b_standing);
  // The hypotheses with the most matched walls, each placed along an axis its walls leave
  // free by the points, then the one the points fit best.
  struct Ranked {
    Hypothesis h;
    Scored s;
    double overlap = 0;
  };
  std::vector<Ranked> ranked;
  for (const auto& h : hypotheses(a, b)) ranked.push_back({h, associate(a, b, h.yaw, h.t)});
  auto byMatches = [](const Ranked& x, const Ranked& y) { return better(x.s, y.s); };
  std::sort(ranked.begin(), ranked.end(), byMatches);
  if (ranked.empty() || ranked.front().s.matches.empty()) return result;
  std::vector<Ranked> top;
  for (auto& r : ranked) {
    if (r.s.matches.size() < ranked.front().s.matches.size()) break;
    const bool seen = std::any_of(top.begin(), top.end(), [&](const Ranked& o) {
      return std::abs(angleBetween(rot(o.h.yaw).col(0), rot(r.h.yaw).col(0))) < 0.01 && (o.h.t - r.h.t).norm() < 0.05;
    });
    if (seen) continue;
    if (const auto free = freeAxis(a, r.s)) r.h.t = overlap.bestAlong(r.h, *free);
    r.overlap = overlap.at(r.h);
    top.push_back(r);
  }
  const Ranked& chosen = *std::max_element(top.begin(), top.end(), [](const Ranked& x, const Ranked& y) { return x.overlap < y.overlap; });
  const Scored& best = chosen.s;
  // Refine on the matches: the mean angle, then t by least squares; along a free axis t keeps
  // the points' placement.
  double dyaw = 0;
  for (const auto& [i, j] : best.matches) dyaw += angleBetween(rot(chosen.h.yaw) * b[j].n, a[i].n);
  const double yaw = chosen.h.yaw + dyaw / double(best.matches.size());
  Eigen::MatrixXd m(best.matches.size(), 2);
  Eigen::VectorXd rhs(best.matches.size());
  for (std::size_t k = 0; k < best.matches.size(); ++k) {
    const auto [i, j] = best.matches[k];
    m.row(long(k)) = (rot(yaw) * b[j].n).transpose();
    rhs(long(k)) = b[j].d - a[i].d;
  }
  // Walls all one way: their normals differ by a fraction of a degree, and the axis along them
  // is noise, not measured (rank 1 below a fifth of the largest singular value).
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(m);
  cod.setThreshold(0.2);
  Eigen::Vector2d t = cod.solve(rhs);
  if (const auto free = freeAxis(a, best)) t += free->dot(chosen.h.t) * *free;
  result.pose = Eigen::Vector3d(t.x(), t.y(), yaw);
  result.matches = best.matches;
  result.overlap = overlap.at({yaw, t});
  std::vector<double> directions;
  for (const auto& [i, j] : best.matches) {
    const Line l = moved(b[j], yaw, t);
    result.worst_angle_deg = std::max(result.worst_angle_deg, std::abs(angleBetween(a[i].n, l.n)) * 180.0 / M_PI);
    result.worst_offset_m = std::max(result.worst_offset_m, std::abs(l.d - a[i].d));
  }
  result.directions = freeAxis(a, best) ? 1 : 2;
  // The rectangle's other reading: the best hypothesis turned by 180 degrees, placed the same way.
  std::optional<Ranked> turned;
  for (auto r : ranked) {
    if (std::abs(angleBetween(rot(r.h.yaw).col(0), rot(yaw + M_PI).col(0))) > 0.2) continue;
    if (turned && r.s.matches.size() < turned->s.matches.size()) break;
    if (const auto free = freeAxis(a, r.s)) r.h.t = overlap.bestAlong(r.h, *free);
    r.overlap = overlap.at(r.h);
    if (!turned || r.overlap > turned->overlap) turned = r;
  }
  if (turned) result.turned_matches = int(turned->s.matches.size()), result.turned_overlap = turned->overlap;
  return result;
}

const std::vector<RealFrame>* nebulaFrames() {
  static const std::vector<RealFrame> loaded = [] {
    std::vector<RealFrame> out;
    for (const auto& sensor : kNebulaSensors) {
      const std::string pcd = nebulaPcd(sensor);
      if (pcd.empty()) return std::vector<RealFrame>{};
      RealFrame f;
      f.sensor = sensor;
      f.points = sim::readPcdPoints(pcd);
      f.standing = standingPoints(f.points);
      f.walls = realFrameWalls(f.points);
      f.whole_walls = planes::extractPlanes(f.points, wholeFrameConfig()).walls;
      out.push_back(std::move(f));
    }
    for (std::size_t k = 1; k < out.size(); ++k) out[k].in_vlp = alignWalls(out[0].walls, out[0].standing, out[k].walls, out[k].standing);
    return out;
  }();
  return loaded.empty() ? nullptr : &loaded;
}

Eigen::Vector3d poseInRoom(const RealFrame& frame, const RealFrame& vlp16, double shelf_from_south_m) {
  // The plan's +x is the west wall's normal (pointing into the room, towards the sensor); its
  // -y the shelf front's. Their directions in the VLP-16's frame, averaged.
  const planes::ObservedPlane* west = nullptr;
  const planes::ObservedPlane* shelf = nullptr;
  for (const auto& w : vlp16.walls) {
    const Eigen::Vector2d n = w.normal.head<2>().normalized();
    if (n.y() > 0.99 && (!west || w.d > west->d)) west = &w;
    if (n.x() > 0.99 && (!shelf || w.d > shelf->d)) shelf = &w;
  }
  if (!west || !shelf) return Eigen::Vector3d::Constant(std::nan(""));
  const Eigen::Vector2d n_west = west->normal.head<2>().normalized(), n_shelf = shelf->normal.head<2>().normalized();
  const Eigen::Vector2d x_axis = n_west + Eigen::Vector2d(-n_shelf.y(), n_shelf.x());
  const double west_d = west->d, shelf_d = shelf->d;
  const double room_yaw_in_vlp = std::atan2(x_axis.y(), x_axis.x());
  const double vlp_yaw = -room_yaw_in_vlp;  // the VLP-16's heading in the plan
  const Eigen::Vector2d vlp_xy(west_d, shelf_from_south_m - shelf_d);
  const Eigen::Vector2d xy = vlp_xy + Eigen::Rotation2Dd(vlp_yaw) * frame.in_vlp.pose.head<2>();
  return {xy.x(), xy.y(), std::remainder(vlp_yaw + frame.in_vlp.pose.z(), 2 * M_PI)};
}

}  // namespace bimloc::test
