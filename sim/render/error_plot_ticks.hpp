// Axis ticks for the error plot: round steps on a linear axis, decades on a logarithmic one.
#pragma once

#include <string>
#include <vector>

namespace bimloc::sim::render {

// Multiples of 1, 2 or 5 x 10^k within [lo, hi], at most about `max_count` of them.
std::vector<double> niceTicks(double lo, double hi, int max_count);

// The powers of ten from lo to hi (both powers of ten themselves).
std::vector<double> decades(double lo, double hi);

// Whole decades [lo, hi] around the finite positive values, from `floor` up (an error below
// it, or zero, is "better than we can tell") and at most `cap`; a flat series gets a decade
// of its own, no values a default pair of decades.
void logDecadeRange(const std::vector<double>& values, double floor, double cap, double& lo, double& hi);

// "0.01", "0.1", "1", "10": a decade as a reader writes it.
std::string decadeLabel(double decade);

// A tick's label with no more digits than the step needs: "2.5", "10", "120".
std::string tickLabel(double value, double step);

}  // namespace bimloc::sim::render
