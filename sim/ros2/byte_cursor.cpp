#include "sim/ros2/byte_cursor.hpp"

#include <cstring>
#include <stdexcept>

namespace bimloc::sim::ros2 {

void ByteCursor::fail(const std::string& what) const {
  throw std::runtime_error(where_ + ": at byte " + std::to_string(base_ + pos_) + ": " + what);
}

const std::uint8_t* ByteCursor::need(std::uint64_t n, const char* field) {
  if (n > size_ - pos_)
    fail(std::string(field) + ": needs " + std::to_string(n) + " bytes, " + std::to_string(size_ - pos_) + " left");
  const std::uint8_t* p = data_ + pos_;
  pos_ += static_cast<std::size_t>(n);
  return p;
}

std::uint8_t ByteCursor::u8(const char* field) { return *need(1, field); }

#define BIMLOC_CURSOR_READ(NAME, TYPE)        \
  TYPE ByteCursor::NAME(const char* field) {  \
    TYPE v;                                   \
    std::memcpy(&v, need(sizeof v, field), sizeof v); \
    return v;                                 \
  }
BIMLOC_CURSOR_READ(u16, std::uint16_t)
BIMLOC_CURSOR_READ(u32, std::uint32_t)
BIMLOC_CURSOR_READ(u64, std::uint64_t)
#undef BIMLOC_CURSOR_READ

std::string ByteCursor::string(const char* field) {
  const std::uint32_t n = u32(field);
  const std::uint8_t* p = need(n, field);
  return std::string(reinterpret_cast<const char*>(p), n);
}

const std::uint8_t* ByteCursor::bytes(std::uint64_t n, const char* field) { return need(n, field); }

std::map<std::string, std::string> ByteCursor::stringMap(const char* field) {
  const std::uint32_t n = u32(field);
  const std::uint64_t at = fileOffset();
  ByteCursor inner(need(n, field), n, where_, at);
  std::map<std::string, std::string> m;
  while (!inner.done()) {
    std::string key = inner.string(field);
    m[key] = inner.string(field);
  }
  return m;
}

}  // namespace bimloc::sim::ros2
