#include "sim/ros2/compression.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <memory>
#include <stdexcept>

namespace bimloc::sim::ros2 {
namespace {

// The largest expansion each format allows, with room for headers: zstd's blocks cannot
// expand beyond about 1:32768 (a block of 128 KiB from 4 bytes), LZ4's beyond 1:255.
std::uint64_t largestExpansion(const std::string& compression, std::size_t size) {
  const std::uint64_t s = size;
  if (compression == "zstd") return s * 32768 + (1u << 20);
  return s * 256 + (1u << 20);
}

}  // namespace

std::vector<std::uint8_t> decompress(const std::string& compression, const std::uint8_t* data, std::size_t size,
                                     std::uint64_t uncompressed_size, const std::string& where) {
  auto fail = [&](const std::string& what) -> std::runtime_error {
    return std::runtime_error(where + ": " + (compression.empty() ? "uncompressed" : compression) + " chunk: " + what);
  };
  if (compression.empty()) {
    if (uncompressed_size != size)
      throw fail("uncompressed_size " + std::to_string(uncompressed_size) + " differs from its " + std::to_string(size) + " bytes");
    return std::vector<std::uint8_t>(data, data + size);
  }
  if (compression != "zstd" && compression != "lz4") throw fail("unknown compression (bimloc reads zstd, lz4 or none)");
  if (uncompressed_size > largestExpansion(compression, size))
    throw fail("uncompressed_size " + std::to_string(uncompressed_size) + " is more than " + std::to_string(size) +
               " compressed bytes can hold");
  std::vector<std::uint8_t> out(static_cast<std::size_t>(uncompressed_size));
  if (compression == "zstd") {
    const std::size_t got = ZSTD_decompress(out.data(), out.size(), data, size);
    if (ZSTD_isError(got)) throw fail(std::string("does not decompress: ") + ZSTD_getErrorName(got));
    if (got != out.size())
      throw fail("decompresses to " + std::to_string(got) + " bytes, not the " + std::to_string(out.size()) + " it declares");
    return out;
  }
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) throw fail("no LZ4 context");
  std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> ctx(raw, LZ4F_freeDecompressionContext);
  std::size_t in_pos = 0, out_pos = 0;
  while (true) {
    std::size_t in_n = size - in_pos, out_n = out.size() - out_pos;
    const std::size_t hint = LZ4F_decompress(ctx.get(), out.data() + out_pos, &out_n, data + in_pos, &in_n, nullptr);
    if (LZ4F_isError(hint)) throw fail(std::string("does not decompress: ") + LZ4F_getErrorName(hint));
    in_pos += in_n, out_pos += out_n;
    if (hint == 0) break;  // the frame is complete
    if (in_n == 0 && out_n == 0) {
      if (out_pos == out.size()) throw fail("decompresses to more than the " + std::to_string(out.size()) + " bytes it declares");
      throw fail("the LZ4 frame ends early (" + std::to_string(in_pos) + " of " + std::to_string(size) + " bytes read)");
    }
  }
  if (out_pos != out.size())
    throw fail("decompresses to " + std::to_string(out_pos) + " bytes, not the " + std::to_string(out.size()) + " it declares");
  return out;
}

std::vector<std::uint8_t> compress(const std::string& compression, const std::vector<std::uint8_t>& data) {
  if (compression.empty()) return data;
  if (compression == "zstd") {
    std::vector<std::uint8_t> out(ZSTD_compressBound(data.size()));
    const std::size_t n = ZSTD_compress(out.data(), out.size(), data.data(), data.size(), 3);
    if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(n));
    out.resize(n);
    return out;
  }
  if (compression == "lz4") {
    LZ4F_preferences_t prefs{};
    prefs.frameInfo.contentSize = data.size();
    std::vector<std::uint8_t> out(LZ4F_compressFrameBound(data.size(), &prefs));
    const std::size_t n = LZ4F_compressFrame(out.data(), out.size(), data.data(), data.size(), &prefs);
    if (LZ4F_isError(n)) throw std::runtime_error(std::string("lz4: ") + LZ4F_getErrorName(n));
    out.resize(n);
    return out;
  }
  throw std::runtime_error("unknown compression '" + compression + "'");
}

}  // namespace bimloc::sim::ros2
