// The traversal compiled for AVX-512 (F and VL; chosen at run time by simd.cpp): comparisons
// into mask registers, four triangle packs (16 lanes) per leaf step.
#if defined(__x86_64__)
#define VT_KERNEL_NS avx512
#define VT_KERNEL_ISA VT_ISA_AVX512
#define VT_KERNEL_LEAF_LANES 16
#define VT_KERNEL_TARGET "avx512f,avx512vl,fma"
#include "kernel_set.inc"
#endif
