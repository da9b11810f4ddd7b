// The median of a band's residuals, which the trimmed refit (refine.cpp) asks for five times
// per candidate plane, over every return near it: std::nth_element's introselect was half of
// the refit's time (perf, floor100 R065), its comparisons of random residuals mispredicted.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace bimloc::planes::detail {

// The k-th smallest of `values` (0-based, k < values.size()): the value std::nth_element(begin,
// begin + k, end) leaves at begin + k, the same double. For values that are all >= 0 and none
// NaN (residuals |r|), by radix selection on their bits, most significant byte first: the bits
// of a non-negative double, read as an unsigned integer, order as its value (IEEE 754), so
// the k-th smallest integer is the k-th smallest value's bits. Otherwise (a negative value or
// a NaN) by std::nth_element on a copy. `scratch` is reused between calls.
double kthSmallest(const std::vector<double>& values, std::size_t k, std::vector<std::uint64_t>& scratch);

}  // namespace bimloc::planes::detail
