#pragma once
// Adaptive binary range coder (the LZMA scheme: 11-bit probabilities, carry via a cached
// byte) with a short flush: the final value is chosen with as many trailing zero bytes as
// possible and those are dropped, since the decoder reads zeros past the end. Small blocks
// (a few bytes each) are why the flush matters.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

namespace vt::haptics::codec {

/// Probability that the next bit is 0, in 1/2048; adapts towards what was coded.
struct BitModel {
  std::uint16_t p = 1024;
};

inline constexpr int kProbBits = 11;
inline constexpr int kAdaptShift = 4;  // fast adaptation: a short block has few symbols per context

/// Moves `model` towards the coded bit; larger shifts adapt slower but settle closer.
inline void adapt(BitModel& model, int bit, int shift) noexcept {
  if (bit == 0) model.p = std::uint16_t(model.p + (((1u << kProbBits) - model.p) >> shift));
  else model.p = std::uint16_t(model.p - (model.p >> shift));
}

class RangeEncoder {
 public:
  static constexpr bool kEncodes = true;
  explicit RangeEncoder(std::span<std::uint8_t> out, int adaptShift = kAdaptShift) noexcept
      : m_out(out), m_shift(adaptShift) {}

  void bit(BitModel& model, int bit) noexcept {
    const std::uint32_t bound = (m_range >> kProbBits) * model.p;
    if (bit == 0) {
      m_range = bound;
    } else {
      m_low += bound;
      m_range -= bound;
    }
    adapt(model, bit, m_shift);
    normalize();
  }
  /// An equiprobable bit (signs, suffixes).
  void direct(int bit) noexcept {
    m_range >>= 1;
    if (bit) m_low += m_range;
    normalize();
  }
  /// True once a byte did not fit into the output.
  bool overflowed() const noexcept { return m_overflow; }
  /// Flushes; returns the byte count, or 0 if the output overflowed.
  std::size_t finish() noexcept {
    for (int bits = 32; bits >= 0; --bits) {
      const std::uint64_t mask = (std::uint64_t(1) << bits) - 1;
      const std::uint64_t v = (m_low + mask) & ~mask;
      if (v < m_low + m_range) {
        m_low = v;
        break;
      }
    }
    for (int i = 0; i < 5; ++i) shiftLow();
    if (m_overflow) return 0;
    while (m_pos > 0 && m_out[m_pos - 1] == 0) --m_pos;
    return m_pos;
  }

 private:
  void normalize() noexcept {
    while (m_range < (1u << 24)) {
      m_range <<= 8;
      shiftLow();
    }
  }
  void shiftLow() noexcept {
    if (std::uint32_t(m_low) < 0xFF000000u || (m_low >> 32) != 0) {
      std::uint8_t carry = std::uint8_t(m_low >> 32);
      std::uint8_t temp = m_cache;
      do {
        emit(std::uint8_t(temp + carry));
        temp = 0xFF;
      } while (--m_cacheSize != 0);
      m_cache = std::uint8_t(m_low >> 24);
    }
    ++m_cacheSize;
    m_low = (m_low & 0x00FFFFFFu) << 8;
  }
  void emit(std::uint8_t byte) noexcept {
    // The very first byte is always the initial zero cache: never stored.
    if (m_first) {
      m_first = false;
      return;
    }
    if (m_pos < m_out.size()) m_out[m_pos++] = byte;
    else m_overflow = true;
  }

  std::span<std::uint8_t> m_out;
  int m_shift;
  std::size_t m_pos = 0;
  std::uint64_t m_low = 0;
  std::uint32_t m_range = 0xFFFFFFFFu;
  std::uint8_t m_cache = 0;
  std::uint64_t m_cacheSize = 1;
  bool m_first = true;
  bool m_overflow = false;
};

/// Counts what a RangeEncoder would spend (in bits, adapting the models the same way) without
/// writing: the encoder's rate estimate when it compares ways to code a block.
class BitCounter {
 public:
  static constexpr bool kEncodes = true;
  explicit BitCounter(int adaptShift = kAdaptShift) noexcept : m_shift(adaptShift) {}
  void bit(BitModel& model, int bit) noexcept {
    const int p = bit == 0 ? model.p : (1 << kProbBits) - model.p;
    m_bits += cost(std::max(p, 1));
    adapt(model, bit, m_shift);
  }
  void direct(int) noexcept { m_bits += 1.0; }
  double bits() const noexcept { return m_bits; }

 private:
  static double cost(int p) noexcept {
    static const auto table = [] {
      std::array<float, (1 << kProbBits) + 1> t{};
      for (int i = 1; i <= (1 << kProbBits); ++i) t[std::size_t(i)] = -std::log2(float(i) / float(1 << kProbBits));
      return t;
    }();
    return table[std::size_t(p)];
  }
  int m_shift;
  double m_bits = 0.0;
};

class RangeDecoder {
 public:
  static constexpr bool kEncodes = false;
  explicit RangeDecoder(std::span<const std::uint8_t> in, int adaptShift = kAdaptShift) noexcept
      : m_in(in), m_shift(adaptShift) {
    for (int i = 0; i < 4; ++i) m_code = (m_code << 8) | next();
  }
  int bit(BitModel& model) noexcept {
    const std::uint32_t bound = (m_range >> kProbBits) * model.p;
    int bit = 0;
    if (m_code < bound) {
      m_range = bound;
    } else {
      m_code -= bound;
      m_range -= bound;
      bit = 1;
    }
    adapt(model, bit, m_shift);
    normalize();
    return bit;
  }
  int direct() noexcept {
    m_range >>= 1;
    int bit = 0;
    if (m_code >= m_range) {
      m_code -= m_range;
      bit = 1;
    }
    normalize();
    return bit;
  }
  /// Bytes read beyond the input (zeros); a well-formed block stays within a few.
  std::size_t overrun() const noexcept { return m_pos > m_in.size() ? m_pos - m_in.size() : 0; }

 private:
  std::uint8_t next() noexcept {
    const std::uint8_t byte = m_pos < m_in.size() ? m_in[m_pos] : 0;
    ++m_pos;
    return byte;
  }
  void normalize() noexcept {
    while (m_range < (1u << 24)) {
      m_range <<= 8;
      m_code = (m_code << 8) | next();
    }
  }
  std::span<const std::uint8_t> m_in;
  int m_shift;
  std::size_t m_pos = 0;
  std::uint32_t m_code = 0;
  std::uint32_t m_range = 0xFFFFFFFFu;
};

}  // namespace vt::haptics::codec
