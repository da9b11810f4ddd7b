// Per-cell values of a large grid, stored in chunks of 1024 consecutive cells made on first
// write: memory and clearing cost follow the cells a search touches, not the grid's extent.
// The path grid of a 235 m x 212 m storey holds 20 M cells of 5 cm; a path search there
// touches a few hundred thousand of them.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

namespace bimloc::sim {

template <class T>
class ChunkedCells {
 public:
  static constexpr int kChunkBits = 10;
  static constexpr std::size_t kChunk = std::size_t{1} << kChunkBits;

  ChunkedCells() = default;
  ChunkedCells(std::size_t cells, T fill) : cells_(cells), fill_(fill), chunks_((cells + kChunk - 1) / kChunk) {}

  std::size_t size() const { return cells_; }
  // The cell's value; `fill` where it was never written.
  T operator[](std::size_t cell) const {
    const auto& chunk = chunks_[cell >> kChunkBits];
    return chunk ? chunk[cell & (kChunk - 1)] : fill_;
  }
  // The cell, for writing (its chunk made, filled, on first use).
  T& at(std::size_t cell) {
    auto& chunk = chunks_[cell >> kChunkBits];
    if (!chunk) {
      chunk = std::make_unique<T[]>(kChunk);
      std::fill_n(chunk.get(), kChunk, fill_);
    }
    return chunk[cell & (kChunk - 1)];
  }
  // Every cell back to `fill`.
  void clear() {
    for (auto& chunk : chunks_) chunk.reset();
  }
  // f(cell, value) for the cells of the chunks written to, in cell order (the others hold fill).
  template <class F>
  void forEachWritten(F&& f) const {
    for (std::size_t k = 0; k < chunks_.size(); ++k) {
      if (!chunks_[k]) continue;
      const std::size_t end = std::min(cells_, (k + 1) * kChunk);
      for (std::size_t c = k * kChunk; c < end; ++c) f(c, chunks_[k][c - k * kChunk]);
    }
  }

 private:
  std::size_t cells_ = 0;
  T fill_{};
  std::vector<std::unique_ptr<T[]>> chunks_;
};

}  // namespace bimloc::sim
