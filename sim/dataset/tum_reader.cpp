#include "sim/dataset/tum_reader.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace bimloc::sim {

namespace {

constexpr double kUnitTolerance = 1e-6;  // |‖q‖ - 1| beyond this: not written as a unit quaternion

std::string seconds(double s) {
  char b[48];
  std::snprintf(b, sizeof b, "%.9f", s);
  return b;
}

}  // namespace

TumTrajectory readTum(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open: " + std::strerror(errno));
  TumTrajectory t;
  t.path = path;
  std::string line;
  int number = 0, non_unit = 0, first_non_unit = 0;
  while (std::getline(in, line)) {
    ++number;
    const auto at = [&](const std::string& why) { return std::runtime_error(path + ":" + std::to_string(number) + ": " + why); };
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    std::vector<double> v;
    std::string word;
    while (fields >> word) {
      char* end = nullptr;
      const double x = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0') throw at("'" + word + "' is not a number (expected: timestamp tx ty tz qx qy qz qw)");
      if (!std::isfinite(x)) throw at("'" + word + "' is not a finite number");
      v.push_back(x);
    }
    if (v.size() != 8)
      throw at(std::to_string(v.size()) + " values, expected 8: timestamp tx ty tz qx qy qz qw");
    if (!t.stamps_s.empty() && !(v[0] > t.stamps_s.back()))
      throw at("timestamp " + seconds(v[0]) + " is not after the previous pose's, " + seconds(t.stamps_s.back()) +
               " (TUM stamps must increase strictly)");
    Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);  // w, x, y, z
    const double norm = q.norm();
    if (!(norm > 1e-9)) throw at("the quaternion is zero: no rotation");
    if (std::abs(norm - 1.0) > kUnitTolerance && non_unit++ == 0) first_non_unit = number;
    q.normalize();
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = q.toRotationMatrix();
    pose.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
    t.stamps_s.push_back(v[0]);
    t.poses.push_back(pose);
  }
  if (in.bad()) throw std::runtime_error(path + ": read failed: " + std::strerror(errno));
  if (t.poses.empty()) throw std::runtime_error(path + ": no pose (expected lines of: timestamp tx ty tz qx qy qz qw)");
  if (non_unit > 0)
    t.warnings.push_back(path + ":" + std::to_string(first_non_unit) + ": " + std::to_string(non_unit) +
                         " quaternion(s) not of unit norm (first on this line), normalised");
  return t;
}

}  // namespace bimloc::sim
