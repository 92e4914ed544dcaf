#pragma once
// Single-writer, many-reader "newest value" channel (a seqlock). Lock-free, allocation-free:
// safe on the haptic thread. The payload is stored as relaxed atomic words so the
// reader's speculative copy is not a data race (TSan-clean).
#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace vt {

template <class T>
class LatestValue {
  static_assert(std::is_trivially_copyable_v<T>, "LatestValue carries trivially copyable snapshots");

 public:
  /// Writer thread only. Never blocks.
  void publish(const T& value) noexcept {
    Words words;
    std::memcpy(words.data(), &value, sizeof(T));
    const std::uint64_t seq = m_sequence.load(std::memory_order_relaxed);
    m_sequence.store(seq + 1, std::memory_order_relaxed);  // odd: write in progress
    std::atomic_thread_fence(std::memory_order_release);
    for (std::size_t i = 0; i < kWords; ++i) m_words[i].store(words[i], std::memory_order_relaxed);
    m_sequence.store(seq + 2, std::memory_order_release);
  }

  /// Any thread. Returns false when nothing was published yet. Retries while a write races.
  bool read(T& out) const noexcept {
    Words words;
    std::uint64_t before = 0;
    do {
      before = m_sequence.load(std::memory_order_acquire);
      if (before == 0) return false;
      if (before & 1u) continue;
      for (std::size_t i = 0; i < kWords; ++i) words[i] = m_words[i].load(std::memory_order_relaxed);
      std::atomic_thread_fence(std::memory_order_acquire);
    } while ((before & 1u) || before != m_sequence.load(std::memory_order_relaxed));
    std::memcpy(static_cast<void*>(&out), words.data(), sizeof(T));  // T may have member initialisers
    return true;
  }

  /// Increases by one per publish; lets readers see whether anything new arrived.
  std::uint64_t version() const noexcept { return m_sequence.load(std::memory_order_acquire) / 2; }

 private:
  static constexpr std::size_t kWords = (sizeof(T) + 7) / 8;
  using Words = std::array<std::uint64_t, kWords>;
  std::atomic<std::uint64_t> m_sequence{0};
  std::array<std::atomic<std::uint64_t>, kWords> m_words{};
};

}  // namespace vt
