#include "sim/dataset/dataset_writer.hpp"

#include "sim/dataset/bag_writer.hpp"
#include "sim/dataset/dataset_clock.hpp"
#include "sim/dataset/dataset_metadata.hpp"
#include "sim/dataset/pcap_writer.hpp"
#include "sim/dataset/pcd_writer.hpp"
#include "sim/dataset/ros2_bag_writer.hpp"
#include "sim/dataset/tum_writer.hpp"
#include "sim/dataset/velodyne_points.hpp"
#include "sim/common/atomic_file.hpp"

#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>

namespace bimloc::sim {
namespace fs = std::filesystem;

namespace {

const char* const kBagFile = "dataset.bag";
const char* const kRosbag2Dir = "rosbag2";
const char* const kOdometryFile = "odometry.tum";
const char* const kGroundTruthFile = "ground_truth.tum";
const char* const kCloudDir = "clouds";
const char* const kCloudIndexFile = "clouds/index.csv";
const char* const kMetadataFile = "metadata.json";
const char* const kPcapFile = "velodyne.pcap";

std::string cloudFileName(std::size_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "%06zu.pcd", index);
  return name;
}

// Within one stream, samples must move forward: a bag topic in time order, one TUM pose per
// stamp, and tf never sees the same stamp twice.
std::uint64_t nextStamp(double stamp_s, std::optional<std::uint64_t>& last_ns, const char* stream) {
  const std::uint64_t ns = datasetStampNs(stamp_s);
  if (last_ns && ns <= *last_ns) {
    char what[160];
    std::snprintf(what, sizeof what, "dataset: %s stamp %.9f s does not follow the previous one (%.9f s)", stream,
                  stamp_s, (static_cast<double>(*last_ns) * 1e-9) - kDatasetTimeOffsetS);
    throw std::invalid_argument(what);
  }
  last_ns = ns;
  return ns;
}

std::string tumComment(const std::string& what) {
  char offset[32];
  std::snprintf(offset, sizeof offset, "%g", kDatasetTimeOffsetS);
  return "timestamp tx ty tz qx qy qz qw: " + what + "; timestamp = simulation time + " + offset + " s";
}

void requireFinite(const Eigen::Isometry3d& pose, const char* stream) {
  if (!pose.matrix().allFinite()) throw std::invalid_argument(std::string("dataset: non-finite ") + stream + " pose");
}

}  // namespace

struct DatasetWriter::Impl {
  std::string out_dir;
  DatasetInfo info;
  StagingDirectory staging;  // declared before the writers, so it outlives them
  std::unique_ptr<DatasetBag> bag;
  TumWriter odometry;
  TumWriter ground_truth;
  std::optional<PcapWriter> pcap;  // with packets
  std::string cloud_index = "file,stamp_s,points\n";
  std::vector<std::string> cloud_files;
  std::size_t point_count = 0;
  std::optional<std::uint64_t> last_scan_ns, last_odometry_ns, last_truth_ns;
  std::optional<std::uint64_t> first_ns, last_ns;
  bool finished = false;  // committed, or a commit failed half-way: no more writing

  Impl(const std::string& dir, DatasetInfo dataset_info)
      : out_dir(dir),
        info(std::move(dataset_info)),
        staging(dir, {kMetadataFile, "bimloc.dataset"}),
        bag(openBag(info, staging)),
        odometry(staging.file(kOdometryFile),
                 tumComment("T_odom_base, base_link in odom (the wheel odometry of /odom)")),
        ground_truth(staging.file(kGroundTruthFile),
                     tumComment("T_map_base, base_link in map (the plan's frame; /ground_truth)")) {
    std::error_code ec;
    fs::create_directory(staging.file(kCloudDir), ec);
    if (ec) throw std::runtime_error(staging.file(kCloudDir) + ": cannot create: " + ec.message());
    if (info.packets_rpm > 0) pcap.emplace(staging.file(kPcapFile));
  }

  static std::unique_ptr<DatasetBag> openBag(const DatasetInfo& info, StagingDirectory& staging) {
    if (info.bag_format == "ros1") return std::make_unique<BagWriter>(staging.file(kBagFile), info);
    if (info.bag_format == "mcap" || info.bag_format == "sqlite3")
      return std::make_unique<Ros2BagWriter>(staging.file(kRosbag2Dir), info.bag_format, info);
    throw std::invalid_argument("dataset: bag format '" + info.bag_format + "' unknown (ros1, mcap or sqlite3)");
  }

  void requireOpen() const {
    if (finished) throw std::logic_error("dataset: " + out_dir + ": commit() was already called");
  }

  void span(std::uint64_t ns) {
    first_ns = first_ns ? std::min(*first_ns, ns) : ns;
    last_ns = last_ns ? std::max(*last_ns, ns) : ns;
  }

  nlohmann::json metadata(const std::vector<std::string>& files) const {
    DatasetSummary summary;
    summary.topics = bag->topics();
    summary.scans = cloud_files.size();
    summary.points = point_count;
    summary.odometry = odometry.size();
    summary.ground_truth = ground_truth.size();
    summary.first_ns = first_ns;
    summary.last_ns = last_ns;
    summary.files = files;
    return datasetMetadata(info, summary);
  }
};

