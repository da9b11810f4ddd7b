// The fuzz cases of compressed ROS 1 bags: a bag of `simulate --compression lz4` and one of
// `--compression bz2` (rosbag's own writer), damaged as a failing disk or a killed recorder
// damages them: cut short, bytes of a chunk's compressed data flipped, a chunk's compression
// field changed to a name rosbag does not know, its size field (the uncompressed bytes) wrong,
// and an index entry pointing past its chunk's end (on which rosbag read past its buffer and
// crashed before sim/dataset/ros1_bag_check.cpp refused it). Each case is read through the
// whole input layer of `localize` (BagInput, every cloud decoded); whatever the damage: no
// crash, no hang, and either refused with a message naming the bag or read with a warning. A
// few cases also go through the binary (exit 2, the bag named, nothing written).
#include "bag_fixtures.hpp"
#include "fuzz_mutator.hpp"
#include "test_support.hpp"


#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>

namespace fs = std::filesystem;
using namespace bimloc;

namespace {

const std::string& simulated() {
  return test::simulatedVariants("ros1-compressed-fuzz",
                                 "name: fuzz\nworld: " + test::officePlan() +
                                     "\nstart: {room: R101, yaw_deg: 90}\nmotion: {type: tour, rooms: [C100]}\n"
                                     "duration_s: 0.6\nodometry: {preset: legged}\nseed: 5\n",
                                 {{"lz4", "--compression lz4"}, {"bz2", "--compression bz2"}});
}

using Outcome = test::BagReadOutcome;
Outcome readBag(const std::string& path) { return test::readWholeBag(path); }

// A record of the bag (format 2.0): where it starts, where a field's value lies, its data.
struct Record {
  std::size_t at = 0, data_at = 0;
  std::uint32_t data_len = 0;
  std::map<std::string, std::pair<std::size_t, std::size_t>> fields;  // name -> (value's offset, length)
  std::uint8_t op = 0;
};

std::uint32_t u32(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

std::vector<Record> records(const std::string& b) {
  std::vector<Record> out;
  for (std::size_t at = 13; at + 8 <= b.size();) {
    Record r;
    r.at = at;
    const std::uint32_t header_len = u32(b, at);
    if (header_len > b.size() - at - 8) break;
    for (std::size_t p = at + 4; p + 4 <= at + 4 + header_len;) {
      const std::uint32_t len = u32(b, p);
      const std::string field = b.substr(p + 4, len);
      const std::size_t eq = field.find('=');
      r.fields[field.substr(0, eq)] = {p + 4 + eq + 1, len - eq - 1};
      p += 4 + len;
    }
    r.op = static_cast<std::uint8_t>(b[r.fields.at("op").first]);
    r.data_at = at + 4 + header_len + 4;
    r.data_len = u32(b, at + 4 + header_len);
    out.push_back(r);
    at = r.data_at + r.data_len;
  }
  return out;
}

struct Tally {
  int cases = 0, refused = 0, warned = 0, accepted = 0;
  void count(const Outcome& o) {
    ++cases;
    o.refused ? ++refused : !o.warnings.empty() ? ++warned : ++accepted;
  }
};

void fuzz(const std::string& compression, std::uint32_t seed) {
  const std::string clean = simulated() + "/" + compression + "/dataset.bag";
  const std::string bytes = test::readFile(clean);
  const auto recs = records(bytes);
  std::vector<Record> chunks, indexes;
  for (const auto& r : recs) {
    if (r.op == 0x05) chunks.push_back(r);
    if (r.op == 0x04) indexes.push_back(r);
  }
  ASSERT_GE(chunks.size(), 2u);
  ASSERT_EQ(bytes.substr(chunks[0].fields.at("compression").first, 3), compression);
  ASSERT_TRUE(readBag(clean).warnings.empty());
  std::mt19937 rng(test::fuzzSeed(seed, 20));
  auto below = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  const std::string path = simulated() + "/case-" + compression + ".bag";
  Tally tally;
  auto check = [&](const std::string& damaged, const std::string& trace, bool must_refuse) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << damaged;
    const Outcome o = readBag(path);
    tally.count(o);
    if (o.refused) {
      EXPECT_NE(o.error.find(path + ": "), std::string::npos) << trace << ": the message must name the bag: " << o.error;
    }
    EXPECT_TRUE(o.refused || !o.warnings.empty() || !must_refuse) << trace << ": accepted in silence";
    return o;
  };
  // Cut short: no index at the end, refused (rosbag reindex would rebuild it).
  for (int i = 0; i < test::fuzzCases(10); ++i) {
    const std::size_t size = 13 + below(bytes.size() - 13);
    check(bytes.substr(0, size), compression + " cut at " + std::to_string(size), true);
  }
  // Chunk bytes flipped: bz2's CRC or roslz4's checksum finds them.
  for (int i = 0; i < test::fuzzCases(8); ++i) {
    std::string b = bytes;
    const Record& c = chunks[below(chunks.size())];
    for (int k = 0; k < 1 + i % 4; ++k) b[c.data_at + below(c.data_len)] ^= static_cast<char>(1 + below(255));
    check(b, compression + " bytes of the chunk at " + std::to_string(c.at) + " flipped", true);
  }
  // The compression field: a name rosbag does not know (of the same length, the records intact).
  for (const std::string other : {"lz5", "zst", "BZ2"}) {
    std::string b = bytes;
    const Record& c = chunks[below(chunks.size())];
    b.replace(c.fields.at("compression").first, 3, other);
    const Outcome o = check(b, compression + " chunk at " + std::to_string(c.at) + " said " + other, true);
    EXPECT_NE(o.error.find("compression '" + other + "' unknown"), std::string::npos) << o.error;
  }
  // The size field (the uncompressed bytes) wrong: smaller is refused by both decompressors;
  // larger by roslz4, while rosbag's bz2 path reads on into a buffer that large: a warning.
  for (int i = 0; i < test::fuzzCases(8); ++i) {
    std::string b = bytes;
    const Record& c = chunks[below(chunks.size())];
    const std::uint32_t size = u32(bytes, c.fields.at("size").first);
    const std::uint32_t values[] = {0, size / 2, size - 1, size + 1, size * 2, 0x7fffffffu, 0xffffffffu, size + 4096};
    const std::uint32_t value = values[i % 8];
    std::memcpy(&b[c.fields.at("size").first], &value, 4);
    const Outcome o = check(b, compression + " chunk at " + std::to_string(c.at) + " size " + std::to_string(value), true);
    if (compression == "lz4" || value < size) {
      EXPECT_TRUE(o.refused) << "size " << value << " of " << size;
    }
  }
  // An index entry pointing past its chunk's end, or nowhere: refused before rosbag reads it.
  for (int i = 0; i < test::fuzzCases(4); ++i) {
    std::string b = bytes;
    const Record& index = indexes[below(indexes.size())];
    const std::uint32_t value = i % 2 ? 0xffffffffu : static_cast<std::uint32_t>(4u << 20) + static_cast<std::uint32_t>(below(1000));
    std::memcpy(&b[index.data_at + 12 * below(index.data_len / 12) + 8], &value, 4);
    const Outcome o = check(b, compression + " index at " + std::to_string(index.at) + " offset " + std::to_string(value), true);
    EXPECT_NE(o.error.find("past its end"), std::string::npos) << o.error;
  }
  std::cout << "fuzz compressed ROS 1 (" << compression << "): " << tally.cases << " cases, " << tally.refused
            << " refused by name, " << tally.warned << " read with a warning, " << tally.accepted << " read whole" << std::endl;
}

}  // namespace

