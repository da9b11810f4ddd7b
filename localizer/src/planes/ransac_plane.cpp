// One plane by RANSAC (S-Graphs' segmentation: SACMODEL_PLANE, RANSAC, 500 iterations): PCL's
// RandomSampleConsensus over its SampleConsensusModelPlane (PCL 1.13), step for step and draw
// for draw, with two differences. The sampling is seeded: PCL seeds every model's generator
// with the constant 12345 (or the wall clock), which would give every call the same sample
// sequence and no way to vary it. And it is written out here, over the packed pool, rather than
// run through PCL's classes: their indices, dynamic-size vectors, virtual calls and debug
// prints cost as much as the count itself (issue 28, Speed). The same planes and inliers to the
// bit: tests/test_ransac_plane.cpp runs PCL's own classes beside it.
#include "band_count.hpp"
#include "plane_steps.hpp"

#include <boost/random/mersenne_twister.hpp>
#include <boost/random/uniform_int.hpp>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace bimloc::planes::detail {
namespace {

// RANSAC stops early once this confident that no larger plane was missed (PCL's default).
constexpr double kRansacConfidence = 0.99;
// A pool spread less than this across its main direction is a line (or a point): it holds no
// plane, and its samples are collinear or nearly so (PCL's model reported each on stderr).
constexpr double kMinPoolWidth_m = 0.01;
// Draws of collinear points before RANSAC gives up (PCL's max_sample_checks_).
constexpr int kMaxSampleChecks = 1000;

bool lineLike(const Cloud& cloud, const Indices& pool) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const int i : pool) mean += cloud[i].cast<double>();
  mean /= double(pool.size());
  // The six distinct entries of the sum of q q^T (q_i q_j and q_j q_i are the same product):
  // the same sums, at two thirds of the work (as fitPlane's moments).
  double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
  for (const int i : pool) {
    const Eigen::Vector3d q = cloud[i].cast<double>() - mean;
    xx += q.x() * q.x(), xy += q.x() * q.y(), xz += q.x() * q.z();
    yy += q.y() * q.y(), yz += q.y() * q.z(), zz += q.z() * q.z();
  }
  Eigen::Matrix3d scatter;
  scatter << xx, xy, xz, xy, yy, yz, xz, yz, zz;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter / double(pool.size()));
  return eig.eigenvalues()[1] < kMinPoolWidth_m * kMinPoolWidth_m;  // ascending: [1] is the middle one
}

// PCL's sample draw (SampleConsensusModel::drawIndexSample, PCL 1.13): three swaps in a
// shuffled copy of the pool, each with a place drawn by boost's uniform_int over [0, INT_MAX]
// from a Mersenne twister seeded by `seed` (PCL seeds it with 12345 and gives no way to vary it).
class SampleDraw {
 public:
  SampleDraw(const Indices& pool, std::uint32_t seed) : shuffled_(pool), engine_(seed), place_(0, std::numeric_limits<int>::max()) {}
  void draw(int sample[3]) {
    const std::size_t n = shuffled_.size();
    for (std::size_t i = 0; i < 3; ++i) std::swap(shuffled_[i], shuffled_[i + (place_(engine_) % (n - i))]);
    std::copy(shuffled_.begin(), shuffled_.begin() + 3, sample);
  }

 private:
  Indices shuffled_;
  boost::mt19937 engine_;
  boost::uniform_int<> place_;
};

// One block of Eigen's stableNorm (StableNorm.h, stable_norm_kernel, Eigen 3.4): the running
// scale rises to the block's largest magnitude, and the sum of squares is kept in its units.
void stableNormBlock(const float* v, int n, float& ssq, float& scale, float& inv_scale) {
  float largest = std::abs(v[0]);
  for (int i = 1; i < n; ++i) largest = std::max(largest, std::abs(v[i]));
  if (largest > scale) {
    const float ratio = scale / largest;
    ssq = ssq * (ratio * ratio);
    const float inverse = 1.0f / largest;
    if (inverse > std::numeric_limits<float>::max()) {
      inv_scale = std::numeric_limits<float>::max(), scale = 1.0f / inv_scale;
    } else if (largest > std::numeric_limits<float>::max()) {
      inv_scale = 1.0f, scale = largest;
    } else {
      scale = largest, inv_scale = inverse;
    }
  } else if (largest != largest) {
    scale = largest;
  }
  if (scale > 0.0f) {
    float sum = (v[0] * inv_scale) * (v[0] * inv_scale);
    for (int i = 1; i < n; ++i) sum += (v[i] * inv_scale) * (v[i] * inv_scale);
    ssq += sum;
  }
}

