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

}  // namespace bimloc::sim::detail