DatasetWriter::DatasetWriter(const std::string& out_dir, DatasetInfo info) {
  if (!info.metadata.is_null() && !info.metadata.is_object())
    throw std::invalid_argument("dataset: DatasetInfo::metadata must be a JSON object");
  if (info.metadata.is_null()) info.metadata = nlohmann::json::object();
  if (!info.T_base_lidar.matrix().allFinite()) throw std::invalid_argument("dataset: non-finite T_base_lidar");
  if (out_dir.empty()) throw std::runtime_error("dataset: empty output directory name");
  impl_ = std::make_unique<Impl>(out_dir, std::move(info));
}

DatasetWriter::~DatasetWriter() = default;

void DatasetWriter::addScan(const LidarScan& scan) {
  impl_->requireOpen();
  if (scan.frame_id != kLidarFrame)
    throw std::invalid_argument("dataset: scan in frame '" + scan.frame_id + "', expected '" + kLidarFrame + "'");
  if (scan.points.size() > std::numeric_limits<std::uint32_t>::max() / kVelodynePointStepBytes)
    throw std::invalid_argument("dataset: scan too large for a PointCloud2");
  const std::uint64_t ns = nextStamp(scan.stamp_s, impl_->last_scan_ns, "scan");
  const std::size_t index = impl_->cloud_files.size();
  const std::string name = cloudFileName(index);
  impl_->bag->writeScan(ns, static_cast<std::uint32_t>(index), scan);
  if (impl_->pcap) {
    // The packets on the dataset's clock, as a driver stamps them: the turn's first firing at
    // the scan's stamp.
    const double stamp_s = static_cast<double>(ns) * 1e-9;
    const auto packets = encodeVlp16Turn(scan, impl_->info.packets_rpm, stamp_s);
    impl_->bag->writePackets(ns, static_cast<std::uint32_t>(index), packets);
    for (const auto& packet : packets) impl_->pcap->writeUdp(packet.stamp_s, packet.data.data(), packet.data.size(), kVlp16DataPort);
  }
  writePcd(impl_->staging.file(std::string(kCloudDir) + "/" + name), scan.points);
  impl_->cloud_files.push_back(std::string(kCloudDir) + "/" + name);
  impl_->cloud_index += name + "," + formatStampS(ns) + "," + std::to_string(scan.points.size()) + "\n";
  impl_->point_count += scan.points.size();
  impl_->span(ns);
}

void DatasetWriter::addOdometry(const OdometrySample& odom) {
  impl_->requireOpen();
  requireFinite(odom.T_odom_base, "odometry");
  if (!odom.linear_velocity_base.allFinite() || !odom.angular_velocity_base.allFinite())
    throw std::invalid_argument("dataset: non-finite odometry velocity");
  const std::uint64_t ns = nextStamp(odom.stamp_s, impl_->last_odometry_ns, "odometry");
  impl_->bag->writeOdometry(ns, static_cast<std::uint32_t>(impl_->odometry.size()), odom);
  impl_->odometry.add(ns, odom.T_odom_base);
  impl_->span(ns);
}

void DatasetWriter::addGroundTruth(const GroundTruthSample& truth) {
  impl_->requireOpen();
  requireFinite(truth.T_map_base, "ground truth");
  const std::uint64_t ns = nextStamp(truth.stamp_s, impl_->last_truth_ns, "ground truth");
  impl_->bag->writeGroundTruth(ns, static_cast<std::uint32_t>(impl_->ground_truth.size()), truth);
  impl_->ground_truth.add(ns, truth.T_map_base);
  impl_->span(ns);
}

std::vector<std::string> DatasetWriter::commit() {
  impl_->requireOpen();
  impl_->finished = true;
  impl_->bag->close();
  impl_->odometry.close();
  impl_->ground_truth.close();
  if (impl_->pcap) impl_->pcap->close();
  writeFileAtomically(impl_->staging.file(kCloudIndexFile), impl_->cloud_index);

  std::vector<std::string> files;
  if (impl_->info.bag_format == "ros1") files.push_back(kBagFile);
  else files.insert(files.end(), {std::string(kRosbag2Dir) + "/metadata.yaml",
                                  std::string(kRosbag2Dir) + (impl_->info.bag_format == "mcap" ? "/rosbag2_0.mcap" : "/rosbag2_0.db3")});
  files.insert(files.end(), {kMetadataFile, kOdometryFile, kGroundTruthFile, kCloudIndexFile});
  if (impl_->pcap) files.push_back(kPcapFile);
  files.insert(files.end(), impl_->cloud_files.begin(), impl_->cloud_files.end());
  writeFileAtomically(impl_->staging.file(kMetadataFile), impl_->metadata(files).dump(1) + "\n");

  impl_->staging.commit();
  return files;
}

}  // namespace bimloc::sim
