#pragma once
// A tiny fork-join loop over independent items (scan lines) on std::threads. Exceptions
// are kept per item and the first in item order is rethrown, so errors do not depend on timing.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <type_traits>
#include <vector>

namespace vt::acq::detail {

/// The number of threads parallelFor(count, jobs, ...) runs on.
inline std::size_t workerCount(std::size_t count, int jobs) {
  const int hw = int(std::max(1u, std::thread::hardware_concurrency()));
  return std::max<std::size_t>(1, std::min(std::size_t(std::clamp(jobs > 0 ? jobs : hw, 1, 256)), count));
}

/// Calls fn(i), or fn(i, worker) with worker in [0, workerCount(count, jobs)) naming the thread
/// (for per-thread storage), for i in [0, count) on up to `jobs` threads (0 = hardware
/// concurrency); done(finished) runs after each item on the worker that finished it.
template <class Fn, class Done>
void parallelFor(std::size_t count, int jobs, Fn&& fn, Done&& done) {
  std::vector<std::exception_ptr> errors(count);
  std::atomic<std::size_t> next{0}, finished{0};
  const auto work = [&](std::size_t worker) {
    for (std::size_t i = next++; i < count; i = next++) {
      try {
        if constexpr (std::is_invocable_v<Fn&, std::size_t, std::size_t>) {
          fn(i, worker);
        } else {
          fn(i);
        }
      } catch (...) {
        errors[i] = std::current_exception();
      }
      done(++finished);
    }
  };
  std::vector<std::thread> pool;
  for (std::size_t k = 1; k < workerCount(count, jobs); ++k) pool.emplace_back(work, k);
  work(0);
  for (auto& t : pool) t.join();
  for (const auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace vt::acq::detail
