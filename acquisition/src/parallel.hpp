#pragma once
// A tiny fork-join loop over independent items (scan lines) on std::threads. Exceptions
// are kept per item and the first in item order is rethrown, so errors do not depend on timing.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace vt::acq::detail {

/// Calls fn(i) for i in [0, count) on up to `jobs` threads (0 = hardware concurrency);
/// done(finished) runs after each item on the worker that finished it.
template <class Fn, class Done>
void parallelFor(std::size_t count, int jobs, Fn&& fn, Done&& done) {
  std::vector<std::exception_ptr> errors(count);
  std::atomic<std::size_t> next{0}, finished{0};
  const auto work = [&] {
    for (std::size_t i = next++; i < count; i = next++) {
      try {
        fn(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
      done(++finished);
    }
  };
  const int hw = int(std::max(1u, std::thread::hardware_concurrency()));
  const auto threads = std::size_t(std::clamp(jobs > 0 ? jobs : hw, 1, 256));
  std::vector<std::thread> pool;
  for (std::size_t k = 1; k < std::min(threads, count); ++k) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  for (const auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace vt::acq::detail
