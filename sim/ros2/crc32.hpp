// The CRC-32 MCAP puts on its chunks and its summary: zlib's (ISO-HDLC, reflected polynomial
// 0xEDB88320, initial and final XOR 0xFFFFFFFF), over `n` bytes, continuing from `crc` (0 to
// start): crc32Update(crc32Update(0, a, n), b, m) is the CRC of a then b.
//
// Computed by Intel ISA-L's crc32_gzip_refl where CMake found libisal (BIMLOC_HAVE_ISAL): it
// folds 64 bytes at a time with carry-less multiplies (PCLMULQDQ), chosen at run time for the
// CPU, several times faster than zlib's table-driven crc32 on a chunk of megabytes. Else zlib's.
#pragma once

#include <cstddef>
#include <cstdint>

namespace bimloc::sim::ros2 {

std::uint32_t crc32Update(std::uint32_t crc, const std::uint8_t* data, std::size_t n);

// "isa-l" or "zlib": which implementation this build computes the CRC with.
const char* crc32Implementation();

}  // namespace bimloc::sim::ros2