TEST(Ros1CompressedFuzz, DamagedLz4BagsAreRefusedByNameNeverACrash) { fuzz("lz4", 29001u); }
TEST(Ros1CompressedFuzz, DamagedBz2BagsAreRefusedOrWarnedByNameNeverACrash) { fuzz("bz2", 29002u); }

// Through the binary: exit 2, the bag named, no output left; a bz2 chunk's size field too large
// is read with the warning (and the same turns).
TEST(Ros1CompressedFuzz, TheBinaryRefusesDamagedCompressedBagsWithExit2) {
  const std::string bytes = test::readFile(simulated() + "/bz2/dataset.bag");
  const auto recs = records(bytes);
  const auto chunk = std::find_if(recs.begin(), recs.end(), [](const Record& r) { return r.op == 0x05; });
  ASSERT_NE(chunk, recs.end());
  for (int i = 0; i < 4; ++i) {
    std::string b = bytes;
    if (i == 0) b.resize(bytes.size() / 2);
    if (i == 1) b.replace(chunk->fields.at("compression").first, 3, "xz2");
    if (i == 2) b[chunk->data_at + chunk->data_len / 2] ^= 0x5A;
    const std::uint32_t huge = 0x7fffffffu;
    if (i == 3) std::memcpy(&b[chunk->fields.at("size").first], &huge, 4);
    const std::string path = simulated() + "/bin" + std::to_string(i) + ".bag", out = simulated() + "/bin_out" + std::to_string(i);
    std::ofstream(path, std::ios::binary) << b;
    const auto r = test::runBimloc("localize '" + path + "' --plan '" + BIMLOC_WORLDS_DIR + "/site_office.ifc' --out '" + out + "'", 60);
    EXPECT_FALSE(r.timed_out) << i;
    EXPECT_EQ(r.signal, 0) << i;
    if (i < 3) {
      EXPECT_EQ(r.exit_code, 2) << i << ": " << r.err;
      EXPECT_NE(r.err.find(path + ": "), std::string::npos) << r.err;
      EXPECT_FALSE(fs::exists(out)) << "output left";
    } else {
      EXPECT_NE(r.exit_code, 2) << r.err;
      EXPECT_NE(r.err.find("declare more uncompressed bytes than their records hold"), std::string::npos) << r.err;
    }
  }
}
