// One plane by RANSAC (S-Graphs' segmentation: SACMODEL_PLANE, RANSAC, 500 iterations),
// through PCL's model and estimator directly rather than pcl::SACSegmentation, so that the
// sampling can be seeded: PCL seeds every model's generator with the constant 12345 (or the
// wall clock), which would give every call the same sample sequence and no way to vary it.
#include "band_count.hpp"
#include "plane_steps.hpp"

#include <bimloc/verbosity.hpp>

#include <pcl/console/print.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_plane.h>

#include <Eigen/Eigenvalues>
#include <atomic>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>


// Here, where PCL is used: its level is one global, set before every use, so the library is
// quiet without its user having to call anything.
namespace bimloc {
namespace {
std::atomic<bool> g_verbose{false};
}  // namespace
void setVerbose(bool verbose) { g_verbose = verbose; }
bool verbose() { return g_verbose; }
}  // namespace bimloc

namespace bimloc::planes::detail {
namespace {

// RANSAC stops early once this confident that no larger plane was missed (PCL's default).
constexpr double kRansacConfidence = 0.99;
// A pool spread less than this across its main direction is a line (or a point): it holds no
// plane, and PCL's model would report every one of its collinear samples on stderr.
constexpr double kMinPoolWidth_m = 0.01;

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

// PCL's plane model with two changes. Its (protected) sample generator is reseeded: it is only
// used to draw samples, and the estimator runs single-threaded (threads_ = -1, PCL's default),
// so the draws, hence the plane, depend only on the points, the pool and the seed. And its
// scoring loop, which RANSAC runs once per hypothesis over the whole pool and which PCL's
// generic build runs through indices and dynamic-size vectors (about 14 ns a point), runs over
// a packed copy of the pool instead (band_count.hpp): the same count (|n·p + d| < threshold),
// at a thirtieth of the cost and less, stopped once it cannot beat the best count so far.
// That best is the largest count returned: RandomSampleConsensus::computeModel (PCL 1.13,
// ransac.hpp), single-threaded, keeps a hypothesis exactly when its count exceeds every
// earlier one, starting from 0, and calls countWithinDistance for nothing else. A count
// stopped early is no larger than that best, and discarded as the full count would be.
class SeededPlaneModel : public pcl::SampleConsensusModelPlane<pcl::PointXYZ> {
 public:
  SeededPlaneModel(const PointCloudConstPtr& cloud, const pcl::Indices& indices, std::uint32_t seed)
      : pcl::SampleConsensusModelPlane<pcl::PointXYZ>(cloud, indices, false) {
    rng_alg_.seed(seed);
    // PCL's default constraint, [](auto) { return true; }, takes the coefficients by value: a
    // VectorXf copied, so allocated and freed, at every hypothesis scored (isModelValid). The
    // same answer by reference.
    setModelConstraints([](const Eigen::VectorXf&) { return true; });
    x_.reserve(indices.size()), y_.reserve(indices.size()), z_.reserve(indices.size());
    for (const auto i : indices) {
      const auto& p = (*cloud)[i];
      x_.push_back(p.x), y_.push_back(p.y), z_.push_back(p.z);
    }
  }

  std::size_t countWithinDistance(const Eigen::VectorXf& model, const double threshold) const override {
    if (!isModelValid(model)) return 0;
    const std::size_t count = countInBand(x_.data(), y_.data(), z_.data(), x_.size(), model[0], model[1], model[2], model[3],
                                          static_cast<float>(threshold), best_);
    best_ = std::max(best_, count);
    return count;
  }

  // The chosen plane's inliers, as PCL selects them (band_count.hpp: the same float residual,
  // the same test), from the packed pool rather than through the indices.
  void selectWithinDistance(const Eigen::VectorXf& model, const double threshold, pcl::Indices& inliers) override {
    if (!isModelValid(model)) return;  // PCL's own: an error, and the inliers left as they were
    inliers.clear(), error_sqr_dists_.clear();
    pclPlaneInliers(x_.data(), y_.data(), z_.data(), indices_->data(), x_.size(), model[0], model[1], model[2], model[3], threshold,
                    inliers, error_sqr_dists_);
  }

