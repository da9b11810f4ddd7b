// CDR, the wire form of ROS 2 messages (OMG XCDR1, as rmw_fastrtps and rmw_cyclonedds
// write it): a 4-byte encapsulation header (0x00 0x00 big endian, 0x00 0x01 little endian,
// then two option bytes), then the fields in order, each primitive aligned to its own size
// (at most 8) counted from the end of the header. Strings are a uint32 length that includes
// the terminating NUL, then the bytes; sequences a uint32 count, then the elements.
// Plain bytes in and out, no ROS: the decoding is tested and fuzzed without a bag.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace bimloc::sim::ros2 {

class CdrReader {
 public:
  // `where` names the message in errors ("FILE: /topic message 3"). Throws std::runtime_error
  // "WHERE: problem" for a header that is not CDR (XCDR2 and parameter lists are refused).
  CdrReader(const std::uint8_t* data, std::size_t size, std::string where);

  bool bigEndian() const { return big_endian_; }
  std::size_t offset() const { return pos_; }  // from the end of the encapsulation header
  std::size_t remaining() const { return size_ - pos_; }
  const std::string& where() const { return where_; }

  std::uint8_t u8();
  std::int8_t i8() { return static_cast<std::int8_t>(u8()); }
  bool boolean() { return u8() != 0; }
  std::uint16_t u16();
  std::int16_t i16() { return static_cast<std::int16_t>(u16()); }
  std::uint32_t u32();
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  std::uint64_t u64();
  std::int64_t i64() { return static_cast<std::int64_t>(u64()); }
  float f32();
  double f64();
  std::string string();
  // A sequence's element count, checked against the bytes left: `min_element_bytes` each.
  std::uint32_t sequenceLength(std::size_t min_element_bytes, const char* field);
  // `n` raw bytes (uint8[] and uint8[N]): a pointer into the message, valid while it lives.
  const std::uint8_t* bytes(std::size_t n, const char* field);
  void align(std::size_t n);

  // Throws "WHERE: broken CDR at byte OFFSET: what".
  [[noreturn]] void fail(const std::string& what) const;

 private:
  void need(std::size_t n, const char* what);
  const std::uint8_t* data_;  // the payload, after the header
  std::size_t size_, pos_ = 0;
  bool big_endian_ = false;
  std::string where_;
};

// Little-endian CDR (the header 00 01 00 00), as every ROS 2 middleware on x86 and ARM writes it.
class CdrWriter {
 public:
  CdrWriter();
  void u8(std::uint8_t v) { buffer_.push_back(v); }
  void i8(std::int8_t v) { u8(static_cast<std::uint8_t>(v)); }
  void boolean(bool v) { u8(v ? 1 : 0); }
  void u16(std::uint16_t v);
  void i16(std::int16_t v) { u16(static_cast<std::uint16_t>(v)); }
  void u32(std::uint32_t v);
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void u64(std::uint64_t v);
  void i64(std::int64_t v) { u64(static_cast<std::uint64_t>(v)); }
  void f32(float v);
  void f64(double v);
  void string(const std::string& s);
  void sequenceLength(std::size_t n);
  void bytes(const std::uint8_t* data, std::size_t n);
  void align(std::size_t n);

  const std::vector<std::uint8_t>& data() const { return buffer_; }
  std::vector<std::uint8_t> take() { return std::move(buffer_); }

 private:
  void raw(const void* p, std::size_t n);
  std::vector<std::uint8_t> buffer_;  // header included: alignment counts from byte 4
};

}  // namespace bimloc::sim::ros2