// The cross product's norm as PCL's compiled plane model gets it (libpcl_sample_consensus 1.13,
// Debian): Eigen's stableNorm cuts a vector into blocks where its storage is 16-byte aligned,
// and that function holds the 3-vector at an address 4 bytes short of it: one block of the
// first coordinate, one of the other two. Another cut (or sqrt of the squared norm) differs in
// the last bit for about one sample in ten, and with it the plane RANSAC keeps.
float pclCrossNorm(const Eigen::Vector3f& cross) {
  float ssq = 0.0f, scale = 0.0f, inv_scale = 1.0f;
  stableNormBlock(cross.data(), 1, ssq, scale, inv_scale);
  stableNormBlock(cross.data() + 1, 2, ssq, scale, inv_scale);
  return scale * std::sqrt(ssq);
}

// The plane through three points (SampleConsensusModelPlane::computeModelCoefficients, with
// its collinearity test, which isSampleGood makes first with the same numbers): none when the
// points are collinear or too close. n·p0 summed as PCL's compiled dot product sums it.
std::optional<Eigen::Vector4f> planeThrough(const Cloud& cloud, const int sample[3]) {
  const Eigen::Vector3f& p0 = cloud[sample[0]];
  const Eigen::Vector3f cross = (cloud[sample[1]] - p0).cross(cloud[sample[2]] - p0);
  const float norm = pclCrossNorm(cross);
  if (norm < Eigen::NumTraits<float>::dummy_precision()) return std::nullopt;
  Eigen::Vector4f model;
  model.head<3>() = cross / norm;
  model[3] = -1.0f * (model[0] * p0.x() + (model[1] * p0.y() + model[2] * p0.z()));
  return model;
}

}  // namespace

std::optional<RansacPlane> ransacPlane(const Cloud& cloud, const Indices& pool, int iterations, double threshold_m,
                                       std::uint32_t seed) {
  if (pool.size() < 3 || iterations < 1 || !(threshold_m > 0) || lineLike(cloud, pool)) return std::nullopt;
  // The pool packed: RANSAC scores every hypothesis over all of it (band_count.hpp: the same
  // count as PCL's, |n·p + d| < threshold, at a thirtieth of its cost and less, stopped once
  // it cannot beat the best count so far; a count stopped early is no larger than that best,
  // and discarded as the full count would be).
  std::vector<float> x, y, z;
  x.reserve(pool.size()), y.reserve(pool.size()), z.reserve(pool.size());
  for (const int i : pool) x.push_back(cloud[i].x()), y.push_back(cloud[i].y()), z.push_back(cloud[i].z());
  const float band = static_cast<float>(threshold_m);

  // RandomSampleConsensus::computeModel (PCL 1.13, ransac.hpp), single-threaded, step for step:
  // a hypothesis replaces the best when it counts more points; the number of trials needed
  // for kRansacConfidence follows the best count; at most iterations + 1 trials. A draw of
  // collinear points is drawn again, up to max_sample_checks_ (1000) times, then RANSAC stops.
  SampleDraw draws(pool, seed);
  const double log_probability = std::log(1.0 - kRansacConfidence);
  const double one_over_indices = 1.0 / static_cast<double>(pool.size());
  double needed = std::numeric_limits<double>::max();
  std::size_t best_count = 0;
  std::optional<Eigen::Vector4f> best;
  for (int trials = 0;;) {
    int sample[3];
    std::optional<Eigen::Vector4f> model;
    for (int check = 0; check < kMaxSampleChecks && !model; ++check) draws.draw(sample), model = planeThrough(cloud, sample);
    if (!model) break;
    const Eigen::Vector4f& m = *model;
    const std::size_t count = countInBand(x.data(), y.data(), z.data(), x.size(), m[0], m[1], m[2], m[3], band, best_count);
    if (count > best_count) {
      best_count = count;
      best = model;
      const double w = static_cast<double>(best_count) * one_over_indices;
      double p_outliers = 1.0 - std::pow(w, 3.0);  // a sample of three holds an outlier
      p_outliers = std::max(std::numeric_limits<double>::epsilon(), p_outliers);
      p_outliers = std::min(1.0 - std::numeric_limits<double>::epsilon(), p_outliers);
      needed = log_probability / std::log(p_outliers);
    }
    ++trials;
    if (trials > needed || trials > iterations) break;
  }
  if (!best) return std::nullopt;

  // The best plane's inliers, as PCL selects them (selectWithinDistance).
  const Eigen::Vector4f& m = *best;
  Indices inliers;
  std::vector<double> distances;
  pclPlaneInliers(x.data(), y.data(), z.data(), pool.data(), x.size(), m[0], m[1], m[2], m[3], threshold_m, inliers, distances);
  if (!m.allFinite() || inliers.empty()) return std::nullopt;

  RansacPlane plane;
  plane.normal = m.head<3>().cast<double>();
  const double norm = plane.normal.norm();
  if (!(norm > 0)) return std::nullopt;
  plane.normal /= norm;
  plane.d = m[3] / norm;
  plane.inliers = std::move(inliers);
  std::sort(plane.inliers.begin(), plane.inliers.end());
  return plane;
}

}  // namespace bimloc::planes::detail
