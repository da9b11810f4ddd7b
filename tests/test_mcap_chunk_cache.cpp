// The MCAP reader's chunk cache (sim/ros2/chunk_cache.hpp) on a bag laid out as `ros2 bag
// record` writes it: every topic in the same chunks, in the order received. BagInput reads such
// a bag in three passes (the small topics', kSmallTopics; the first cloud, kFirst; the clouds',
// kAll), and each chunk must be decompressed once in all, not once by each pass. The truths:
// the bag's chunk count and sizes from its Chunk records (walked here, not through the reader's
// summary), and the same passes read with no cache (every message, byte for byte).
#include "test_support.hpp"

#include "sim/ros2/compression.hpp"
#include "sim/ros2/mcap_reader.hpp"
#include "sim/ros2/mcap_records.hpp"
#include "sim/ros2/mcap_writer.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <random>
#include <stdexcept>

namespace ros2 = bimloc::sim::ros2;

namespace {

struct Seen {
  std::uint16_t channel;
  std::uint64_t log_time;
  std::string bytes;
  bool operator==(const Seen& o) const { return channel == o.channel && log_time == o.log_time && bytes == o.bytes; }
};

// Channel 0: "clouds" of 3-5 KiB; 1 and 2: "odometry" and "tf" of 60-200 bytes, ten of each per
// cloud, interleaved by time as a recorder receives them; chunks of 8 KiB, so that a chunk holds
// about two clouds and small messages before, between and after them (rosbag2's 768 KiB chunks
// and VLP-16 clouds of 0.6 MB, scaled down).
std::string writeMixedMcap(const std::string& dir, const std::string& compression) {
  const std::string path = dir + "/mixed_" + (compression.empty() ? "none" : compression) + ".mcap";
  ros2::McapWriterOptions options;
  options.compression = compression;
  options.chunk_bytes = 8192;
  ros2::McapWriter w(path, options);
  const std::uint16_t schema = w.addSchema("test_msgs/msg/Blob", "ros2msg", "uint8[] data");
  std::vector<std::uint16_t> ids;
  for (const char* topic : {"/cloud", "/odom", "/tf"}) ids.push_back(w.addChannel(schema, topic, "cdr"));
  std::mt19937 rng(2911);
  std::uint64_t t = 1'000'000;
  for (int cloud = 0; cloud < 150; ++cloud) {
    std::vector<std::uint8_t> points(3072 + rng() % 2048);
    for (auto& b : points) b = static_cast<std::uint8_t>(rng() % 64);  // compressible, not trivially
    w.write(ids[0], t += 1000, points);
    for (int k = 0; k < 10; ++k)
      for (const std::uint16_t small : {ids[1], ids[2]}) {
        std::vector<std::uint8_t> data(60 + rng() % 140);
        for (auto& b : data) b = static_cast<std::uint8_t>(rng() % 16);
        w.write(small, t += 100, data);
      }
  }
  w.close();
  return path;
}

// The file's Chunk records in file order (which is the reads' order: the chunks do not overlap
// in time): each decompressed here and its records walked, for the channels it holds.
struct ChunkContent {
  std::uint64_t uncompressed_size = 0;
  bool cloud = false, small = false;
};
std::vector<ChunkContent> chunkContents(const std::string& path) {
  const std::string bytes = bimloc::test::readFile(path);
  std::vector<ChunkContent> chunks;
  const auto* d = reinterpret_cast<const std::uint8_t*>(bytes.data());
  ros2::mcap::walkRecords(d + 8, bytes.size() - 8, 8, path, [&](std::uint8_t op, ros2::ByteCursor& c, std::uint64_t) {
    if (op != ros2::mcap::kChunk) return op != ros2::mcap::kDataEnd && op != ros2::mcap::kFooter;
    const ros2::mcap::ChunkHeader h = ros2::mcap::parseChunk(c);
    const std::vector<std::uint8_t> records =
        ros2::decompress(h.compression, h.records, static_cast<std::size_t>(h.records_size), h.uncompressed_size, path);
    ChunkContent chunk{h.uncompressed_size};
    ros2::mcap::walkRecords(records.data(), records.size(), 0, path, [&](std::uint8_t iop, ros2::ByteCursor& m, std::uint64_t) {
      if (iop == ros2::mcap::kMessage) (m.u16("channel") == 0 ? chunk.cloud : chunk.small) = true;
      return true;
    });
    chunks.push_back(chunk);
    return true;
  });
  return chunks;
}

// The decompressions BagInput's passes make: a prefix of each chunk with small messages, each
// chunk with a cloud whole (the first cloud's chunk handed on to the clouds' pass), less the
// chunks kept: the first chunks with both, while their sizes add up to no more than `budget`.
std::uint64_t expectedDecompressions(const std::vector<ChunkContent>& chunks, std::uint64_t budget) {
  std::uint64_t n = 0, held = 0;
  bool full = false;
  for (const ChunkContent& c : chunks) {
    n += (c.small ? 1 : 0) + (c.cloud ? 1 : 0);
    if (!c.small || !c.cloud || full) continue;
    if (held + c.uncompressed_size > budget) {
      full = true;
      continue;
    }
    held += c.uncompressed_size;
    --n;
  }
  return n;
}

struct Passes {
  std::vector<Seen> small, first, clouds;
  std::string error;
  std::uint64_t decompressions = 0;
};

// BagInput's three passes: odometry and tf, the first cloud, every cloud.
Passes readAsBagInput(const std::string& path, std::uint64_t cache_bytes, std::size_t prefetch) {
  Passes p;
  ros2::McapReader reader(path);
  reader.setChunkCache(cache_bytes);
  reader.setPrefetch(prefetch, 2);
  auto see = [](std::vector<Seen>& into) {
    return [&into](const ros2::McapMessage& m) {
      into.push_back({m.channel->id, m.log_time_ns, std::string(reinterpret_cast<const char*>(m.data), m.size)});
    };
  };
  struct Stop {};
  try {
    reader.forEachMessage({1, 2}, see(p.small), ros2::ReadPlan::kSmallTopics);
    try {
      reader.forEachMessage({0}, [&](const ros2::McapMessage& m) {
        see(p.first)(m);
        throw Stop{};
      }, ros2::ReadPlan::kFirst);
    } catch (const Stop&) {
    }
    reader.forEachMessage({0}, see(p.clouds), ros2::ReadPlan::kAll);
  } catch (const std::runtime_error& e) {
    p.error = e.what();
  }
  p.decompressions = reader.chunkDecompressions();
  return p;
}

void expectSameMessages(const Passes& got, const Passes& truth, const std::string& what) {
  EXPECT_EQ(got.error, truth.error) << what;
  EXPECT_TRUE(got.small == truth.small) << what << ": " << got.small.size() << " small messages, " << truth.small.size() << " without cache";
  EXPECT_TRUE(got.first == truth.first) << what;
  EXPECT_TRUE(got.clouds == truth.clouds) << what << ": " << got.clouds.size() << " clouds, " << truth.clouds.size() << " without cache";
}

}  // namespace

