#include "sim/ros2/chunk_prefetcher.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <system_error>

namespace bimloc::sim::ros2 {

std::size_t defaultPrefetchChunks() {
  const char* env = std::getenv("BIMLOC_MCAP_PREFETCH");
  if (!env || !*env) return 3;
  char* end = nullptr;
  const unsigned long n = std::strtoul(env, &end, 10);
  if (*end != '\0' || n > 64)
    throw std::runtime_error(std::string("BIMLOC_MCAP_PREFETCH=") + env + ": not a number of chunks from 0 to 64");
  return static_cast<std::size_t>(n);
}

std::vector<std::uint8_t> BufferPool::take() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (spares_.empty()) return {};
  std::vector<std::uint8_t> b = std::move(spares_.back());
  spares_.pop_back();
  return b;
}

void BufferPool::give(std::vector<std::uint8_t>&& buffer) {
  if (buffer.capacity() == 0) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (spares_.size() < most_) spares_.push_back(std::move(buffer));  // more would only hold memory
}

void BufferPool::setMost(std::size_t most) {
  std::lock_guard<std::mutex> lock(mutex_);
  most_ = most;
  if (spares_.size() > most_) spares_.resize(most_);
}

ChunkPrefetcher::ChunkPrefetcher(std::size_t count, std::size_t ahead, Load load, std::size_t workers, BufferPool* pool)
    : count_(count), ahead_(ahead), load_(std::move(load)),
      own_pool_(pool ? nullptr : std::make_unique<BufferPool>(ahead + 2)), pool_(pool ? pool : own_pool_.get()) {
  if (ahead_ == 0 || count_ == 0) workers = 0;
  for (std::size_t w = 0; w < std::max<std::size_t>(workers, 1); ++w) decompressors_.push_back(std::make_unique<Decompressor>());
  for (std::size_t w = 0; w < workers; ++w) {
    try {
      workers_.emplace_back([this, z = decompressors_[w].get()] { work(*z); });
    } catch (const std::system_error&) {  // no (more) threads to be had: read with those there are
      break;
    }
  }
}

ChunkPrefetcher::~ChunkPrefetcher() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  for (auto& w : workers_) w.join();
}

bool ChunkPrefetcher::canClaim() const {
  // The chunk the reader waits for, and up to `ahead` after those it has taken, from the start:
  // the first chunks load in parallel while the reader waits for the first.
  return next_load_ < count_ && next_load_ <= failed_at_ && next_load_ < std::max(requested_, taken_ + ahead_);
}

void ChunkPrefetcher::work(Decompressor& z) {
  while (true) {
    std::size_t i;
    Slot slot;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [&] { return stop_ || canClaim() || next_load_ >= count_ || next_load_ > failed_at_; });
      if (stop_ || !canClaim()) break;  // stopped, or nothing left to load
      i = next_load_++;
    }
    slot.chunk.buffer = pool_->take();
    try {
      load_(i, z, slot.chunk);
    } catch (...) {  // handed over as it is: the reader throws it when it reaches this chunk
      slot.error = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (slot.error) failed_at_ = std::min(failed_at_, i);  // nothing after a damaged chunk is loaded
      ready_.emplace(i, std::move(slot));
    }
    changed_.notify_all();
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++workers_done_;
  }
  changed_.notify_all();
}

LoadedChunk ChunkPrefetcher::next() {
  if (workers_.empty()) {
    if (taken_ >= count_) throw std::logic_error("ChunkPrefetcher: no chunk left");
    LoadedChunk chunk;
    chunk.buffer = pool_->take();
    load_(taken_++, *decompressors_[0], chunk);
    return chunk;
  }
  Slot slot;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    if (taken_ >= count_) throw std::logic_error("ChunkPrefetcher: no chunk left");
    requested_ = taken_ + 1;
    changed_.notify_all();  // a worker waiting for the window may load this one
    changed_.wait(lock, [&] { return ready_.count(taken_) || workers_done_ == workers_.size(); });
    const auto it = ready_.find(taken_);
    if (it == ready_.end()) throw std::logic_error("ChunkPrefetcher: the workers stopped before chunk " + std::to_string(taken_));
    slot = std::move(it->second);
    ready_.erase(it);
    ++taken_;
  }
  changed_.notify_all();  // the window moved
  if (slot.error) std::rethrow_exception(slot.error);
  return std::move(slot.chunk);
}

void ChunkPrefetcher::recycle(std::vector<std::uint8_t>&& buffer) { pool_->give(std::move(buffer)); }

}  // namespace bimloc::sim::ros2
