// How many times BagInput's passes decompress the chunks of an MCAP bag laid out as `ros2 bag
// record` writes it (every topic in the same chunks, in the order received): the small topics'
// pass (kSmallTopics: odometry, tf) a prefix of each chunk with a small message, the first
// cloud's read (kFirst) the chunk of the first cloud, handed on, and the clouds' pass (kAll)
// every other chunk with a cloud, whole: a chunk that mixes both is decompressed twice, every
// other chunk once. Counted by McapReader::chunkDecompressions() against the bag's own Chunk
// records, decompressed and walked here (not through the reader), with the messages of each pass
// those of a single-threaded read, whatever the depth of the read-ahead.
//
// Keeping the small topics' pass's chunks for the clouds' pass (a cache bounded in bytes) makes
// each chunk decompressed once, but holding them costs more CPU in page faults than the second
// decompression it saves (docs/results/2026-11-27-h29mixed.md); a single pass over both needs
// the odometry streamed to the turns (docs/ros2.md).
#include "test_support.hpp"

#include "sim/ros2/compression.hpp"
#include "sim/ros2/mcap_reader.hpp"
#include "sim/ros2/mcap_records.hpp"
#include "sim/ros2/mcap_writer.hpp"

#include <gtest/gtest.h>

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

// The decompressions BagInput's passes make: a prefix (or the whole) of each chunk with small
// messages, and each chunk with a cloud whole (the first cloud's chunk once, handed on).
std::uint64_t expectedDecompressions(const std::vector<ChunkContent>& chunks) {
  std::uint64_t n = 0;
  for (const ChunkContent& c : chunks) n += (c.small ? 1 : 0) + (c.cloud ? 1 : 0);
  return n;
}

struct Passes {
  std::vector<Seen> small, first, clouds;
  std::string error;
  std::uint64_t decompressions = 0;
};

// BagInput's three passes: odometry and tf, the first cloud, every cloud.
Passes readAsBagInput(const std::string& path, std::size_t prefetch) {
  Passes p;
  ros2::McapReader reader(path);
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

}  // namespace

TEST(McapDecompressions, AMixedBagsChunksAreDecompressedOnceByEachPassThatNeedsThem) {
  const std::string dir = bimloc::test::tempDir("mcap-decompressions");
  for (const std::string compression : {"zstd", "lz4"}) {
    const std::string path = writeMixedMcap(dir, compression);
    const std::vector<ChunkContent> chunks = chunkContents(path);
    const std::uint64_t n = chunks.size();
    ASSERT_GT(n, 60u) << path;
    std::uint64_t mixed = 0;
    for (const ChunkContent& c : chunks) mixed += c.small && c.cloud;
    EXPECT_GE(mixed, n - 2) << path << ": the layout mixes the topics in (nearly) every chunk";
    const Passes truth = readAsBagInput(path, 0);
    ASSERT_EQ(truth.error, "");
    ASSERT_EQ(truth.small.size(), 150u * 20u);
    ASSERT_EQ(truth.clouds.size(), 150u);
    ASSERT_EQ(truth.first.size(), 1u);
    EXPECT_EQ(truth.decompressions, expectedDecompressions(chunks)) << path;
    EXPECT_EQ(truth.decompressions, n + mixed) << path << ": " << n << " chunks, " << mixed << " of them mixed";
    for (const std::size_t prefetch : {1u, 3u, 8u}) {
      const std::string what = path + ", prefetch " + std::to_string(prefetch);
      const Passes p = readAsBagInput(path, prefetch);
      EXPECT_EQ(p.error, "") << what;
      EXPECT_TRUE(p.small == truth.small) << what;
      EXPECT_TRUE(p.first == truth.first) << what;
      EXPECT_TRUE(p.clouds == truth.clouds) << what;
      EXPECT_EQ(p.decompressions, truth.decompressions) << what << ": nothing decompressed twice by reading ahead";
    }
  }
}
