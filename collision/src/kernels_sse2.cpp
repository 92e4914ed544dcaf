// The traversal for the baseline target (SSE2 on x86-64; plain vector code elsewhere).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "kernels.hpp"
#include "vt/core/error.hpp"

#define VT_KERNEL_NS sse2
#define VT_KERNEL_AVX2 0
#include "traversal.inc"