 protected:
  // PCL's test, without its message on stderr for every collinear sample (a quiet library: a
  // degenerate sample is an ordinary event of RANSAC, and the draw simply goes on).
  bool isSampleGood(const pcl::Indices& samples) const override {
    if (samples.size() != 3) return false;
    const Eigen::Vector3f p0 = (*input_)[samples[0]].getVector3fMap(), p1 = (*input_)[samples[1]].getVector3fMap(),
                          p2 = (*input_)[samples[2]].getVector3fMap();
    return (p1 - p0).cross(p2 - p0).stableNorm() >= Eigen::NumTraits<float>::dummy_precision();
  }

 private:
  std::vector<float> x_, y_, z_;
  mutable std::size_t best_ = 0;  // the largest count returned: RANSAC's best so far
};

}  // namespace

void applyPclVerbosity() {
  pcl::console::setVerbosityLevel(verbose() ? pcl::console::L_INFO : pcl::console::L_ALWAYS);
}

struct RansacCloud::Points {
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud{new pcl::PointCloud<pcl::PointXYZ>};
};

RansacCloud::RansacCloud(const Cloud& cloud) : cloud_(&cloud), points_(std::make_unique<Points>()) {
  points_->cloud->resize(cloud.size());  // filled in place: as push_back, without its bookkeeping per point
  for (std::size_t i = 0; i < cloud.size(); ++i) (*points_->cloud)[i] = pcl::PointXYZ(cloud[i].x(), cloud[i].y(), cloud[i].z());
}
RansacCloud::~RansacCloud() = default;

std::optional<RansacPlane> ransacPlane(const Cloud& cloud, const Indices& pool, int iterations, double threshold_m,
                                       std::uint32_t seed) {
  if (pool.size() < 3 || iterations < 1 || !(threshold_m > 0)) return std::nullopt;  // before the copy
  return ransacPlane(RansacCloud(cloud), pool, iterations, threshold_m, seed);
}

std::optional<RansacPlane> ransacPlane(const RansacCloud& input, const Indices& pool, int iterations, double threshold_m,
                                       std::uint32_t seed) {
  applyPclVerbosity();
  const Cloud& cloud = input.cloud();
  if (pool.size() < 3 || iterations < 1 || !(threshold_m > 0) || lineLike(cloud, pool)) return std::nullopt;
  const pcl::Indices indices(pool.begin(), pool.end());

  // The model only reads the points (PCL's models keep their input const).
  auto model = std::make_shared<SeededPlaneModel>(input.points().cloud, indices, seed);
  pcl::RandomSampleConsensus<pcl::PointXYZ> ransac(model, threshold_m);
  ransac.setMaxIterations(iterations);
  ransac.setProbability(kRansacConfidence);
  ransac.setNumberOfThreads(-1);  // sequential: parallel sampling would not be reproducible
  if (!ransac.computeModel()) return std::nullopt;

  Eigen::VectorXf coefficients;
  ransac.getModelCoefficients(coefficients);
  pcl::Indices inliers;
  ransac.getInliers(inliers);
  if (coefficients.size() != 4 || !coefficients.allFinite() || inliers.empty()) return std::nullopt;

  RansacPlane plane;
  plane.normal = coefficients.head<3>().cast<double>();
  const double norm = plane.normal.norm();
  if (!(norm > 0)) return std::nullopt;
  plane.normal /= norm;
  plane.d = coefficients[3] / norm;
  plane.inliers.assign(inliers.begin(), inliers.end());
  std::sort(plane.inliers.begin(), plane.inliers.end());
  return plane;
}

}  // namespace bimloc::planes::detail
