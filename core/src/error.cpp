#include "vt/core/error.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>

namespace vt {
namespace {
std::atomic<std::uint64_t> g_invariantViolations{0};
thread_local const LoadScope* t_innermostLoad = nullptr;
// A fixed buffer: the destructor that fills it runs while an allocation failure unwinds.
thread_local char t_failedLoad[512] = "";
}  // namespace

LoadScope::LoadScope(std::string what)
    : m_what(std::move(what)), m_outer(t_innermostLoad), m_exceptions(std::uncaught_exceptions()) {
  if (!m_outer) t_failedLoad[0] = '\0';  // a new load: forget an earlier failure that was handled
  t_innermostLoad = this;
}

LoadScope::~LoadScope() {
  t_innermostLoad = m_outer;
  if (std::uncaught_exceptions() > m_exceptions && t_failedLoad[0] == '\0') {
    std::strncpy(t_failedLoad, m_what.c_str(), sizeof t_failedLoad - 1);
    t_failedLoad[sizeof t_failedLoad - 1] = '\0';
  }
}

std::string failedLoad() { return t_failedLoad; }

void countInvariantViolation() noexcept { g_invariantViolations.fetch_add(1, std::memory_order_relaxed); }

std::uint64_t invariantViolations() noexcept { return g_invariantViolations.load(std::memory_order_relaxed); }

void assertFailed(const char* expr, const char* file, int line) noexcept {
  std::fprintf(stderr, "vtouching: internal error: assertion '%s' failed at %s:%d\n", expr, file, line);
  std::abort();
}

}  // namespace vt
