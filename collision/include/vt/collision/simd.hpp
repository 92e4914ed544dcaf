#pragma once
// Run-time choice of the instruction set the BVH query kernels use. The library is built for
// baseline x86-64; the same traversal is compiled again for AVX2 and for AVX-512, and the best
// level the CPU and OS support is chosen when the program starts.
namespace vt::collision {

/// Kernel variants. Sse2: the portable vector code (SSE2 on x86-64, the fallback). Avx2 (with
/// FMA): a node's eight children in one register, 8 triangles a leaf step. Avx512 (F, VL, FMA):
/// point queries with masks in mask registers, 16 triangles a leaf step; rays on the Avx2
/// walks, which measured faster (docs/PERFORMANCE.md, "Rays on the AVX2 walks"). Avx512AllQueries:
/// rays on the AVX-512 walks too, for tests and benchmarks; never chosen automatically.
/// Avx512OnAvx2: the AVX-512 kernels' 16-lane logic built from AVX2 halves, so CPUs without
/// AVX-512 test it; never chosen automatically.
enum class SimdLevel { Sse2, Avx2, Avx512, Avx512AllQueries, Avx512OnAvx2 };

/// Every level, in declaration order (tests and benchmarks go through them).
inline constexpr SimdLevel kSimdLevels[] = {SimdLevel::Sse2, SimdLevel::Avx2, SimdLevel::Avx512,
                                            SimdLevel::Avx512AllQueries, SimdLevel::Avx512OnAvx2};

/// The level queries use now. Any thread.
SimdLevel simdLevel() noexcept;
/// The best level this CPU (and OS) supports: Avx512, Avx2 or Sse2.
SimdLevel bestSimdLevel() noexcept;
/// Whether this CPU (and OS) can run `level`'s kernels. Any thread.
bool simdLevelSupported(SimdLevel level) noexcept;
/// Forces a level (tests and benchmarks compare them); false, and no change, when the CPU
/// lacks it. Setup threads, while no query runs.
bool setSimdLevel(SimdLevel level) noexcept;
/// "sse2", "avx2", "avx512", "avx512-all-queries" or "avx512-on-avx2".
const char* simdLevelName(SimdLevel level) noexcept;

}  // namespace vt::collision
