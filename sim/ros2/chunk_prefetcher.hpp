// Reading an MCAP file's chunks ahead of the reader: a worker thread decompresses (and checks
// the CRC of, and indexes the messages of) the next chunks while the reading thread decodes the
// messages of the current one. On a zstd bag that takes the decompression, about a tenth of the
// read's CPU, off the reading thread's path.
//
// Deterministic: the chunks come out in the order given, each exactly as the reading thread
// would have loaded it itself (the same load function), so the messages, their order and their
// bytes do not depend on the threads' timing. A chunk that fails to load is handed over as its
// error, rethrown by next() when the reader reaches that chunk, after every message before it,
// as a single-threaded read would throw it; the worker stops there. Bounded: at most `ahead`
// chunks wait loaded. The destructor stops and joins the worker (a reader that stops early, or
// whose visit throws, never leaves it running or blocked).
#pragma once

#include "sim/ros2/compression.hpp"
#include "sim/ros2/mcap_reader.hpp"

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <cstdint>
#include <map>
#include <memory>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace bimloc::sim::ros2 {

struct LoadedChunk {
  std::vector<std::uint8_t> buffer;   // the decompressed records (unused for a chunk read in place)
  std::vector<McapMessage> messages;  // into `buffer` or the file, sorted by log time
};

// Buffers a reader is done with, whose capacity serves the next chunks to decompress: shared by
// the passes of one McapReader (BagInput reads the small topics, the first cloud, then the
// clouds), so that a pass starts on pages an earlier pass already touched instead of fresh ones
// (each fresh 4 KiB page is a page fault, and glibc hands a freed buffer of chunk size back to
// the kernel). Holds at most `most` buffers; safe from any thread.
class BufferPool {
 public:
  explicit BufferPool(std::size_t most) : most_(most) {}
  // A spare buffer (its capacity kept, its size whatever it was), or an empty one.
  std::vector<std::uint8_t> take();
  void give(std::vector<std::uint8_t>&& buffer);
  void setMost(std::size_t most);

 private:
  std::mutex mutex_;
  std::size_t most_;
  std::vector<std::vector<std::uint8_t>> spares_;
};

class ChunkPrefetcher {
 public:
  // Loads the i-th chunk into `chunk` (whose buffer may hold an earlier chunk's capacity),
  // decompressing with `z`; throws for a damaged chunk. With workers it runs on their threads,
  // several chunks at once, so it must only read what the reading thread does not change.
  using Load = std::function<void(std::size_t i, Decompressor& z, LoadedChunk& chunk)>;

  // `count` chunks; `ahead`: how many may be loaded (or loading) beyond those the reader took,
  // by `workers` threads (ahead 0 or workers 0: none, each chunk is loaded by next() on the
  // calling thread: the single-threaded read). The workers start at once, on the first `ahead`
  // chunks: a read that stops early should ask for none ahead (McapReader's ReadPlan::kFirst).
  // `pool`: where the chunks' buffers come from and go back to (a reader's, outliving this
  // prefetcher); nullptr: a pool of its own.
  ChunkPrefetcher(std::size_t count, std::size_t ahead, Load load, std::size_t workers = 1, BufferPool* pool = nullptr);
  ~ChunkPrefetcher();
  ChunkPrefetcher(const ChunkPrefetcher&) = delete;
  ChunkPrefetcher& operator=(const ChunkPrefetcher&) = delete;

  // The next chunk, in order; rethrows the error of a chunk that failed to load.
  LoadedChunk next();
  // A buffer the reader is done with: its capacity serves a later chunk.
  void recycle(std::vector<std::uint8_t>&& buffer);
  bool threaded() const { return !workers_.empty(); }

 private:
  struct Slot {
    LoadedChunk chunk;
    std::exception_ptr error;
  };
  void work(Decompressor& z);
  bool canClaim() const;  // under mutex_

  std::size_t count_, ahead_;
  Load load_;
  std::vector<std::unique_ptr<Decompressor>> decompressors_;  // one a worker, or the caller's
  std::mutex mutex_;
  std::condition_variable changed_;
  std::map<std::size_t, Slot> ready_;  // loaded chunks by index
  std::size_t taken_ = 0, requested_ = 0, next_load_ = 0, failed_at_ = SIZE_MAX, workers_done_ = 0;
  std::unique_ptr<BufferPool> own_pool_;
  BufferPool* pool_;
  bool stop_ = false;
  std::vector<std::thread> workers_;
};

// How many chunks an MCAP read decompresses ahead on worker threads: the environment's
// BIMLOC_MCAP_PREFETCH (0: none, the single-threaded read), else 3. Throws
// std::runtime_error naming the variable when it is not a number from 0 to 64.
std::size_t defaultPrefetchChunks();

}  // namespace bimloc::sim::ros2
