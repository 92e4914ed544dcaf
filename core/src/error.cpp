#include "vt/core/error.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>

namespace vt {
namespace {
std::atomic<std::uint64_t> g_invariantViolations{0};
}  // namespace

void countInvariantViolation() noexcept { g_invariantViolations.fetch_add(1, std::memory_order_relaxed); }

std::uint64_t invariantViolations() noexcept { return g_invariantViolations.load(std::memory_order_relaxed); }

void assertFailed(const char* expr, const char* file, int line) noexcept {
  std::fprintf(stderr, "vtouching: internal error: assertion '%s' failed at %s:%d\n", expr, file, line);
  std::abort();
}

}  // namespace vt
