// The traversal for the baseline target (SSE2 on x86-64; plain vector code elsewhere).
#define VT_KERNEL_NS sse2
#define VT_KERNEL_ISA VT_ISA_BASELINE
#define VT_KERNEL_LEAF_LANES 4
#include "kernel_set.inc"
