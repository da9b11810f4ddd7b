#include "sim/dataset/dataset_reader.hpp"

#include "sim/dataset/dataset_metadata.hpp"
#include "sim/dataset/pcd_header.hpp"
#include "sim/dataset/recording_checks.hpp"
#include "sim/common/json_errors.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace bimloc::sim {
namespace fs = std::filesystem;
namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw std::runtime_error(where + ": " + what); }

std::string at(const std::string& path, int line) { return path + ":" + std::to_string(line); }

std::string seconds(double s) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.9g", s);
  return buffer;
}

// A unit quaternion, as every pose of the dataset must have (a zero one is no rotation).
Eigen::Quaterniond unitQuaternion(double qx, double qy, double qz, double qw, const std::string& where) {
  const Eigen::Quaterniond q(qw, qx, qy, qz);
  if (!std::isfinite(q.norm()) || std::abs(q.norm() - 1.0) > 1e-3)
    fail(where, "quaternion (" + seconds(qx) + ", " + seconds(qy) + ", " + seconds(qz) + ", " + seconds(qw) +
                    ") does not have unit norm");
  return q.normalized();
}

void requireIncreasing(double stamp, const double* previous, const std::string& where) {
  if (!std::isfinite(stamp)) fail(where, "stamp is not a finite number");
  if (previous && !(stamp > *previous))
    fail(where, "stamp " + seconds(stamp) + " does not follow the previous one (" + seconds(*previous) + ")");
}

// One number of a TUM line: "nan" and "inf" parse (as the samples they make are counted, not
// refused); anything else that is no number is an error.
bool tumNumber(std::istringstream& ss, double& value) {
  std::string token;
  if (!(ss >> token)) return false;
  const char* begin = token.c_str();
  char* end = nullptr;
  value = std::strtod(begin, &end);
  return end != begin && *end == '\0';
}

// The samples of a TUM file. A sample that is no pose (a value not finite, a quaternion zero
// or off unit norm) is dropped and counted in `drops`, as the bag readers do; a line that is
// no sample, or a stamp that goes back, is an error.
std::vector<StampedPose> readTum(const std::string& path, bool required, PoseSampleDrops& drops) {
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
    double v[8];
    for (double& x : v)
      if (!tumNumber(ss, x)) fail(at(path, n), "expected 'timestamp tx ty tz qx qy qz qw'");
    const double t = v[0];
    if (!std::isfinite(t)) {  // no time to put it at: dropped with the non-finite poses
      ++drops.read, ++drops.non_finite;
      continue;
    }
    requireIncreasing(t, out.empty() ? nullptr : &out.back().stamp_s, at(path, n));
    const auto pose = checkedPose(v[1], v[2], v[3], v[4], v[5], v[6], v[7], drops);
    if (!pose) continue;
    out.push_back({t, *pose});
  }
  return out;
}

std::string noPoseCounts(const PoseSampleDrops& drops) {
  return std::to_string(drops.non_finite) + " not finite, " + std::to_string(drops.zero_quaternion) +
         " with a zero quaternion, " + std::to_string(drops.not_unit_quaternion) + " with a quaternion not of unit norm";
}

// The value at `key` of an object, or an error naming the key's path in the file.
const nlohmann::json& member(const nlohmann::json& j, const std::string& key, const std::string& where,
                             const std::string& path) {
  if (!j.is_object() || !j.contains(key)) fail(path, "missing key '" + where + key + "'");
  return j[key];
}

std::vector<double> numbers(const nlohmann::json& j, std::size_t n, const std::string& what, const std::string& path) {
  if (!j.is_array() || j.size() != n) fail(path, "'" + what + "' must be an array of " + std::to_string(n) + " numbers");
  std::vector<double> v;
  for (const auto& x : j) {
    if (!x.is_number() || !std::isfinite(x.get<double>())) fail(path, "'" + what + "' holds a value that is no finite number");
    v.push_back(x.get<double>());
  }
  return v;
}

void readMetadata(const std::string& path, RecordedDataset& d) {
  std::ifstream in(path);
  if (!in) fail(path, "cannot open (is this a folder written by 'bimloc simulate'?)");
  nlohmann::json meta;
  try {
    meta = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    fail(path, jsonProblem(e));
  }
  if (!meta.is_object()) fail(path, "not a JSON object");
  if (meta.contains("format") && meta["format"] != "bimloc.dataset")
    fail(path, "format " + meta["format"].dump() + " is not bimloc.dataset");
  const auto& version = member(meta, "version", "", path);
  if (version != kDatasetFormatVersion)
    fail(path, "version " + version.dump() + " is not supported (this bimloc reads version " +
                   std::to_string(kDatasetFormatVersion) + ")");
  const auto& mount = member(meta, "T_base_lidar", "", path);
  const auto t = numbers(member(mount, "xyz", "T_base_lidar.", path), 3, "T_base_lidar.xyz", path);
  const auto q = numbers(member(mount, "quaternion_xyzw", "T_base_lidar.", path), 4, "T_base_lidar.quaternion_xyzw", path);
  d.T_base_lidar.linear() = unitQuaternion(q[0], q[1], q[2], q[3], path + ": T_base_lidar").toRotationMatrix();
  d.T_base_lidar.translation() = Eigen::Vector3d(t[0], t[1], t[2]);
  if (meta.contains("sensor") && meta["sensor"].is_object() && meta["sensor"].contains("rpm")) {
    const auto& rpm = meta["sensor"]["rpm"];
    if (!rpm.is_number() || !(rpm.get<double>() > 0) || !std::isfinite(rpm.get<double>()))
      fail(path, "'sensor.rpm' must be a positive number");
    d.turn_period_s = 60.0 / rpm.get<double>();
  }
  if (meta.contains("storey")) {
    if (!meta["storey"].is_string()) fail(path, "'storey' must be a string");
    d.storey = meta["storey"].get<std::string>();
  }
}

