// The AVX-512 set's 16-lane traversal built with AVX2 operations (each 16-lane vector two
// 8-lane halves): on CPUs without AVX-512 the tests check that logic bit for bit against the
// other sets. Never chosen automatically (SimdLevel::Avx512OnAvx2).
#if defined(__x86_64__)
#define VT_KERNEL_NS avx512_on_avx2
#define VT_KERNEL_ISA VT_ISA_AVX2
#define VT_KERNEL_LEAF_LANES 16
#define VT_KERNEL_TARGET "avx2,fma"
#include "kernel_set.inc"
#endif
