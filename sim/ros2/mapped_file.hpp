// A file mapped read-only into memory (POSIX mmap): the MCAP reader jumps to chunks by the
// summary's offsets without reading the whole file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace bimloc::sim::ros2 {

class MappedFile {
 public:
  explicit MappedFile(const std::string& path);  // throws std::runtime_error naming the file
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  const std::uint8_t* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  const std::uint8_t* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace bimloc::sim::ros2
