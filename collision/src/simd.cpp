#include "vt/collision/simd.hpp"

#include <atomic>

#include "kernels.hpp"

namespace vt::collision {
namespace {

SimdLevel detect() noexcept {
#if defined(__x86_64__)
  // libgcc's check includes the OS saving AVX state (XCR0), not only the CPUID bit.
  if (__builtin_cpu_supports("avx2")) return SimdLevel::Avx2;
#endif
  return SimdLevel::Sse2;
}

std::atomic<SimdLevel>& current() noexcept {
  static std::atomic<SimdLevel> level{detect()};
  return level;
}

}  // namespace

SimdLevel simdLevel() noexcept { return current().load(std::memory_order_relaxed); }

SimdLevel bestSimdLevel() noexcept { return detect(); }

bool setSimdLevel(SimdLevel level) noexcept {
  if (level == SimdLevel::Avx2 && detect() != SimdLevel::Avx2) return false;
  current().store(level, std::memory_order_relaxed);
  return true;
}

const char* simdLevelName(SimdLevel level) noexcept { return level == SimdLevel::Avx2 ? "avx2" : "sse2"; }

const QueryKernels& activeKernels() noexcept {
#if defined(__x86_64__)
  if (simdLevel() == SimdLevel::Avx2) return avx2::kKernels;
#endif
  return sse2::kKernels;
}

}  // namespace vt::collision
