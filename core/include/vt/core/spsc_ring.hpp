#pragma once
// Bounded single-producer single-consumer queue. Lock-free and allocation-free after
// construction; a full ring refuses the push and counts it (never silently blocks).
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>

#include "vt/core/error.hpp"

namespace vt {

template <class T>
class SpscRing {
  static_assert(std::is_trivially_copyable_v<T>, "SpscRing carries trivially copyable messages");

 public:
  /// capacity is rounded up to a power of two. Allocates here, never afterwards.
  explicit SpscRing(std::size_t capacity) {
    std::size_t size = 1;
    while (size < capacity) size <<= 1;
    m_mask = size - 1;
    m_slots = std::make_unique<T[]>(size);
  }

  /// Producer thread only. False (and the drop counter grows) when the ring is full.
  bool push(const T& value) noexcept {
    const std::size_t head = m_head.load(std::memory_order_relaxed);
    if (head - m_tail.load(std::memory_order_acquire) > m_mask) {
      m_dropped.fetch_add(1, std::memory_order_relaxed);
      return false;
    }
    m_slots[head & m_mask] = value;
    m_head.store(head + 1, std::memory_order_release);
    return true;
  }

  /// Consumer thread only. False when empty.
  bool pop(T& out) noexcept {
    const std::size_t tail = m_tail.load(std::memory_order_relaxed);
    if (tail == m_head.load(std::memory_order_acquire)) return false;
    out = m_slots[tail & m_mask];
    m_tail.store(tail + 1, std::memory_order_release);
    return true;
  }

  std::size_t capacity() const noexcept { return m_mask + 1; }
  /// Approximate from any thread; exact from the consumer.
  std::size_t size() const noexcept {
    return m_head.load(std::memory_order_acquire) - m_tail.load(std::memory_order_acquire);
  }
  std::uint64_t dropped() const noexcept { return m_dropped.load(std::memory_order_relaxed); }

 private:
  alignas(64) std::atomic<std::size_t> m_head{0};
  alignas(64) std::atomic<std::size_t> m_tail{0};
  alignas(64) std::atomic<std::uint64_t> m_dropped{0};
  std::size_t m_mask = 0;
  std::unique_ptr<T[]> m_slots;
};

}  // namespace vt
