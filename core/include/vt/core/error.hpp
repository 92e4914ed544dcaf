#pragma once
// Errors at setup and load boundaries. Real-time code never throws: it counts.
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace vt {

/// A failure a user can act on: the message names the file/source, the field and the problem.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Concatenates any streamable values into one string (GCC 12 has no std::format).
template <class... Args>
std::string str(Args&&... args) {
  std::ostringstream out;
  (out << ... << std::forward<Args>(args));
  return out.str();
}

/// Throws vt::Error with the concatenated message.
template <class... Args>
[[noreturn]] void fail(Args&&... args) {
  throw Error(str(std::forward<Args>(args)...));
}

/// Names what this thread is loading while it exists, so that an allocation failure caught far
/// above (main) can say what it was loading: "out of memory while loading glTF 'x.gltf'".
class LoadScope {
 public:
  explicit LoadScope(std::string what);
  ~LoadScope();
  LoadScope(const LoadScope&) = delete;
  LoadScope& operator=(const LoadScope&) = delete;

 private:
  std::string m_what;
  const LoadScope* m_outer;
  int m_exceptions;
};

/// What the innermost LoadScope that an exception unwound was loading (empty if none since the
/// outermost scope began). This thread only.
std::string failedLoad();

/// Called when an internal invariant breaks (a bug, not bad input): one line on stderr, abort.
[[noreturn]] void assertFailed(const char* expr, const char* file, int line) noexcept;

/// Counts a broken invariant on a path that must not stop (the haptic thread): lock-free and
/// allocation-free. See VT_INVARIANT.
void countInvariantViolation() noexcept;
/// Broken invariants counted so far in this process (release builds). Any thread.
std::uint64_t invariantViolations() noexcept;

}  // namespace vt

/// Invariant check that stays on in release builds (cheap checks only).
#define VT_ASSERT(expr) ((expr) ? (void)0 : ::vt::assertFailed(#expr, __FILE__, __LINE__))

/// An invariant on a real-time path: a bug when false. Debug and sanitizer builds
/// (VT_CHECKED_INVARIANTS) fail loudly (assertFailed: a line, then abort); release builds count it
/// (invariantViolations(), shown by the HUD and reports) and the caller takes its documented
/// fallback. Evaluates to `expr`, so `if (!VT_INVARIANT(x)) return fallback;` reads naturally.
#ifdef VT_CHECKED_INVARIANTS
#define VT_INVARIANT(expr) ((expr) ? true : (::vt::assertFailed(#expr, __FILE__, __LINE__), false))
#else
#define VT_INVARIANT(expr) ((expr) ? true : (::vt::countInvariantViolation(), false))
#endif
