// The buffers MCAP chunks are decompressed into, reused from chunk to chunk and from pass to
// pass (compression.hpp's Decompressor, chunk_prefetcher.hpp's BufferPool). The truth: the
// bytes that were compressed. One buffer taken through chunks that grow and shrink (the growth
// no longer copies the earlier chunk over) must give each chunk's bytes exactly, whole or as a
// prefix, whatever the compression; a damaged chunk after them must still be refused; the pool
// must hand back the capacity it was given and hold no more buffers than it may.
#include "sim/ros2/chunk_prefetcher.hpp"
#include "sim/ros2/compression.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

namespace ros2 = bimloc::sim::ros2;

namespace {

// Bytes as a lidar cloud's: a few compressible fields (zeros, slowly varying rings), noisy floats.
std::vector<std::uint8_t> chunkBytes(std::size_t n, std::mt19937& rng) {
  std::vector<std::uint8_t> b(n);
  std::uniform_int_distribution<int> byte(0, 255);
  for (std::size_t i = 0; i < n; ++i) b[i] = (i % 22) < 12 ? static_cast<std::uint8_t>(byte(rng)) : (i % 22) < 16 ? 0 : static_cast<std::uint8_t>(i / 2200);
  return b;
}

}  // namespace

TEST(McapBuffers, OneBufferThroughGrowingAndShrinkingChunksGivesEachChunksBytes) {
  std::mt19937 rng(29);
  // Sizes as a writer cuts them (about one size, a message more or less), then a much larger
  // chunk (a dense cloud alone), then small ones again.
  const std::vector<std::size_t> sizes = {300000, 310000, 295000, 340000, 1200000, 250000, 20000, 1250000, 0, 64};
  for (const std::string compression : {"zstd", "lz4", ""}) {
    ros2::Decompressor z;
    std::vector<std::uint8_t> buffer;
    for (std::size_t k = 0; k < sizes.size(); ++k) {
      // The empty chunk follows a prefix read: with liblz4's context reused after a frame left
      // mid-way, this empty LZ4 frame was refused ("ERROR_frameSize_wrong").
      const std::vector<std::uint8_t> raw = chunkBytes(sizes[k], rng);
      const std::vector<std::uint8_t> packed = ros2::compress(compression, raw);
      const std::string what = "'" + compression + "' chunk " + std::to_string(k) + " of " + std::to_string(raw.size()) + " bytes";
      z.decompress(compression, packed.data(), packed.size(), raw.size(), "test", buffer);
      EXPECT_EQ(buffer, raw) << what;
      if (compression.empty() || raw.size() < 1000) continue;
      // A prefix into the same buffer: at least that many bytes, those of the chunk.
      const std::size_t prefix = raw.size() / 3;
      z.decompress(compression, packed.data(), packed.size(), raw.size(), "test", buffer, prefix);
      ASSERT_GE(buffer.size(), prefix) << what;
      EXPECT_TRUE(std::equal(buffer.begin(), buffer.end(), raw.begin())) << what;
    }
    // Still refused after all that reuse: a size the data does not decompress to.
    const std::vector<std::uint8_t> raw = chunkBytes(100000, rng);
    const std::vector<std::uint8_t> packed = ros2::compress(compression, raw);
    EXPECT_THROW(z.decompress(compression, packed.data(), packed.size(), raw.size() + 1, "test", buffer), std::runtime_error)
        << "'" << compression << "'";
  }
}

TEST(McapBuffers, AGrownBufferHasRoomForTheNextChunksOfAboutItsSize) {
  std::mt19937 rng(30);
  const std::vector<std::uint8_t> raw = chunkBytes(400000, rng);
  const std::vector<std::uint8_t> packed = ros2::compress("zstd", raw);
  ros2::Decompressor z;
  std::vector<std::uint8_t> buffer(1000, 7);  // an earlier, smaller chunk's
  z.decompress("zstd", packed.data(), packed.size(), raw.size(), "test", buffer);
  EXPECT_EQ(buffer, raw);
  EXPECT_GE(buffer.capacity(), raw.size() + raw.size() / 4);  // a chunk a quarter larger fits
  const std::uint8_t* where = buffer.data();
  const std::vector<std::uint8_t> next = chunkBytes(480000, rng);
  const std::vector<std::uint8_t> next_packed = ros2::compress("zstd", next);
  z.decompress("zstd", next_packed.data(), next_packed.size(), next.size(), "test", buffer);
  EXPECT_EQ(buffer, next);
  EXPECT_EQ(buffer.data(), where);  // no new allocation
}

TEST(McapBuffers, ThePoolHandsBackWhatItWasGivenUpToItsBound) {
  ros2::BufferPool pool(2);
  EXPECT_EQ(pool.take().capacity(), 0u);  // none yet: an empty buffer
  std::vector<const std::uint8_t*> given;
  for (const std::size_t n : {1000u, 2000u, 3000u}) {
    std::vector<std::uint8_t> b(n);
    given.push_back(b.data());
    pool.give(std::move(b));
  }
  pool.give({});  // no capacity: not kept
  const std::vector<std::uint8_t> a = pool.take(), b = pool.take();
  EXPECT_EQ(pool.take().capacity(), 0u);  // the third was beyond the bound
  EXPECT_EQ(a.data(), given[1]);
  EXPECT_EQ(b.data(), given[0]);
  pool.give(std::vector<std::uint8_t>(10)), pool.give(std::vector<std::uint8_t>(10));
  pool.setMost(1);
  EXPECT_EQ(pool.take().capacity(), 10u);
  EXPECT_EQ(pool.take().capacity(), 0u);
}
