#include "sim/dataset/dataset_metadata.hpp"

#include "sim/dataset/tum_writer.hpp"
#include "sim/dataset/velodyne_points.hpp"

namespace bimloc::sim {

nlohmann::json poseJson(const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond q = canonicalRotation(pose);
  const Eigen::Vector3d t = pose.translation();
  return {{"xyz", {t.x(), t.y(), t.z()}}, {"quaternion_xyzw", {q.x(), q.y(), q.z(), q.w()}}};
}

namespace {

nlohmann::json pointFieldsJson() {
  nlohmann::json fields = nlohmann::json::array();
  for (const PointFieldLayout& f : velodynePointFields())
    fields.push_back({{"name", f.name},
                      {"offset", f.offset_bytes},
                      {"datatype", f.type == PointFieldType::kFloat32 ? "FLOAT32" : "UINT16"},
                      {"count", 1}});
  return fields;
}

nlohmann::json topicsJson(const std::map<std::string, BagWriter::TopicCount>& counts) {
  nlohmann::json topics = nlohmann::json::object();
  for (const auto& [topic, count] : counts) topics[topic] = {{"type", count.type}, {"messages", count.messages}};
  topics[kCloudTopic]["frame_id"] = kLidarFrame;
  topics[kOdomTopic]["frame_id"] = kOdomFrame;
  topics[kOdomTopic]["child_frame_id"] = kBaseFrame;
  topics[kTfTopic]["transforms"] = {std::string(kOdomFrame) + " -> " + kBaseFrame,
                                    std::string(kBaseFrame) + " -> " + kLidarFrame};
  topics[kGroundTruthTopic]["frame_id"] = kMapFrame;
  topics[kGroundTruthTopic]["child_frame_id"] = kBaseFrame;
  topics[kGroundTruthTopic]["note"] = "pose only: twist and covariance are zero";
  return topics;
}

}  // namespace

nlohmann::json datasetMetadata(const DatasetInfo& info, const DatasetSummary& summary) {
  nlohmann::json doc = info.metadata.is_object() ? info.metadata : nlohmann::json::object();
  doc["format"] = "bimloc.dataset";
  doc["version"] = kDatasetFormatVersion;
  doc["frames"] = {{"map", kMapFrame}, {"odom", kOdomFrame}, {"base_link", kBaseFrame}, {"velodyne", kLidarFrame}};
  doc["T_base_lidar"] = poseJson(info.T_base_lidar);
  doc["T_base_lidar"]["parent"] = kBaseFrame;
  doc["T_base_lidar"]["child"] = kLidarFrame;
  doc["time_offset_s"] = kDatasetTimeOffsetS;
  doc["time_base"] = "every stamp (bag, TUM files, clouds/index.csv) is the simulation time + time_offset_s";
  const auto seconds = [](std::uint64_t ns) { return static_cast<double>(ns) * 1e-9; };
  doc["time_range_s"] = summary.first_ns ? nlohmann::json{seconds(*summary.first_ns), seconds(*summary.last_ns)}
                                         : nlohmann::json(nullptr);
  doc["topics"] = topicsJson(summary.topics);
  doc["pointcloud2"] = {{"point_step", kVelodynePointStepBytes}, {"fields", pointFieldsJson()}};
  doc["counts"] = {{"scans", summary.scans},
                   {"points", summary.points},
                   {"odometry", summary.odometry},
                   {"ground_truth", summary.ground_truth}};
  doc["clouds_index"] = "clouds/index.csv: file (relative to clouds/), stamp_s, points";
  doc["files"] = summary.files;
  return doc;
}

}  // namespace bimloc::sim
