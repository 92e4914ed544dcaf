// The desktop's present pacer: the planned display lag follows the slowest recent frame, shrinks
// only by a clear margin, and a stall is shown late instead of delaying every later frame.
#include <catch2/catch.hpp>

#include "modes/present_pacer.hpp"
#include "test_support.hpp"

using vt::app::PresentPacer;

namespace {
using vt::test::kMs;
}

TEST_CASE("The planned lag is the slowest recent frame plus the p90 present time and the margin", "[app][pacing]") {
  PresentPacer pacer;
  for (int i = 0; i < 40; ++i) pacer.observe((i % 4 == 0 ? 30 : 20) * kMs, 1 * kMs);
  CHECK(pacer.plan() == 30 * kMs + 1 * kMs + PresentPacer::kMargin_ns);
  // With the felt side at the plan, the frame is presented at it, less the present call's own time.
  CHECK(pacer.presentAt(100 * kMs, 100 * kMs, pacer.plan()) == 100 * kMs + pacer.plan() - 1 * kMs);
}

TEST_CASE("While the felt side slews to a new plan, each frame is shown at the lag it plays then", "[app][pacing]") {
  PresentPacer pacer;
  for (int i = 0; i < 40; ++i) pacer.observe(20 * kMs, 1 * kMs);
  const std::int64_t plan = pacer.plan();  // 23 ms
  // The felt side still plays 63 ms behind (an earlier, longer plan): it catches up at
  // LeadSlew::kSlew, so a frame of input 0 asked for at 0 is shown at d with d = 63 - 0.1 d.
  const std::int64_t shown = pacer.presentAt(0, 0, 63 * kMs) + 1 * kMs;
  CHECK(shown == Approx(63.0 / 1.1 * kMs).margin(1e3));
  // Slewing up it is shown later than the felt side plays now, never later than the plan.
  const std::int64_t upShown = pacer.presentAt(0, 0, 15 * kMs) + 1 * kMs;
  CHECK(upShown == Approx(15.0 / 0.9 * kMs).margin(1e3));
  CHECK(pacer.presentAt(0, 0, plan - 100'000) + 1 * kMs == plan);
  // At the plan, the felt lag is the plan.
  CHECK(pacer.presentAt(5 * kMs, 0, plan) + 1 * kMs == 5 * kMs + plan);
}

TEST_CASE("A slow frame raises the plan at once, it shrinks back only after the window and by a margin",
          "[app][pacing]") {
  PresentPacer pacer;
  for (int i = 0; i < 40; ++i) pacer.observe(20 * kMs, 1 * kMs);
  const std::int64_t steady = pacer.plan();
  pacer.observe(60 * kMs, 1 * kMs);
  CHECK(pacer.plan() == 60 * kMs + 1 * kMs + PresentPacer::kMargin_ns);
  for (std::size_t i = 0; i + 1 < PresentPacer::kFrames; ++i) pacer.observe(20 * kMs, 1 * kMs);
  CHECK(pacer.plan() > steady);  // the slow frame is still among the last 32
  pacer.observe(20 * kMs, 1 * kMs);
  CHECK(pacer.plan() == steady);
  // A drop within the hysteresis keeps the plan (each change is an offset until slewed in).
  for (std::size_t i = 0; i < PresentPacer::kFrames; ++i) pacer.observe(18 * kMs, 1 * kMs);
  CHECK(pacer.plan() == steady);
}

TEST_CASE("A stall is shown late: the plan never exceeds its ceiling", "[app][pacing]") {
  PresentPacer pacer;
  for (int i = 0; i < 10; ++i) pacer.observe(90 * kMs, 1 * kMs);
  pacer.observe(1000 * kMs, 1 * kMs);  // a 1 s stall (a swapchain rebuilt, the first pipeline)
  CHECK(pacer.plan() == PresentPacer::kMaxPlan_ns);
  for (std::size_t i = 0; i < PresentPacer::kFrames; ++i) pacer.observe(90 * kMs, 1 * kMs);
  CHECK(pacer.plan() == 90 * kMs + 1 * kMs + PresentPacer::kMargin_ns);
}
