#include "recording_fixtures.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <map>

namespace bimloc::test {

std::string recordingPlan() { return std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc"; }

std::string simulatedRecording(const std::string& tag) {
  static std::map<std::string, std::string> made;
  auto it = made.find(tag);
  if (it != made.end()) return it->second;
  const std::string d = tempDir(tag);
  std::ofstream(d + "/s.yaml") << "name: " << tag << "\nworld: " << recordingPlan()
                               << "\nstart: {room: C100, yaw_deg: 0}\nmotion: {type: tour, rooms: [R101]}\n"
                                  "duration_s: 8\nodometry: {preset: legged}\nseed: 3\n";
  const auto r = runBimloc("simulate '" + d + "/s.yaml' --out '" + d + "/data' --quiet");
  if (r.exit_code != 0) ADD_FAILURE() << r.err;
  return made[tag] = d;
}

}  // namespace bimloc::test
