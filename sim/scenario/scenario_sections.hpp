// The sections of a scenario file, each read from its mapping with its keys, types and ranges.
#pragma once

#include "sim/scenario/scenario.hpp"
#include "sim/scenario/yaml_mapping.hpp"

namespace bimloc::sim::detail {

StartConfig readStart(const Mapping& top, std::map<std::string, int>& lines);
MotionConfig readMotion(const Mapping& top, std::map<std::string, int>& lines);
Vlp16Config readSensor(const Mapping& top);
OdometryConfig readOdometry(const Mapping& top);
Expectations readExpect(const Mapping& top);
SiteConfig readSite(const Mapping& top, std::map<std::string, int>& lines);
// The site's edits name walls and doors of the plan (a suggestion for a typo).
void checkSiteAgainstWorld(const Scenario& scenario, const World& world);

}  // namespace bimloc::sim::detail
