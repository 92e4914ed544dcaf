#pragma once
// Little-endian field writer/reader over a byte span. A write or read past the end sets
// ok() to false instead of touching memory, so codecs check once at the end.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

namespace vt::net::wire {

class Writer {
 public:
  explicit Writer(std::span<std::uint8_t> out) noexcept : m_out(out) {}
  void u8(std::uint8_t v) noexcept { put(v, 1); }
  void u16(std::uint16_t v) noexcept { put(v, 2); }
  void u32(std::uint32_t v) noexcept { put(v, 4); }
  void u64(std::uint64_t v) noexcept { put(v, 8); }
  void i64(std::int64_t v) noexcept { put(std::uint64_t(v), 8); }
  void f32(float v) noexcept { put(std::bit_cast<std::uint32_t>(v), 4); }
  void i16(std::int16_t v) noexcept { put(std::uint16_t(v), 2); }
  void i32(std::int32_t v) noexcept { put(std::uint32_t(v), 4); }
  /// LEB128: 7 bits a byte, low bits first.
  void varint(std::uint64_t v) noexcept {
    while (v >= 0x80) {
      u8(std::uint8_t(v | 0x80));
      v >>= 7;
    }
    u8(std::uint8_t(v));
  }
  void bytes(std::span<const std::uint8_t> data) noexcept {
    if (!reserve(data.size())) return;
    if (!data.empty()) std::memcpy(m_out.data() + m_pos, data.data(), data.size());
    m_pos += data.size();
  }
  /// Marks the output invalid (a field out of range).
  void fail() noexcept { m_ok = false; }
  bool ok() const noexcept { return m_ok; }
  std::size_t size() const noexcept { return m_pos; }

 private:
  bool reserve(std::size_t n) noexcept {
    if (!m_ok || m_out.size() - m_pos < n) m_ok = false;
    return m_ok;
  }
  void put(std::uint64_t v, int n) noexcept {
    if (!reserve(std::size_t(n))) return;
    for (int i = 0; i < n; ++i) m_out[m_pos++] = std::uint8_t(v >> (8 * i));
  }
  std::span<std::uint8_t> m_out;
  std::size_t m_pos = 0;
  bool m_ok = true;
};

class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> in) noexcept : m_in(in) {}
  std::uint8_t u8() noexcept { return std::uint8_t(get(1)); }
  std::uint16_t u16() noexcept { return std::uint16_t(get(2)); }
  std::uint32_t u32() noexcept { return std::uint32_t(get(4)); }
  std::uint64_t u64() noexcept { return get(8); }
  std::int64_t i64() noexcept { return std::int64_t(get(8)); }
  float f32() noexcept { return std::bit_cast<float>(std::uint32_t(get(4))); }
  std::int16_t i16() noexcept { return std::int16_t(std::uint16_t(get(2))); }
  std::int32_t i32() noexcept { return std::int32_t(std::uint32_t(get(4))); }
  /// LEB128 of at most 10 bytes; a longer or overlong one fails the reader (one encoding each).
  std::uint64_t varint() noexcept {
    std::uint64_t v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      const std::uint8_t b = u8();
      if (!m_ok) return 0;
      if (shift == 63 && b > 1) break;
      v |= std::uint64_t(b & 0x7f) << shift;
      if (!(b & 0x80)) {
        if (b == 0 && shift > 0) break;  // a trailing zero byte: not the shortest form
        return v;
      }
    }
    m_ok = false;
    return 0;
  }
  /// The bytes not read yet (empty after a failure).
  std::span<const std::uint8_t> rest() const noexcept { return m_ok ? m_in.subspan(m_pos) : std::span<const std::uint8_t>{}; }
  void skip(std::size_t n) noexcept {
    if (!m_ok || m_in.size() - m_pos < n) m_ok = false;
    else m_pos += n;
  }
  /// Copies n bytes into out (n <= out.size() is the caller's check).
  void bytes(std::uint8_t* out, std::size_t n) noexcept {
    if (!m_ok || m_in.size() - m_pos < n) {
      m_ok = false;
      return;
    }
    if (n) std::memcpy(out, m_in.data() + m_pos, n);
    m_pos += n;
  }
  bool ok() const noexcept { return m_ok; }
  std::size_t remaining() const noexcept { return m_ok ? m_in.size() - m_pos : 0; }

 private:
  std::uint64_t get(int n) noexcept {
    if (!m_ok || m_in.size() - m_pos < std::size_t(n)) {
      m_ok = false;
      return 0;
    }
    std::uint64_t v = 0;
    for (int i = 0; i < n; ++i) v |= std::uint64_t(m_in[m_pos++]) << (8 * i);
    return v;
  }
  std::span<const std::uint8_t> m_in;
  std::size_t m_pos = 0;
  bool m_ok = true;
};

}  // namespace vt::net::wire
