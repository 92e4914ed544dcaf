#include "vt/collision/simd.hpp"

#include <atomic>
#include <cstdint>

#if defined(__x86_64__)
#include <cpuid.h>
#endif

#include "kernels.hpp"

namespace vt::collision {
namespace {

#if defined(__x86_64__)
// XCR0: the register state the OS saves on a context switch. A CPU that has an instruction
// set is no use if the OS does not save its registers.
std::uint64_t enabledStates() noexcept {
  unsigned eax, ebx, ecx, edx;
  if (!__get_cpuid(1, &eax, &ebx, &ecx, &edx) || !(ecx & bit_OSXSAVE)) return 0;
  std::uint32_t lo, hi;
  __asm__("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0));
  return std::uint64_t(hi) << 32 | lo;
}
#endif

SimdLevel detect() noexcept {
#if defined(__x86_64__)
  unsigned eax, ebx, ecx, edx;
  // The wider kernels decode planes with FMA (kernel_set.inc).
  if (!__get_cpuid(1, &eax, &ebx, &ecx, &edx) || !(ecx & bit_FMA)) return SimdLevel::Sse2;
  if (!__get_cpuid_count(7, 0, &eax, &ebx, &ecx, &edx)) return SimdLevel::Sse2;
  const std::uint64_t states = enabledStates();
  constexpr std::uint64_t kSseAvx = 0x6;           // XMM and YMM upper halves
  constexpr std::uint64_t kAvx512 = kSseAvx | 0xe0;  // and opmask, ZMM upper halves, ZMM16-31
  if ((ebx & bit_AVX512F) && (ebx & bit_AVX512VL) && (states & kAvx512) == kAvx512) return SimdLevel::Avx512;
  if ((ebx & bit_AVX2) && (states & kSseAvx) == kSseAvx) return SimdLevel::Avx2;
#endif
  return SimdLevel::Sse2;
}

SimdLevel best() noexcept {
  static const SimdLevel level = detect();
  return level;
}

#if defined(__x86_64__)
// Point queries from `points`, rays from `rays`.
template <class Node>
WalkKernels<Node> combined(const WalkKernels<Node>& rays, const WalkKernels<Node>& points) noexcept {
  return {rays.intersect, points.closestPoint, rays.intersects, points.closestPoints};
}

// What AVX-512 CPUs run: spheres on the 16-lane AVX-512 walks (on Zen 5, 13 - 18 % faster than
// AVX2's), rays on the AVX2 walks (there 2 - 5 % faster than AVX-512's on 1M triangles, as
// fast in cache; docs/PERFORMANCE.md, "Rays on the AVX2 walks"). Built on first use: the sets
// live in other files.
const QueryKernels& avx512Default() noexcept {
  static const QueryKernels kernels{combined(avx2::kKernels.floatNodes, avx512::kKernels.floatNodes),
                                    combined(avx2::kKernels.quantizedNodes, avx512::kKernels.quantizedNodes),
                                    avx512::kKernels.orderChildren};
  return kernels;
}
#endif

const QueryKernels& kernelsOf(SimdLevel level) noexcept {
#if defined(__x86_64__)
  switch (level) {
    case SimdLevel::Avx2: return avx2::kKernels;
    case SimdLevel::Avx512: return avx512Default();
    case SimdLevel::Avx512AllQueries: return avx512::kKernels;
    case SimdLevel::Avx512OnAvx2: return avx512_on_avx2::kKernels;
    case SimdLevel::Sse2: break;
  }
#endif
  return sse2::kKernels;
}

// The level and its kernels, set together: every query reads the kernels, in one load.
struct Current {
  std::atomic<SimdLevel> level{best()};
  std::atomic<const QueryKernels*> kernels{&kernelsOf(best())};
};

Current& current() noexcept {
  static Current state;
  return state;
}

}  // namespace

SimdLevel simdLevel() noexcept { return current().level.load(std::memory_order_relaxed); }

SimdLevel bestSimdLevel() noexcept { return best(); }

bool simdLevelSupported(SimdLevel level) noexcept {
  switch (level) {
    case SimdLevel::Sse2: return true;
    case SimdLevel::Avx2:
    case SimdLevel::Avx512OnAvx2: return best() == SimdLevel::Avx2 || best() == SimdLevel::Avx512;
    case SimdLevel::Avx512:
    case SimdLevel::Avx512AllQueries: return best() == SimdLevel::Avx512;
  }
  return false;
}

bool setSimdLevel(SimdLevel level) noexcept {
  if (!simdLevelSupported(level)) return false;
  current().kernels.store(&kernelsOf(level), std::memory_order_relaxed);
  current().level.store(level, std::memory_order_relaxed);
  return true;
}

const char* simdLevelName(SimdLevel level) noexcept {
  switch (level) {
    case SimdLevel::Sse2: return "sse2";
    case SimdLevel::Avx2: return "avx2";
    case SimdLevel::Avx512: return "avx512";
    case SimdLevel::Avx512AllQueries: return "avx512-all-queries";
    case SimdLevel::Avx512OnAvx2: return "avx512-on-avx2";
  }
  return "?";
}

const QueryKernels& activeKernels() noexcept { return *current().kernels.load(std::memory_order_relaxed); }

}  // namespace vt::collision
