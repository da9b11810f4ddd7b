// The header of a PCD file (v0.7), read and checked before any point is: a header that
// disagrees with itself or with the file's size is refused with the file named, not followed
// into a huge allocation or a read past the end.
#pragma once

#include <cstddef>
#include <istream>
#include <string>
#include <vector>

namespace bimloc::sim {

struct PcdHeader {
  std::vector<std::string> fields;
  std::size_t points = 0;
  std::size_t stride = 0;     // bytes per point (binary)
  std::size_t x_offset = 0;   // byte offset of x within a point; y and z follow as floats
  std::size_t x_index = 0;    // index of the x field (ascii)
  bool binary = true;
  std::size_t data_offset = 0;  // where the point data starts
};

// Reads the header from `in` (left at the start of the data). Throws std::runtime_error
// "PATH: problem" for anything missing or inconsistent; for binary data, also when the file's
// size (`file_size`) is not that of the header's points.
PcdHeader readPcdHeader(const std::string& path, std::istream& in, std::size_t file_size);

}  // namespace bimloc::sim
