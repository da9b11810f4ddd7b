// metadata.json of a dataset: the caller's description of the run plus what the writer knows
// (format, frames, mount, clock, topics and counts, point layout, files).
#pragma once

#include "sim/dataset/bag_writer.hpp"
#include "sim/dataset/dataset_writer.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::sim {

inline constexpr int kDatasetFormatVersion = 1;

struct DatasetSummary {
  std::map<std::string, DatasetBag::TopicCount> topics;
  std::size_t scans = 0, points = 0, odometry = 0, ground_truth = 0;
  std::optional<std::uint64_t> first_ns, last_ns;  // dataset time span of all streams
  std::vector<std::string> files;                  // relative to the dataset directory
};

// info.metadata with the writer's keys added (they win on a clash).
// A pose as {"xyz": [...], "quaternion_xyzw": [...]} (w >= 0), as metadata.json writes poses.
nlohmann::json poseJson(const Eigen::Isometry3d& pose);

nlohmann::json datasetMetadata(const DatasetInfo& info, const DatasetSummary& summary);

}  // namespace bimloc::sim
