#include "sim/ros2/cdr.hpp"

#include <cstdio>
#include <cstring>
#include <utility>
#include <stdexcept>

namespace bimloc::sim::ros2 {
namespace {

constexpr std::size_t kHeaderBytes = 4;

template <typename T>
T swapped(T v) {
  std::uint8_t b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
  std::memcpy(&v, b, sizeof(T));
  return v;
}

}  // namespace

CdrReader::CdrReader(const std::uint8_t* data, std::size_t size, std::string where)
    : data_(data), size_(size), where_(std::move(where)) {
  if (size < kHeaderBytes) throw std::runtime_error(where_ + ": broken CDR: " + std::to_string(size) + " bytes, shorter than the 4-byte encapsulation header");
  // Representation identifier: 0x0000 CDR_BE, 0x0001 CDR_LE (XCDR1, plain). 0x0002/0x0003 are
  // parameter lists, 0x0006.. XCDR2: other layouts, which ROS 2 does not use for its messages.
  if (data[0] != 0 || data[1] > 1) {
    char id[16];
    std::snprintf(id, sizeof id, "0x%02x%02x", data[0], data[1]);
    throw std::runtime_error(where_ + ": not plain CDR: encapsulation " + id + " (expected 0x0000 or 0x0001)");
  }
  big_endian_ = data[1] == 0;
  data_ = data + kHeaderBytes;
  size_ = size - kHeaderBytes;
}

void CdrReader::fail(const std::string& what) const {
  throw std::runtime_error(where_ + ": broken CDR at byte " + std::to_string(pos_ + kHeaderBytes) + ": " + what);
}

void CdrReader::need(std::size_t n, const char* what) {
  if (n > size_ - pos_)
    fail(std::string(what) + " needs " + std::to_string(n) + " bytes, " + std::to_string(size_ - pos_) + " left");
}

void CdrReader::align(std::size_t n) {
  const std::size_t pad = (n - pos_ % n) % n;
  need(pad, "alignment");
  pos_ += pad;
}

std::uint8_t CdrReader::u8() {
  need(1, "a byte");
  return data_[pos_++];
}

#define BIMLOC_CDR_READ(NAME, TYPE)                   \
  TYPE CdrReader::NAME() {                            \
    align(sizeof(TYPE));                              \
    need(sizeof(TYPE), #NAME);                        \
    TYPE v;                                           \
    std::memcpy(&v, data_ + pos_, sizeof(TYPE));      \
    pos_ += sizeof(TYPE);                             \
    return big_endian_ ? swapped(v) : v;              \
  }
BIMLOC_CDR_READ(u16, std::uint16_t)
BIMLOC_CDR_READ(u32, std::uint32_t)
BIMLOC_CDR_READ(u64, std::uint64_t)
BIMLOC_CDR_READ(f32, float)
BIMLOC_CDR_READ(f64, double)
#undef BIMLOC_CDR_READ

std::string CdrReader::string() {
  const std::uint32_t n = u32();
  need(n, "a string");
  if (n == 0) return {};  // some writers send 0 for an empty string (no NUL)
  if (data_[pos_ + n - 1] != 0) fail("a string of " + std::to_string(n) + " bytes without its terminating NUL");
  std::string s(reinterpret_cast<const char*>(data_ + pos_), n - 1);
  pos_ += n;
  return s;
}

std::uint32_t CdrReader::sequenceLength(std::size_t min_element_bytes, const char* field) {
  const std::uint32_t n = u32();
  if (min_element_bytes > 0 && n > (size_ - pos_) / min_element_bytes)
    fail(std::string(field) + ": " + std::to_string(n) + " elements claimed, only " + std::to_string(size_ - pos_) +
         " bytes left");
  return n;
}

const std::uint8_t* CdrReader::bytes(std::size_t n, const char* field) {
  need(n, field);
  const std::uint8_t* p = data_ + pos_;
  pos_ += n;
  return p;
}

CdrWriter::CdrWriter() : buffer_{0x00, 0x01, 0x00, 0x00} {
  static_assert(sizeof(double) == 8 && sizeof(float) == 4);
  const std::uint16_t probe = 1;
  std::uint8_t first;
  std::memcpy(&first, &probe, 1);
  if (first != 1) throw std::logic_error("CdrWriter: a big-endian host is not supported");
}

void CdrWriter::align(std::size_t n) {
  while ((buffer_.size() - kHeaderBytes) % n != 0) buffer_.push_back(0);
}

void CdrWriter::raw(const void* p, std::size_t n) {
  const auto* b = static_cast<const std::uint8_t*>(p);
  buffer_.insert(buffer_.end(), b, b + n);
}

void CdrWriter::u16(std::uint16_t v) { align(2), raw(&v, 2); }
void CdrWriter::u32(std::uint32_t v) { align(4), raw(&v, 4); }
void CdrWriter::u64(std::uint64_t v) { align(8), raw(&v, 8); }
void CdrWriter::f32(float v) { align(4), raw(&v, 4); }
void CdrWriter::f64(double v) { align(8), raw(&v, 8); }

void CdrWriter::string(const std::string& s) {
  u32(static_cast<std::uint32_t>(s.size() + 1));
  raw(s.data(), s.size());
  buffer_.push_back(0);
}

void CdrWriter::sequenceLength(std::size_t n) { u32(static_cast<std::uint32_t>(n)); }

void CdrWriter::bytes(const std::uint8_t* data, std::size_t n) { raw(data, n); }

}  // namespace bimloc::sim::ros2
