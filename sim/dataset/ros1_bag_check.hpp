// The records of a ROS 1 bag checked before rosbag reads it. rosbag trusts what the index says
// about a chunk: an index entry whose offset lies past its chunk's end made it read beyond its
// buffer (SIGSEGV, tests/test_ros1_compressed_fuzz.cpp), and an index record whose count says
// more entries than its bytes hold made it take the next records for entries. Checked here: the
// chunks' compression (none, lz4 or bz2: what rosbag decompresses), every chunk within the file,
// an uncompressed chunk's size, each index record's count against its bytes, and each entry's
// offset within its chunk; in an uncompressed chunk, that it is a message record that ends
// within the chunk. A compressed chunk's contents are checked by its decompressor (bz2's CRC,
// roslz4's XXH32) when rosbag reads it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bimloc::sim {

// The last message of a compressed chunk, as its index says: its record must end where the
// chunk's size field says the chunk ends. roslz4 checks the size; rosbag's bz2 path does not
// (it sizes its buffer by the field and reads on), so the reader checks it as it reads that
// message (ros1_bag_messages.cpp) and warns.
struct Ros1ChunkEnd {
  std::uint64_t chunk_pos = 0;
  std::uint32_t size = 0;           // the chunk's size field: its uncompressed bytes
  std::uint32_t last_offset = 0;    // where its last message record starts in them
  std::string topic;
  std::uint64_t stamp_ns = 0;       // that message's receive time (the index's)
};

// Throws std::runtime_error "PATH: at byte N: ..." naming the record and the problem. A bag
// without an index (a recording cut short) or whose index records cannot be parsed is left to
// rosbag, which refuses it with its own words. Returns the compressed chunks' last messages.
std::vector<Ros1ChunkEnd> checkRos1BagRecords(const std::string& path);

}  // namespace bimloc::sim
