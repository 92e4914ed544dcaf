// The traversal compiled for AVX2 (chosen at run time by simd.cpp). Headers come first so
// that only the kernels below get the wider target; library code they inline is compiled
// anew inside them, and the copies other files link stay baseline.
#if defined(__x86_64__)
#include <immintrin.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include "kernels.hpp"
#include "vt/core/error.hpp"

#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#else
#pragma GCC push_options
#pragma GCC target("avx2")
#endif

#define VT_KERNEL_NS avx2
#define VT_KERNEL_AVX2 1
#include "traversal.inc"

#if defined(__clang__)
#pragma clang attribute pop
#else
#pragma GCC pop_options
#endif
#endif
