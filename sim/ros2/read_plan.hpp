// How far a read of a bag's messages will go, so that the storage decompresses what it needs and
// no more: an MCAP file's chunks are read ahead on worker threads from the first chunk for a
// read that goes to the end, and not at all for one that stops at once.
#pragma once

namespace bimloc::sim::ros2 {

enum class ReadPlan {
  kAll,          // every message of the topics, to the end
  kSmallTopics,  // the same, a few small topics whose messages share chunks with big ones (the
                 // clouds): MCAP decompresses a chunk only as far as its last message of them
  kFirst,        // the first message or so, then the visit stops (the first cloud's layout):
                 // MCAP reads no chunk ahead, and keeps the chunk it stopped in for the next
                 // read of the same topics, which starts there
};

}  // namespace bimloc::sim::ros2
