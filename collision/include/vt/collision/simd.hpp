#pragma once
// Run-time choice of the instruction set the BVH query kernels use. The library is built for
// baseline x86-64; the same traversal is compiled a second time for AVX2, and the best level
// the CPU supports is chosen when the program starts.
namespace vt::collision {

/// Kernel variants: Sse2 is the portable vector code (SSE2 on x86-64, the fallback), Avx2
/// handles a node's eight children in one register.
enum class SimdLevel { Sse2, Avx2 };

/// The level queries use now. Any thread.
SimdLevel simdLevel() noexcept;
/// The best level this CPU (and OS) supports.
SimdLevel bestSimdLevel() noexcept;
/// Forces a level (tests and benchmarks compare them); false, and no change, when the CPU
/// lacks it. Setup threads, while no query runs.
bool setSimdLevel(SimdLevel level) noexcept;
/// "sse2" or "avx2".
const char* simdLevelName(SimdLevel level) noexcept;

}  // namespace vt::collision
