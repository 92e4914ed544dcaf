// The committed AVX2 kernels (HEAD), compiled under the avx512_on_avx2 set's name for A/B.
#define VT_KERNEL_NS avx512_on_avx2
#define VT_KERNEL_ISA VT_ISA_AVX2
#define VT_KERNEL_LEAF_LANES 8
#define VT_KERNEL_TARGET "avx2,fma"
#include "kernel_set.inc"
