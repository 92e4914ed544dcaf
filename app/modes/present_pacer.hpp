#pragma once
// The desktop preview's frame pacing (app/modes/desktop_mode.cpp's render thread).

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

#include "vt/core/time_alignment.hpp"

namespace vt::app {

// Frame pacing with a planned display lag: each frame is presented a fixed time after the input
// it shows was read (once rendered), so the haptic loop, which renders the hand that lag in the
// past, plays at every present exactly the hand the frame shows. The plan is the slowest of the
// recent frames' time to finish rendering plus the 90th percentile of their present time and a
// margin (the present call is made the median present time before the planned moment): a frame
// slower than all of them is shown late (the consistency meter counts it), the others wait.
// Visual latency is spent on consistency; --no-frame-pacing spends it the other way.
// The felt side takes a new plan in slowly (vt/core/time_alignment.hpp: its hand's time never
// jumps); the display can move at once, so each frame is shown at the lag the felt side plays
// when it is shown, not at the plan: a changed plan is never an offset while it is slewed in.
class PresentPacer {
 public:
  static constexpr std::size_t kFrames = 32;
  static constexpr std::int64_t kMargin_ns = 2'000'000;
  static constexpr std::int64_t kShrink_ns = 4'000'000;  // the plan shrinks only by more than this
  // A frame slower than this (a stall, a swapchain rebuilt) is shown late rather than planned
  // for: planning for it held every one of the next 32 frames as long (a 1 s stall at 10 fps
  // slowed the window to 1 frame a second for the rest of the run).
  static constexpr std::int64_t kMaxPlan_ns = 150'000'000;

  /// The planned display lag: from the input's stamp to the end of the present call (with the
  /// window's host present, to the X server's copy of the frame).
  std::int64_t plan() const { return m_plan_ns; }
  /// When to present a frame showing input stamped `input_ns` (once it is rendered), asked at
  /// `now_ns` while the felt side plays the hand `feltLag_ns` in the past and slews that lag
  /// towards the plan (LeadSlew::kSlew): shown when the felt side's lag equals the frame's age.
  std::int64_t presentAt(std::int64_t input_ns, std::int64_t now_ns, std::int64_t feltLag_ns) const {
    // The shown time d solves d = input + lag(d); lag moves by at most kSlew per unit of time,
    // so each step shrinks the error tenfold.
    std::int64_t shown_ns = input_ns + feltLag_ns;
    for (int i = 0; i < 4; ++i) {
      const auto step = std::int64_t(LeadSlew::kSlew * double(std::max<std::int64_t>(0, shown_ns - now_ns)));
      shown_ns = input_ns + feltLag_ns + std::clamp(m_plan_ns - feltLag_ns, -step, step);
    }
    return shown_ns - m_present_ns;
  }
  /// One frame: rendering finished `ready_ns` after its input's stamp; the present call took `present_ns`.
  void observe(std::int64_t ready_ns, std::int64_t present_ns) {
    m_readySamples[m_count % kFrames] = ready_ns;
    m_presentSamples[m_count % kFrames] = present_ns;
    ++m_count;
    const std::int64_t want =
        std::min(slowest(m_readySamples) + percentile(m_presentSamples, 9, 10) + kMargin_ns, kMaxPlan_ns);
    // Late frames raise the plan at once; a shorter plan waits for a clear margin (each change
    // is slewed into the haptic loop, whose texture plays 10 % fast or slow while it is).
    if (want > m_plan_ns || want < m_plan_ns - kShrink_ns) m_plan_ns = want;
    // The present call is made its median time before the display moment: as often early as late.
    m_present_ns = percentile(m_presentSamples, 1, 2);
  }

 private:
  std::int64_t slowest(const std::array<std::int64_t, kFrames>& values) const {
    return *std::max_element(values.begin(), values.begin() + std::ptrdiff_t(std::min(m_count, kFrames)));
  }
  std::int64_t percentile(std::array<std::int64_t, kFrames> values, std::size_t num, std::size_t den) const {
    const std::size_t n = std::min(m_count, kFrames);
    const std::size_t k = n * num / den;
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(k), values.begin() + std::ptrdiff_t(n));
    return values[k];
  }

  std::array<std::int64_t, kFrames> m_readySamples{}, m_presentSamples{};
  std::size_t m_count = 0;
  std::int64_t m_plan_ns = 0, m_present_ns = 0;
};

}  // namespace vt::app
