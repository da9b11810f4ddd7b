#pragma once
#include "sim/base/gait.hpp"
#include <bimloc/geometry/pose.hpp>
