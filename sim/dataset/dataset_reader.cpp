#include "sim/dataset/dataset_reader.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace bimloc::sim {
namespace fs = std::filesystem;
namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw std::runtime_error(where + ": " + what); }

std::vector<StampedPose> readTum(const std::string& path, bool required) {
  std::ifstream in(path);
  if (!in) {
    if (required) fail(path, "cannot open");
    return {};
  }
  std::vector<StampedPose> out;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    double t, x, y, z, qx, qy, qz, qw;
    if (!(ss >> t >> x >> y >> z >> qx >> qy >> qz >> qw)) fail(path + ":" + std::to_string(n), "expected 'timestamp tx ty tz qx qy qz qw'");
    StampedPose p;
    p.stamp_s = t;
    p.pose.linear() = Eigen::Quaterniond(qw, qx, qy, qz).normalized().toRotationMatrix();
    p.pose.translation() = Eigen::Vector3d(x, y, z);
    if (!p.pose.matrix().allFinite()) fail(path + ":" + std::to_string(n), "non-finite pose");
    out.push_back(p);
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.stamp_s < b.stamp_s; });
  return out;
}

Eigen::Isometry3d isometry(const nlohmann::json& j) {
  const auto& t = j.at("xyz");
  const auto& q = j.at("quaternion_xyzw");
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(q[3].get<double>(), q[0].get<double>(), q[1].get<double>(), q[2].get<double>())
                   .normalized()
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(t[0].get<double>(), t[1].get<double>(), t[2].get<double>());
  return T;
}

}  // namespace

const StampedPose& nearest(const std::vector<StampedPose>& samples, double t) {
  auto it = std::lower_bound(samples.begin(), samples.end(), t, [](const StampedPose& s, double v) { return s.stamp_s < v; });
  if (it == samples.end()) return samples.back();
  if (it != samples.begin() && t - std::prev(it)->stamp_s < it->stamp_s - t) --it;
  return *it;
}

RecordedDataset readDataset(const std::string& dir) {
  RecordedDataset d;
  d.dir = dir;
  const std::string meta_path = (fs::path(dir) / "metadata.json").string();
  std::ifstream meta_in(meta_path);
  if (!meta_in) fail(meta_path, "cannot open (is this a folder written by 'bimloc simulate'?)");
  try {
    const auto meta = nlohmann::json::parse(meta_in);
    d.T_base_lidar = isometry(meta.at("T_base_lidar"));
    if (meta.contains("sensor") && meta["sensor"].contains("rpm")) d.turn_period_s = 60.0 / meta["sensor"]["rpm"].get<double>();
    d.storey = meta.value("storey", "");
  } catch (const std::exception& e) {
    fail(meta_path, e.what());
  }
  const std::string index_path = (fs::path(dir) / "clouds" / "index.csv").string();
  std::ifstream index(index_path);
  if (!index) fail(index_path, "cannot open");
  std::string line;
  std::getline(index, line);  // header
  for (int n = 2; std::getline(index, line); ++n) {
    const auto c1 = line.find(','), c2 = line.find(',', c1 + 1);
    if (c1 == std::string::npos || c2 == std::string::npos) fail(index_path + ":" + std::to_string(n), "expected 'file,stamp_s,points'");
    d.scans.push_back({(fs::path(dir) / "clouds" / line.substr(0, c1)).string(), std::stod(line.substr(c1 + 1, c2 - c1 - 1))});
  }
  d.odometry = readTum((fs::path(dir) / "odometry.tum").string(), true);
  if (d.odometry.empty()) fail((fs::path(dir) / "odometry.tum").string(), "no poses");
  d.ground_truth = readTum((fs::path(dir) / "ground_truth.tum").string(), false);
  return d;
}

std::vector<Eigen::Vector3f> readPcdPoints(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open");
  std::map<std::string, std::vector<std::string>> header;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::string key, value;
    ss >> key;
    while (ss >> value) header[key].push_back(value);
    if (key == "DATA") break;
  }
  const auto& fields = header["FIELDS"];
  const auto& sizes = header["SIZE"];
  if (fields.empty() || sizes.size() != fields.size() || header["POINTS"].empty() || header["DATA"].empty())
    fail(path, "not a PCD file (missing FIELDS, SIZE, POINTS or DATA)");
  std::size_t offset = 0, stride = 0;
  int x = -1;
  std::vector<std::size_t> offsets;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    offsets.push_back(stride);
    stride += std::stoul(sizes[i]);
    if (fields[i] == "x") x = static_cast<int>(i);
  }
  if (x < 0 || x + 2 >= static_cast<int>(fields.size()) || fields[x + 1] != "y" || fields[x + 2] != "z")
    fail(path, "no consecutive x y z fields");
  offset = offsets[static_cast<std::size_t>(x)];
  const std::size_t n = std::stoul(header["POINTS"][0]);
  std::vector<Eigen::Vector3f> points(n);
  if (header["DATA"][0] == "binary") {
    std::vector<char> buffer(n * stride);
    if (!in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()))) fail(path, "truncated point data");
    for (std::size_t i = 0; i < n; ++i) std::memcpy(points[i].data(), buffer.data() + i * stride + offset, 3 * sizeof(float));
  } else if (header["DATA"][0] == "ascii") {
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<float> values(fields.size());
      for (auto& v : values)
        if (!(in >> v)) fail(path, "truncated point data at point " + std::to_string(i));
      points[i] = {values[static_cast<std::size_t>(x)], values[static_cast<std::size_t>(x) + 1], values[static_cast<std::size_t>(x) + 2]};
    }
  } else {
    fail(path, "unsupported DATA '" + header["DATA"][0] + "'");
  }
  return points;
}

}  // namespace bimloc::sim
