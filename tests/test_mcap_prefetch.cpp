// The MCAP reader with its chunks decompressed ahead on a worker thread (chunk_prefetcher.hpp)
// against the same reader on one thread, the truth here: the same messages (channel, sequence,
// log time, bytes) in the same order, on bags of many small chunks that overlap in time, read
// through the summary and by a linear scan, and on damaged bags the same error after the same
// messages, whatever the prefetch depth and the threads' timing (random pauses in the reader's
// visit and in the worker's loads, seeded). A worker that fails, or a reader that stops early,
// never hangs.
#include "test_support.hpp"

#include "sim/ros2/chunk_prefetcher.hpp"
#include "sim/ros2/mcap_reader.hpp"
#include "sim/ros2/mcap_records.hpp"
#include "sim/ros2/mcap_writer.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <stdexcept>
#include <thread>

namespace ros2 = bimloc::sim::ros2;

namespace {

struct SeenMessage {
  std::uint16_t channel;
  std::uint32_t sequence;
  std::uint64_t log_time;
  std::string bytes;
  bool operator==(const SeenMessage& o) const {
    return channel == o.channel && sequence == o.sequence && log_time == o.log_time && bytes == o.bytes;
  }
};

struct McapRead {
  std::vector<SeenMessage> messages;
  std::string error;  // "" when the read went to the end
  std::vector<std::string> warnings;
};

// Every message of `channels` (all when empty), `prefetch` chunks ahead; the visit pauses up to
// `pause_us` microseconds at random messages (seeded), so the worker runs ahead or falls behind.
McapRead readWholeMcap(const std::string& path, std::size_t prefetch, int pause_us, unsigned seed,
                       const std::set<std::uint16_t>& channels = {}, std::size_t workers = 1, bool whole_chunks = true) {
  McapRead r;
  std::mt19937 rng(seed);
  try {
    ros2::McapReader reader(path);
    r.warnings = reader.warnings();
    reader.setPrefetch(prefetch, workers);
    reader.forEachMessage(channels, [&](const ros2::McapMessage& m) {
      r.messages.push_back({m.channel->id, m.sequence, m.log_time_ns, std::string(reinterpret_cast<const char*>(m.data), m.size)});
      if (pause_us > 0 && rng() % 8 == 0) std::this_thread::sleep_for(std::chrono::microseconds(rng() % pause_us));
    }, whole_chunks ? ros2::ReadPlan::kAll : ros2::ReadPlan::kSmallTopics);
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  return r;
}

// Many small chunks (about 2 KiB of records each) of three channels, messages of 1 to 600
// random bytes whose log times jitter, so that neighbouring chunks overlap in time and the
// reader's merge by log time has work to do.
std::string writeSmallChunkMcap(const std::string& dir, const std::string& compression, bool summary) {
  const std::string path = dir + "/small_" + (compression.empty() ? "none" : compression) + (summary ? "" : "_nosummary") + ".mcap";
  ros2::McapWriterOptions options;
  options.compression = compression;
  options.chunk_bytes = 2048;
  options.summary = summary;
  ros2::McapWriter w(path, options);
  const std::uint16_t schema = w.addSchema("test_msgs/msg/Blob", "ros2msg", "uint8[] data");
  std::vector<std::uint16_t> channels;
  for (const char* topic : {"/a", "/b", "/c"}) channels.push_back(w.addChannel(schema, topic, "cdr"));
  std::mt19937 rng(29);
  for (int i = 0; i < 1500; ++i) {
    const std::uint16_t channel = channels[rng() % channels.size()];
    std::vector<std::uint8_t> data(1 + rng() % 600);
    for (auto& b : data) b = static_cast<std::uint8_t>(rng());
    const std::uint64_t t = 1'000'000 + 1000ull * static_cast<std::uint64_t>(i) + rng() % 9000;  // jitter beyond a chunk
    w.write(channel, t, data);
  }
  w.close();
  return path;
}

void writeMcapBytes(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

// The file offsets of the top-level Chunk records.
std::vector<std::uint64_t> mcapChunkOffsets(const std::string& bytes) {
  std::vector<std::uint64_t> at;
  const auto* d = reinterpret_cast<const std::uint8_t*>(bytes.data());
  ros2::mcap::walkRecords(d + 8, bytes.size() - 8, 8, "test", [&](std::uint8_t op, ros2::ByteCursor&, std::uint64_t offset) {
    if (op == ros2::mcap::kChunk) at.push_back(offset);
    return op != ros2::mcap::kDataEnd && op != ros2::mcap::kFooter;
  });
  return at;
}

// The single-threaded read against the prefetching one at several depths and timings.
void expectPrefetchedAsOneThread(const std::string& path, const std::set<std::uint16_t>& channels = {}, bool whole_chunks = true) {
  const McapRead truth = readWholeMcap(path, 0, 0, 1, channels, 1, whole_chunks);
  int trial = 0;
  for (const std::size_t prefetch : {1u, 2u, 3u, 8u})
    for (const int pause_us : {0, 300}) {
      const std::size_t workers = prefetch == 8 ? 3 : prefetch == 3 ? 2 : 1;
      const McapRead r = readWholeMcap(path, prefetch, pause_us, static_cast<unsigned>(++trial), channels, workers, whole_chunks);
      EXPECT_EQ(r.error, truth.error) << path << ", prefetch " << prefetch << ", pauses " << pause_us;
      EXPECT_EQ(r.warnings, truth.warnings) << path;
      ASSERT_EQ(r.messages.size(), truth.messages.size()) << path << ", prefetch " << prefetch << ", pauses " << pause_us;
      EXPECT_TRUE(r.messages == truth.messages) << path << ", prefetch " << prefetch << ", pauses " << pause_us;
    }
}

}  // namespace

TEST(McapPrefetch, GivesTheOneThreadReadsMessagesOnManySmallChunks) {
  const std::string dir = bimloc::test::tempDir("mcap-prefetch");
  for (const std::string compression : {"zstd", "lz4", ""})
    for (const bool summary : {true, false}) {
      const std::string path = writeSmallChunkMcap(dir, compression, summary);
      ASSERT_GT(mcapChunkOffsets(bimloc::test::readFile(path)).size(), 100u) << path;
      const McapRead truth = readWholeMcap(path, 0, 0, 1);
      ASSERT_EQ(truth.error, "");
      ASSERT_EQ(truth.messages.size(), 1500u) << path;  // the single-threaded reader reads them all
      expectPrefetchedAsOneThread(path);
      expectPrefetchedAsOneThread(path, {1});  // one channel: chunks skipped by their message indexes
    }
}

TEST(McapPrefetch, DamagedBagsGiveTheSameErrorAfterTheSameMessages) {
  const std::string dir = bimloc::test::tempDir("mcap-prefetch-damaged");
  for (const std::string compression : {"zstd", "lz4", ""}) {
    const std::string path = writeSmallChunkMcap(dir, compression, true);
    const std::string bytes = bimloc::test::readFile(path);
    const std::vector<std::uint64_t> chunks = mcapChunkOffsets(bytes);
    ASSERT_GT(chunks.size(), 100u);
    const std::uint64_t middle = chunks[chunks.size() / 2], later = chunks[chunks.size() * 3 / 4];
    struct Case {
      std::string name, bytes;
    };
    std::vector<Case> cases;
    {  // bytes of a chunk's records garbled: it does not decompress, or fails its CRC
      std::string b = bytes;
      for (std::uint64_t i = middle + 120; i < middle + 160 && i < b.size(); ++i) b[i] = static_cast<char>(b[i] ^ 0x5a);
      cases.push_back({"garbled records", b});
    }
    {  // a chunk's records length far past the file
      std::string b = bytes;
      const std::uint64_t huge = 1ull << 40;
      // Chunk: opcode, length, start, end, uncompressed_size, crc, compression (u32 + bytes), records length
      std::memcpy(&b[later + 9 + 8 + 8 + 8 + 4 + 4 + compression.size()], &huge, 8);
      cases.push_back({"bad records length", b});
    }
    {  // a chunk's CRC wrong
      std::string b = bytes;
      b[middle + 9 + 24] = static_cast<char>(b[middle + 9 + 24] ^ 1);
      cases.push_back({"bad CRC", b});
    }
    // Cut short (a recording that did not finish: no summary, read by a linear scan), also
    // inside a chunk, and cut with a chunk garbled before the cut.
    cases.push_back({"cut", bytes.substr(0, later + 1000)});
    cases.push_back({"cut garbled", cases[0].bytes.substr(0, later + 1000)});
    for (const Case& c : cases) {
      const std::string damaged = dir + "/damaged.mcap";
      writeMcapBytes(damaged, c.bytes);
      const McapRead truth = readWholeMcap(damaged, 0, 0, 1);
      SCOPED_TRACE(compression + ": " + c.name + ": " + truth.error);
      if (c.name == "cut") {
        EXPECT_FALSE(truth.warnings.empty());  // said so
      } else {
        EXPECT_NE(truth.error, "");  // refused by name
        EXPECT_NE(truth.error.find(damaged), std::string::npos);
      }
      // The messages before the damage were read (but for a linear scan, whose counting pass in
      // the constructor already meets the garbled chunk).
      if (c.name != "cut garbled") {
        EXPECT_GT(truth.messages.size(), 0u);
      }
      expectPrefetchedAsOneThread(damaged);
    }
  }
}

// A pass over some channels only (the small topics' pass) decompresses each chunk only as far
// as its last message of them: the messages are those of a whole read of every channel, kept
// by channel; on a damaged bag, prefetched or not, the same outcome.
TEST(McapPrefetch, APassOverSomeChannelsReadsChunkPrefixesAndTheSameMessages) {
  const std::string dir = bimloc::test::tempDir("mcap-prefix");
  for (const std::string compression : {"zstd", "lz4", ""}) {
    const std::string path = writeSmallChunkMcap(dir, compression, true);
    const McapRead all = readWholeMcap(path, 0, 0, 1);
    ASSERT_EQ(all.error, "");
    for (const std::set<std::uint16_t>& channels : {std::set<std::uint16_t>{1}, std::set<std::uint16_t>{0, 2}}) {
      std::vector<SeenMessage> expected;
      for (const SeenMessage& m : all.messages)
        if (channels.count(m.channel)) expected.push_back(m);
      for (const std::size_t prefetch : {0u, 3u}) {
        const McapRead side = readWholeMcap(path, prefetch, 0, 1, channels, 2, /*whole_chunks=*/false);
        EXPECT_EQ(side.error, "") << compression;
        ASSERT_EQ(side.messages.size(), expected.size()) << compression << ", prefetch " << prefetch;
        EXPECT_TRUE(side.messages == expected) << compression << ", prefetch " << prefetch;
      }
      expectPrefetchedAsOneThread(path, channels, false);
    }
    // Damaged: garbled records in one chunk, a bad CRC in another.
    std::string bytes = bimloc::test::readFile(path);
    const std::vector<std::uint64_t> chunks = mcapChunkOffsets(bytes);
    for (std::uint64_t i = chunks[chunks.size() / 3] + 100; i < chunks[chunks.size() / 3] + 140; ++i) bytes[i] = static_cast<char>(bytes[i] ^ 0x33);
    bytes[chunks[chunks.size() / 2] + 9 + 24] = static_cast<char>(bytes[chunks[chunks.size() / 2] + 9 + 24] ^ 1);
    const std::string damaged = dir + "/damaged_prefix.mcap";
    writeMcapBytes(damaged, bytes);
    expectPrefetchedAsOneThread(damaged, {1}, false);
    expectPrefetchedAsOneThread(damaged, {0, 2}, false);
  }
}

// The first cloud's read (ReadPlan::kFirst) stops after a message or a few: no chunk is read
// ahead for it, and the chunk it stopped in serves the whole read that follows, which then
// decompresses every chunk once. The messages are those of a read from scratch whatever the
// plans, and a damaged first chunk gives the same error as a whole read's.
TEST(McapPrefetch, TheFirstMessagesReadHandsItsChunkToTheNextRead) {
  const std::string dir = bimloc::test::tempDir("mcap-first");
  struct Stop {};
  for (const std::string compression : {"zstd", "lz4", ""})
    for (const bool summary : {true, false})
      for (const bool jitter : {false, true}) {
        std::string path = writeSmallChunkMcap(dir, compression, summary);
        if (!jitter) {  // in order: no two chunks overlap in time, so the first read stops in one
          path = dir + "/ordered_" + (compression.empty() ? "none" : compression) + (summary ? "" : "_nosummary") + ".mcap";
          ros2::McapWriterOptions options;
          options.compression = compression, options.chunk_bytes = 2048, options.summary = summary;
          ros2::McapWriter w(path, options);
          const std::uint16_t schema = w.addSchema("test_msgs/msg/Blob", "ros2msg", "uint8[] data");
          std::vector<std::uint16_t> ids;
          for (const char* topic : {"/a", "/b", "/c"}) ids.push_back(w.addChannel(schema, topic, "cdr"));
          std::mt19937 rng(31);
          for (int i = 0; i < 600; ++i) w.write(ids[rng() % 3], 1000ull * static_cast<std::uint64_t>(i + 1), std::vector<std::uint8_t>(1 + rng() % 600, 7));
          w.close();
        }
        for (const std::set<std::uint16_t>& channels : {std::set<std::uint16_t>{}, std::set<std::uint16_t>{1}}) {
          const McapRead truth = readWholeMcap(path, 0, 0, 1, channels);
          ASSERT_EQ(truth.error, "");
          std::uint64_t whole_loads = 0;
          {
            ros2::McapReader fresh(path);
            fresh.forEachMessage(channels, [](const ros2::McapMessage&) {});
            whole_loads = fresh.chunkLoads();
          }
          for (const std::size_t stop_after : {1u, 2u, 5u, 40u})
            for (const std::size_t prefetch : {0u, 3u}) {
              const std::string what = path + ", stop after " + std::to_string(stop_after) + ", prefetch " + std::to_string(prefetch);
              ros2::McapReader reader(path);
              reader.setPrefetch(prefetch, 2);
              std::vector<SeenMessage> first;
              auto see = [](std::vector<SeenMessage>& into, const ros2::McapMessage& m) {
                into.push_back({m.channel->id, m.sequence, m.log_time_ns, std::string(reinterpret_cast<const char*>(m.data), m.size)});
              };
              EXPECT_THROW(reader.forEachMessage(channels, [&](const ros2::McapMessage& m) {
                see(first, m);
                if (first.size() == stop_after) throw Stop{};
              }, ros2::ReadPlan::kFirst), Stop);
              ASSERT_EQ(first.size(), stop_after) << what;
              EXPECT_TRUE(std::equal(first.begin(), first.end(), truth.messages.begin())) << what;
              if (!jitter && summary && stop_after == 1) {
                EXPECT_EQ(reader.chunkLoads(), 1u) << what;  // nothing read ahead
              }
              const std::uint64_t first_loads = reader.chunkLoads();
              std::vector<SeenMessage> all;
              reader.forEachMessage(channels, [&](const ros2::McapMessage& m) { see(all, m); });
              EXPECT_TRUE(all == truth.messages) << what;
              // In order (no two chunks held at once): the chunk it stopped in is not loaded again.
              if (!jitter) {
                EXPECT_EQ(reader.chunkLoads(), first_loads - 1 + whole_loads) << what;
              }
              // The chunk serves one read only; another plan or other channels load their own.
              std::vector<SeenMessage> again;
              reader.forEachMessage(channels, [&](const ros2::McapMessage& m) { see(again, m); });
              EXPECT_TRUE(again == truth.messages) << what;
              EXPECT_THROW(reader.forEachMessage(channels, [&](const ros2::McapMessage&) { throw Stop{}; }, ros2::ReadPlan::kFirst), Stop);
              std::vector<SeenMessage> others;
              reader.forEachMessage({2}, [&](const ros2::McapMessage& m) { see(others, m); });
              std::vector<SeenMessage> expected_others;
              for (const SeenMessage& m : readWholeMcap(path, 0, 0, 1).messages)
                if (m.channel == 2) expected_others.push_back(m);
              EXPECT_TRUE(others == expected_others) << what;
            }
        }
      }
  // A bad CRC in the first chunk: the first message's read says so, as the whole read does.
  const std::string path = writeSmallChunkMcap(dir, "zstd", true);
  std::string bytes = bimloc::test::readFile(path);
  const std::vector<std::uint64_t> chunks = mcapChunkOffsets(bytes);
  bytes[chunks[0] + 9 + 24] = static_cast<char>(bytes[chunks[0] + 9 + 24] ^ 1);  // uncompressed_crc
  const std::string damaged = dir + "/damaged_first.mcap";
  writeMcapBytes(damaged, bytes);
  const McapRead whole = readWholeMcap(damaged, 0, 0, 1);
  ASSERT_NE(whole.error, "");
  ros2::McapReader reader(damaged);
  try {
    reader.forEachMessage({}, [&](const ros2::McapMessage&) { throw Stop{}; }, ros2::ReadPlan::kFirst);
    ADD_FAILURE() << "the first message's read of " << damaged << " did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), whole.error);
  }
}

TEST(McapPrefetch, PrefetcherKeepsOrderPassesErrorsAndNeverHangs) {
  // Loads that take random times on the worker, a reader that takes random times too.
  for (const std::size_t workers : {1u, 3u}) {
    for (const std::size_t ahead : {1u, 2u, 5u})
      for (int fail_at : {-1, 0, 7, 19}) {
        std::mt19937 reader_rng(7);
        ros2::ChunkPrefetcher p(20, ahead, [&](std::size_t i, ros2::Decompressor&, ros2::LoadedChunk& chunk) {
          // a pause of its own per chunk (the workers share no generator)
          std::this_thread::sleep_for(std::chrono::microseconds((i * 7919 + ahead * 31 + workers) % 400));
          if (static_cast<int>(i) == fail_at) throw std::runtime_error("chunk " + std::to_string(i) + " is damaged");
          chunk.buffer.assign(1, static_cast<std::uint8_t>(i));
        }, workers);
        EXPECT_TRUE(p.threaded());
        std::size_t got = 0;
        std::string error;
        try {
          for (std::size_t i = 0; i < 20; ++i) {
            ros2::LoadedChunk c = p.next();
            ASSERT_EQ(c.buffer.size(), 1u);
            EXPECT_EQ(c.buffer[0], i);
            ++got;
            std::this_thread::sleep_for(std::chrono::microseconds(reader_rng() % 400));
          }
        } catch (const std::runtime_error& e) {
          error = e.what();
        }
        if (fail_at < 0) {
          EXPECT_EQ(got, 20u);
          EXPECT_EQ(error, "");
        } else {
          EXPECT_EQ(got, static_cast<std::size_t>(fail_at)) << "ahead " << ahead;
          EXPECT_EQ(error, "chunk " + std::to_string(fail_at) + " is damaged");
        }
      }
  }
  // A reader that stops after two chunks (its visit threw, say): the destructor stops the worker
  // (blocked on a full queue) and joins it.
  const auto t0 = std::chrono::steady_clock::now();
  {
    ros2::ChunkPrefetcher p(1000, 2, [](std::size_t, ros2::Decompressor&, ros2::LoadedChunk& chunk) { chunk.buffer.resize(64); });
    p.next(), p.next();
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
  // No worker (ahead 0): loaded by next() on this thread, errors as they come.
  ros2::ChunkPrefetcher p(3, 0, [](std::size_t i, ros2::Decompressor&, ros2::LoadedChunk&) {
    if (i == 1) throw std::runtime_error("one");
  });
  EXPECT_FALSE(p.threaded());
  p.next();
  EXPECT_THROW(p.next(), std::runtime_error);
}

TEST(McapPrefetch, TheEnvironmentChoosesTheDepth) {
  const char* before = std::getenv("BIMLOC_MCAP_PREFETCH");
  const std::string saved = before ? before : "";
  ::setenv("BIMLOC_MCAP_PREFETCH", "0", 1);
  EXPECT_EQ(ros2::defaultPrefetchChunks(), 0u);
  ::setenv("BIMLOC_MCAP_PREFETCH", "5", 1);
  EXPECT_EQ(ros2::defaultPrefetchChunks(), 5u);
  ::setenv("BIMLOC_MCAP_PREFETCH", "many", 1);
  EXPECT_THROW(ros2::defaultPrefetchChunks(), std::runtime_error);
  ::unsetenv("BIMLOC_MCAP_PREFETCH");
  EXPECT_EQ(ros2::defaultPrefetchChunks(), 3u);
  if (before) ::setenv("BIMLOC_MCAP_PREFETCH", saved.c_str(), 1);
}
