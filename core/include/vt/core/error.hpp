#pragma once
// Errors at setup and load boundaries. Real-time code never throws: it counts.
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

/// Called when an internal invariant breaks (a bug, not bad input); replaceable for tests.
using AssertHandler = void (*)(const char* expr, const char* file, int line);
void setAssertHandler(AssertHandler handler) noexcept;
[[noreturn]] void assertFailed(const char* expr, const char* file, int line) noexcept;

}  // namespace vt

/// Invariant check that stays on in release builds (cheap checks only).
#define VT_ASSERT(expr) ((expr) ? (void)0 : ::vt::assertFailed(#expr, __FILE__, __LINE__))
