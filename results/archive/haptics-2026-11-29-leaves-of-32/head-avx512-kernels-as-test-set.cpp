// The committed AVX-512 kernels (HEAD), compiled under the avx512_on_avx2 set's name for A/B.
#define VT_KERNEL_NS avx512_on_avx2
#define VT_KERNEL_ISA VT_ISA_AVX512
#define VT_KERNEL_LEAF_LANES 16
#define VT_KERNEL_TARGET "avx512f,avx512vl,fma"
#include "kernel_set.inc"
