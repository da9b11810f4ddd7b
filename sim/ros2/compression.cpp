#include "sim/ros2/compression.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
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

// No chunk of a recording comes near this (rosbag2 writes chunks of 768 KiB, a message larger
// than that makes a chunk of its own size: tens of MB for the densest clouds).
constexpr std::uint64_t kLargestChunkBytes = std::uint64_t{1} << 30;

}  // namespace

struct Decompressor::Contexts {
  std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> zstd{nullptr, ZSTD_freeDCtx};
  std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> lz4{nullptr, LZ4F_freeDecompressionContext};
  // The LZ4 context was left in mid-frame (a prefix read, a damaged chunk): liblz4 1.9.4's
  // LZ4F_resetDecompressionContext does not clear the frame's remaining content size, which the
  // next frame, if its header declares no size (an empty chunk), inherits and is refused with
  // ERROR_frameSize_wrong. Such a context is replaced by a new one, not reset.
  bool lz4_mid_frame = false;
};

Decompressor::Decompressor() : contexts_(std::make_unique<Contexts>()) {}
Decompressor::~Decompressor() = default;

void Decompressor::decompress(const std::string& compression, const std::uint8_t* data, std::size_t size,
                              std::uint64_t uncompressed_size, const std::string& where, std::vector<std::uint8_t>& out,
                              std::uint64_t prefix) {
  auto fail = [&](const std::string& what) -> std::runtime_error {
    return std::runtime_error(where + ": " + (compression.empty() ? "uncompressed" : compression) + " chunk: " + what);
  };
  if (compression.empty()) {
    if (uncompressed_size != size)
      throw fail("uncompressed_size " + std::to_string(uncompressed_size) + " differs from its " + std::to_string(size) + " bytes");
    out.assign(data, data + size);
    return;
  }
  if (compression != "zstd" && compression != "lz4") throw fail("unknown compression (bimloc reads zstd, lz4 or none)");
  if (uncompressed_size > largestExpansion(compression, size) || uncompressed_size > kLargestChunkBytes)
    throw fail("uncompressed_size " + std::to_string(uncompressed_size) + " is more than " + std::to_string(size) +
               " compressed bytes can hold (or than a chunk of 1 GiB)");
  // Decompressed as a stream into a buffer that grows with what actually comes out: a damaged
  // size never allocates more than the data really holds (beyond what an earlier chunk needed).
  // The output is bounded by what the reader needs (`goal`): the whole chunk, or its prefix.
  const std::uint64_t goal = std::min(uncompressed_size, prefix);
  const bool partial = goal < uncompressed_size;
  const std::size_t first = static_cast<std::size_t>(std::min<std::uint64_t>(goal, std::max<std::size_t>(out.size(), 16u << 20)));
  if (first > out.capacity()) {
    // Grown without keeping the earlier chunk's bytes (resize would copy them over, and touch
    // twice the pages), with room for the next chunks: a writer closes a chunk once it passes
    // its size, so the chunks of a file differ by about one message (a quarter covers it).
    out.clear();
    out.reserve(first + first / 4);
  }
  out.resize(first);
  std::size_t in_pos = 0, out_pos = 0;
  auto room = [&] {
    if (out_pos < out.size()) return true;
    if (out.size() >= goal) return false;
    out.resize(static_cast<std::size_t>(std::min<std::uint64_t>(goal, 2 * static_cast<std::uint64_t>(out.size()))));
    return true;
  };
  if (compression == "zstd") {
    if (!contexts_->zstd) contexts_->zstd.reset(ZSTD_createDCtx());
    ZSTD_DCtx* z = contexts_->zstd.get();
    if (!z) throw fail("no zstd context");
    ZSTD_DCtx_reset(z, ZSTD_reset_session_only);  // a chunk is a frame of its own; a damaged one left state behind
    while (true) {
      const bool more_room = room();
      ZSTD_inBuffer in{data, size, in_pos};
      ZSTD_outBuffer o{out.data(), more_room ? out.size() : out_pos, out_pos};
      const std::size_t hint = ZSTD_decompressStream(z, &o, &in);
      if (ZSTD_isError(hint)) throw fail(std::string("does not decompress: ") + ZSTD_getErrorName(hint));
      const bool progressed = in.pos != in_pos || o.pos != out_pos;
      in_pos = in.pos, out_pos = o.pos;
      if (hint == 0 && in_pos == size) break;  // the frame is complete
      if (partial && out_pos >= goal) break;    // as much as the reader needs
      if (!more_room && out_pos == out.size() && hint != 0)
        throw fail("decompresses to more than the " + std::to_string(uncompressed_size) + " bytes it declares");
      if (!progressed) throw fail("the zstd data ends early (" + std::to_string(in_pos) + " of " + std::to_string(size) + " bytes read)");
    }
  } else {
    if (!contexts_->lz4 || contexts_->lz4_mid_frame) {
      LZ4F_dctx* raw = nullptr;
      if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION))) throw fail("no LZ4 context");
      contexts_->lz4.reset(raw);
    }
    LZ4F_dctx* ctx = contexts_->lz4.get();
    contexts_->lz4_mid_frame = true;
    while (true) {
      const bool more_room = room();
      std::size_t in_n = size - in_pos, out_n = more_room ? out.size() - out_pos : 0;
      const std::size_t hint = LZ4F_decompress(ctx, out.data() + out_pos, &out_n, data + in_pos, &in_n, nullptr);
      if (LZ4F_isError(hint)) throw fail(std::string("does not decompress: ") + LZ4F_getErrorName(hint));
      in_pos += in_n, out_pos += out_n;
      if (hint == 0) {  // the frame is complete
        contexts_->lz4_mid_frame = false;
        break;
      }
      if (partial && out_pos >= goal) break;  // as much as the reader needs
      if (in_n == 0 && out_n == 0) {
        if (!more_room) throw fail("decompresses to more than the " + std::to_string(uncompressed_size) + " bytes it declares");
        throw fail("the LZ4 frame ends early (" + std::to_string(in_pos) + " of " + std::to_string(size) + " bytes read)");
      }
    }
  }
  if (partial && out_pos >= goal) {  // stopped early, on purpose: the rest is not checked
    out.resize(out_pos);
    return;
  }
  if (out_pos != uncompressed_size)
    throw fail("decompresses to " + std::to_string(out_pos) + " bytes, not the " + std::to_string(uncompressed_size) + " it declares");
  out.resize(out_pos);
}

std::vector<std::uint8_t> decompress(const std::string& compression, const std::uint8_t* data, std::size_t size,
                                     std::uint64_t uncompressed_size, const std::string& where) {
  std::vector<std::uint8_t> out;
  Decompressor().decompress(compression, data, size, uncompressed_size, where, out);
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