// Each chunk decompressed once when the budget holds the bag; without a cache twice (a prefix
// by the small topics' pass, whole by the clouds' or the first cloud's); with a budget of the
// first K chunks' sizes, N + (N - K) (K: the mixed ones). The messages are the same whatever the budget and depth.
TEST(McapChunkCache, AMixedBagsChunksAreDecompressedOnceAcrossTheThreePasses) {
  const std::string dir = bimloc::test::tempDir("mcap-chunk-cache");
  for (const std::string compression : {"zstd", "lz4"}) {
    const std::string path = writeMixedMcap(dir, compression);
    const std::vector<ChunkContent> chunks = chunkContents(path);
    const std::uint64_t n = chunks.size();
    ASSERT_GT(n, 60u) << path;
    std::uint64_t total = 0, mixed = 0;
    for (const ChunkContent& c : chunks) total += c.uncompressed_size, mixed += c.small && c.cloud;
    EXPECT_GE(mixed, n - 2) << path << ": the layout mixes the topics in (nearly) every chunk";
    const Passes truth = readAsBagInput(path, 0, 0);
    ASSERT_EQ(truth.error, "");
    ASSERT_EQ(truth.small.size(), 150u * 20u);
    ASSERT_EQ(truth.clouds.size(), 150u);
    ASSERT_EQ(truth.first.size(), 1u);
    EXPECT_EQ(truth.decompressions, n + mixed) << path << ": no cache, a chunk with both by two passes";
    EXPECT_EQ(truth.decompressions, expectedDecompressions(chunks, 0)) << path;
    for (const std::size_t prefetch : {0u, 3u}) {
      const std::string what = path + ", prefetch " + std::to_string(prefetch);
      const Passes all = readAsBagInput(path, total, prefetch);
      expectSameMessages(all, truth, what);
      EXPECT_EQ(all.decompressions, n) << what << ": a budget of the whole bag, each of its " << n << " chunks once";
      for (const std::uint64_t k : {std::uint64_t{1}, n / 3, n - 1}) {
        std::uint64_t budget = 0;
        for (std::uint64_t i = 0; i < k; ++i) budget += chunks[i].uncompressed_size;
        budget += chunks[k].uncompressed_size - 1;  // one byte short of chunk k
        const Passes some = readAsBagInput(path, budget, prefetch);
        expectSameMessages(some, truth, what + ", budget " + std::to_string(budget));
        EXPECT_EQ(some.decompressions, expectedDecompressions(chunks, budget)) << what << ", budget " << budget;
      }
    }
  }
}

