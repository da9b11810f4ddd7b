#include "sim/dataset/dataset_clock.hpp"

#include "sim/dataset/dataset_writer.hpp"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace bimloc::sim {

namespace {
constexpr std::uint64_t kNsPerS = 1000000000ULL;
}  // namespace

std::uint64_t datasetStampNs(double stamp_s) {
  // Rounding the simulation stamp alone, then adding the offset as an integer, keeps the
  // nanoseconds the caller meant (stamp_s + 1000.0 in double would already round).
  const double ns = std::round(stamp_s * 1e9) + kDatasetTimeOffsetS * 1e9;
  // ros::Time holds uint32 seconds; a zero stamp is refused by rosbag.
  if (!std::isfinite(ns) || ns < 1.0 || ns >= 4294967296.0 * 1e9) {
    char what[96];
    std::snprintf(what, sizeof what, "stamp %.9g s is outside the dataset's clock", stamp_s);
    throw std::invalid_argument(what);
  }
  const std::int64_t offset_ns = static_cast<std::int64_t>(kDatasetTimeOffsetS) * static_cast<std::int64_t>(kNsPerS);
  return static_cast<std::uint64_t>(std::llround(stamp_s * 1e9) + offset_ns);
}

std::string formatStampS(std::uint64_t stamp_ns) {
  char text[48];
  std::snprintf(text, sizeof text, "%" PRIu64 ".%09" PRIu64, stamp_ns / kNsPerS, stamp_ns % kNsPerS);
  return text;
}

}  // namespace bimloc::sim