// clouds/index.csv: file,stamp_s,points; every file checked (present, sound header).
std::vector<DatasetScan> readIndex(const std::string& dir) {
  const std::string path = (fs::path(dir) / "clouds" / "index.csv").string();
  std::ifstream index(path);
  if (!index) fail(path, "cannot open");
  std::string line;
  if (!std::getline(index, line) || line.rfind("file,stamp_s,points", 0) != 0)
    fail(at(path, 1), "expected the header 'file,stamp_s,points'");
  std::vector<DatasetScan> scans;
  for (int n = 2; std::getline(index, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto c1 = line.find(','), c2 = c1 == std::string::npos ? c1 : line.find(',', c1 + 1);
    if (c2 == std::string::npos) fail(at(path, n), "expected 'file,stamp_s,points'");
    const std::string name = line.substr(0, c1);
    if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..")
      fail(at(path, n), "'" + name + "' is not a file name in clouds/");
    DatasetScan scan;
    scan.file = (fs::path(dir) / "clouds" / name).string();
    const char* s = line.data() + c1 + 1;
    const auto [end_stamp, ec1] = std::from_chars(s, line.data() + c2, scan.stamp_s);
    if (ec1 != std::errc() || end_stamp != line.data() + c2) fail(at(path, n), "stamp_s is not a number");
    requireIncreasing(scan.stamp_s, scans.empty() ? nullptr : &scans.back().stamp_s, at(path, n));
    const auto [end_points, ec2] = std::from_chars(line.data() + c2 + 1, line.data() + line.size(), scan.points);
    if (ec2 != std::errc() || end_points != line.data() + line.size()) fail(at(path, n), "points is not a count");
    std::ifstream pcd(scan.file, std::ios::binary);
    if (!pcd) fail(at(path, n), scan.file + " is missing");
    std::error_code size_error;
    const auto size = fs::file_size(scan.file, size_error);
    const PcdHeader header = readPcdHeader(scan.file, pcd, size_error ? 0 : size);
    if (header.points != scan.points)
      fail(at(path, n), "points " + std::to_string(scan.points) + ", but " + scan.file + " holds " +
                            std::to_string(header.points));
    scans.push_back(std::move(scan));
  }
  if (scans.empty()) fail(path, "no scans");
  return scans;
}

void requireOverlap(double a0, double a1, const std::string& a, double b0, double b1, const std::string& b,
                    const std::string& dir) {
  if (a0 <= b1 && b0 <= a1) return;
  fail(dir, a + " (" + seconds(a0) + " to " + seconds(a1) + " s) and " + b + " (" + seconds(b0) + " to " + seconds(b1) +
                " s) never overlap in time");
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
  if (!fs::is_directory(dir)) fail(dir, "not a folder (a dataset is a folder written by 'bimloc simulate')");
  readMetadata((fs::path(dir) / "metadata.json").string(), d);
  d.scans = readIndex(dir);
  const std::string odometry = (fs::path(dir) / "odometry.tum").string();
  d.odometry = readTum(odometry, true, d.odometry_drops);
  if (d.odometry.empty() && d.odometry_drops.read > 0)
    fail(odometry, "no poses: all " + std::to_string(d.odometry_drops.read) + " samples are no pose (" +
                       noPoseCounts(d.odometry_drops) + ")");
  if (d.odometry.empty()) fail(odometry, "no poses");
  const std::string ground_truth = (fs::path(dir) / "ground_truth.tum").string();
  d.ground_truth = readTum(ground_truth, false, d.ground_truth_drops);
  if (d.ground_truth.empty() && d.ground_truth_drops.read > 0)
    fail(ground_truth, "no poses: all " + std::to_string(d.ground_truth_drops.read) + " samples are no pose (" +
                           noPoseCounts(d.ground_truth_drops) + ")");
  const double s0 = d.scans.front().stamp_s, s1 = d.scans.back().stamp_s;
  requireOverlap(s0, s1, "the clouds", d.odometry.front().stamp_s, d.odometry.back().stamp_s, "odometry.tum", dir);
  if (!d.ground_truth.empty())
    requireOverlap(s0, s1, "the clouds", d.ground_truth.front().stamp_s, d.ground_truth.back().stamp_s,
                   "ground_truth.tum", dir);
  return d;
}

std::vector<Eigen::Vector3f> readPcdPoints(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open");
  std::error_code size_error;
  const auto size = fs::file_size(path, size_error);
  const PcdHeader h = readPcdHeader(path, in, size_error ? 0 : size);
  std::vector<Eigen::Vector3f> points(h.points);
  if (h.binary) {
    std::vector<char> data(h.points * h.stride);
    if (!in.read(data.data(), static_cast<std::streamsize>(data.size()))) fail(path, "truncated point data");
    for (std::size_t i = 0; i < h.points; ++i)
      std::memcpy(points[i].data(), data.data() + i * h.stride + h.x_offset, 3 * sizeof(float));
  } else {
    std::vector<float> values(h.fields.size());
    for (std::size_t i = 0; i < h.points; ++i) {
      for (auto& v : values)
        if (!(in >> v)) fail(path, "truncated point data at point " + std::to_string(i));
      points[i] = {values[h.x_index], values[h.x_index + 1], values[h.x_index + 2]};
    }
  }
  return points;
}

}  // namespace bimloc::sim