// A damaged chunk within the budget: each pass reads what it would have without the cache (the
// small topics' pass a prefix whose CRC it does not check, or the whole chunk), and the same
// error comes after the same messages.
TEST(McapChunkCache, ADamagedChunkGivesTheErrorsOfAReadWithoutCache) {
  const std::string dir = bimloc::test::tempDir("mcap-chunk-cache-damaged");
  const std::string path = writeMixedMcap(dir, "zstd");
  std::string bytes = bimloc::test::readFile(path);
  std::vector<std::uint64_t> chunks;
  const auto* d = reinterpret_cast<const std::uint8_t*>(bytes.data());
  ros2::mcap::walkRecords(d + 8, bytes.size() - 8, 8, path, [&](std::uint8_t op, ros2::ByteCursor&, std::uint64_t at) {
    if (op == ros2::mcap::kChunk) chunks.push_back(at);
    return op != ros2::mcap::kDataEnd && op != ros2::mcap::kFooter;
  });
  ASSERT_GT(chunks.size(), 10u);
  // (A chunk whose last message is a small one is read whole by the small topics' pass, which
  // then finds the damage itself; one that ends with a cloud, in part: the clouds' pass does.)
  for (const std::size_t which : {chunks.size() / 4, chunks.size() / 2, 3 * chunks.size() / 4}) {
    std::string damaged_bytes = bytes;
    const std::uint64_t bad = chunks[which];
    damaged_bytes[bad + 9 + 24] = static_cast<char>(damaged_bytes[bad + 9 + 24] ^ 1);  // uncompressed_crc
    const std::string damaged = dir + "/damaged_crc_" + std::to_string(which) + ".mcap";
    std::ofstream(damaged, std::ios::binary) << damaged_bytes;
    const Passes truth = readAsBagInput(damaged, 0, 0);
    ASSERT_NE(truth.error, "");
    EXPECT_NE(truth.error.find("CRC"), std::string::npos) << truth.error;
    for (const std::size_t prefetch : {0u, 3u}) expectSameMessages(readAsBagInput(damaged, 1u << 30, prefetch), truth, damaged);
  }
}

TEST(McapChunkCache, TheEnvironmentChoosesTheBudget) {
  const char* before = std::getenv("BIMLOC_MCAP_CACHE_MB");
  const std::string saved = before ? before : "";
  ::setenv("BIMLOC_MCAP_CACHE_MB", "0", 1);
  EXPECT_EQ(ros2::defaultChunkCacheBytes(), 0u);
  ::setenv("BIMLOC_MCAP_CACHE_MB", "64", 1);
  EXPECT_EQ(ros2::defaultChunkCacheBytes(), 64u << 20);
  ::setenv("BIMLOC_MCAP_CACHE_MB", "lots", 1);
  try {
    ros2::defaultChunkCacheBytes();
    ADD_FAILURE() << "BIMLOC_MCAP_CACHE_MB=lots accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("BIMLOC_MCAP_CACHE_MB"), std::string::npos) << e.what();
  }
  ::unsetenv("BIMLOC_MCAP_CACHE_MB");
  EXPECT_EQ(ros2::defaultChunkCacheBytes(), 256u << 20);
  if (before) ::setenv("BIMLOC_MCAP_CACHE_MB", saved.c_str(), 1);
}
