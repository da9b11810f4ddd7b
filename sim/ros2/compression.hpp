// MCAP chunk compression: "zstd" (libzstd), "lz4" (an LZ4 frame, liblz4) or "" (none).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace bimloc::sim::ros2 {

// Decompresses `size` bytes into exactly `uncompressed_size` bytes. Throws std::runtime_error
// "WHERE: problem" for an unknown compression, a size the data cannot have (bounded by the
// format's largest ratio, so a damaged size allocates nothing huge), or data that does not
// decompress to that size.
std::vector<std::uint8_t> decompress(const std::string& compression, const std::uint8_t* data, std::size_t size,
                                     std::uint64_t uncompressed_size, const std::string& where);

// The same, for a reader that decompresses chunk after chunk: one zstd context and one LZ4
// context for all of them (a fresh context per chunk costs its allocation and initialisation
// every time), and the output written into `out`, whose capacity is reused from chunk to chunk.
// Same bytes, same errors as decompress().
// With `prefix` below uncompressed_size it stops once `prefix` bytes are out (a reader that
// needs only the chunk's first records): `out` then holds at least `prefix` bytes, and the
// data after them is neither decompressed nor checked.
class Decompressor {
 public:
  Decompressor();
  ~Decompressor();
  Decompressor(const Decompressor&) = delete;
  Decompressor& operator=(const Decompressor&) = delete;
  void decompress(const std::string& compression, const std::uint8_t* data, std::size_t size, std::uint64_t uncompressed_size,
                  const std::string& where, std::vector<std::uint8_t>& out, std::uint64_t prefix = UINT64_MAX);

 private:
  struct Contexts;
  std::unique_ptr<Contexts> contexts_;
};

std::vector<std::uint8_t> compress(const std::string& compression, const std::vector<std::uint8_t>& data);

}  // namespace bimloc::sim::ros2
