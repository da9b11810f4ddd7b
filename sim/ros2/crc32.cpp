#include "sim/ros2/crc32.hpp"

#ifdef BIMLOC_HAVE_ISAL
#include <isa-l/crc.h>
#else
#include <zlib.h>

#include <algorithm>
#include <limits>
#endif

namespace bimloc::sim::ros2 {

#ifdef BIMLOC_HAVE_ISAL

// crc32_gzip_refl takes and returns the CRC in zlib's convention (the XORs applied inside), so
// it chains exactly as zlib's crc32 does; its length is 64-bit.
std::uint32_t crc32Update(std::uint32_t crc, const std::uint8_t* data, std::size_t n) {
  if (n == 0) return crc;  // (zlib's convention; no pointer is read)
  return crc32_gzip_refl(crc, data, n);
}

const char* crc32Implementation() { return "isa-l"; }

#else

std::uint32_t crc32Update(std::uint32_t crc, const std::uint8_t* data, std::size_t n) {
  while (n > 0) {  // zlib takes a uInt length
    const uInt step = static_cast<uInt>(std::min<std::size_t>(n, std::numeric_limits<uInt>::max()));
    crc = static_cast<std::uint32_t>(::crc32(crc, data, step));
    data += step, n -= step;
  }
  return crc;
}

const char* crc32Implementation() { return "zlib"; }

#endif

}  // namespace bimloc::sim::ros2
