// x / cell for a grid's cell index, as a multiplication where that gives the same bits. A
// division costs 13-20 cycles of latency, and the face index divides a dozen times per query
// (path evidence, seeds, places: about a million queries on a 40 s search of a 100-room floor).
// Where the cell is a power of two (the face index's 1 m, the room index's 0.5 m), its
// reciprocal is exact, and x * (1 / cell) and x / cell are the correctly rounded values of one
// real number (IEEE 754): the same double, so the same cells, in the same order.
#pragma once

#include <cmath>

namespace bimloc::pf::detail {

class CellScale {
 public:
  explicit CellScale(double cell_m) : cell_m_(cell_m) {
    int exponent = 0;
    // A power of two: its mantissa is exactly 1/2 (frexp), and its reciprocal is representable
    // (not past the exponent range: 2^-1022 and up, then 1 / cell <= 2^1022).
    exact_ = std::isfinite(cell_m) && cell_m > 0.0 && std::frexp(cell_m, &exponent) == 0.5 && exponent > -1021;
    inverse_ = exact_ ? 1.0 / cell_m : 0.0;
  }
  double operator()(double x) const { return exact_ ? x * inverse_ : x / cell_m_; }

 private:
  double cell_m_;
  double inverse_;
  bool exact_;
};

}  // namespace bimloc::pf::detail
