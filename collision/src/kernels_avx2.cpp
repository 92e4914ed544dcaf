// The traversal compiled for AVX2 and FMA (chosen at run time by simd.cpp): a node's eight children
// in one register, two triangle packs per leaf step.
#if defined(__x86_64__)
#define VT_KERNEL_NS avx2
#define VT_KERNEL_ISA VT_ISA_AVX2
#define VT_KERNEL_LEAF_LANES 8
#define VT_KERNEL_TARGET "avx2,fma"
#include "kernel_set.inc"
#endif
