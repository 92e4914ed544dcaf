#pragma once
// Side-by-side timing for ratios that hold under load: every run times each side's whole
// workload in turn (the order reversed on every other run; each after an untimed pass of its
// own), in thread CPU time, and figures
// are medians over the runs (ratios: the median of the runs' own ratios). And the check that
// two sides answered the same queries alike.
#include <time.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace vt::bench {

/// CPU time of the calling thread: other processes on the cores do not count against a side.
inline double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + double(ts.tv_nsec) * 1e-9;
}

/// The median of `values` (0 when empty).
inline double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// One side's workload and the CPU seconds each run of it took.
struct Side {
  std::string name;
  std::size_t items = 0;           // queries (or builds) per run
  std::function<void()> workload;  // one run: every item once
  // Instead of `workload`: one run that returns the CPU seconds of the part that counts, for
  // work whose setup must stay off the clock (a build, not the freeing of the last one).
  std::function<double()> timedWorkload;
  std::vector<double> seconds;  // per run

  /// Median items per second, in millions.
  double medianMillionsPerSecond() const {
    std::vector<double> rates;
    for (double s : seconds) rates.push_back(s > 0.0 ? double(items) / s / 1e6 : 0.0);
    return median(rates);
  }
  /// Median milliseconds per item (builds).
  double medianMilliseconds() const {
    std::vector<double> ms;
    for (double s : seconds) ms.push_back(s * 1e3 / double(items));
    return median(ms);
  }
};

/// Runs every side's workload `runs` times, interleaved, recording each run's CPU seconds.
/// A `workload` side's timed pass follows an untimed pass of its own: every side is timed with
/// its own data in the caches, whichever side ran before it. (Without that pass, the same ray
/// walk on the 1M-triangle sphere timed 7 - 9 % slower after Embree's side than after one of
/// ours, since a 32 MB L3 holds much of either's working set: position, not code, decided.)
/// `timedWorkload` sides (builds) get no extra pass: a build streams through fresh memory.
inline void runInterleaved(std::vector<Side*> sides, int runs) {
  for (int run = 0; run < runs; ++run) {
    for (std::size_t k = 0; k < sides.size(); ++k) {
      Side& side = *sides[run % 2 ? sides.size() - 1 - k : k];
      if (side.timedWorkload) {
        side.seconds.push_back(side.timedWorkload());
        continue;
      }
      side.workload();
      const double t0 = threadCpuSeconds();
      side.workload();
      side.seconds.push_back(threadCpuSeconds() - t0);
    }
  }
}

/// The median over runs of a's speed over b's (per-run ratios: both timed in the same run).
inline double medianSpeedup(const Side& a, const Side& b) {
  std::vector<double> ratios;
  for (std::size_t i = 0; i < std::min(a.seconds.size(), b.seconds.size()); ++i) {
    ratios.push_back((double(a.items) / a.seconds[i]) / (double(b.items) / b.seconds[i]));
  }
  return median(ratios);
}

/// The median over runs of a's time over b's (builds: below 1 is faster).
inline double medianTimeRatio(const Side& a, const Side& b) { return 1.0 / medianSpeedup(a, b); }

/// The queries whose answers (a nearest distance each, +inf for none) differ: one side found
/// something the other did not, or the distances differ by more than `relative` of the larger.
inline std::vector<std::size_t> differingAnswers(const std::vector<float>& ours, const std::vector<float>& theirs,
                                                 float relative) {
  std::vector<std::size_t> differ;
  for (std::size_t i = 0; i < std::min(ours.size(), theirs.size()); ++i) {
    const float a = ours[i], b = theirs[i];
    const bool same = std::isinf(a) || std::isinf(b) ? a == b : std::abs(a - b) <= relative * std::max(a, b);
    if (!same) differ.push_back(i);
  }
  return differ;
}

}  // namespace vt::bench
