// The desktop's present pacer: the planned display lag follows the slowest recent frame, shrinks
// only by a clear margin, and a stall is shown late instead of delaying every later frame.
#include <catch2/catch.hpp>

#include "modes/present_pacer.hpp"

using vt::app::PresentPacer;

namespace {
constexpr std::int64_t kMs = 1'000'000;
}

TEST_CASE("The planned lag is the slowest recent frame plus the p90 present time and the margin", "[app][pacing]") {
  PresentPacer pacer;
  for (int i = 0; i < 40; ++i) pacer.observe((i % 4 == 0 ? 30 : 20) * kMs, 1 * kMs);
  CHECK(pacer.plan() == 30 * kMs + 1 * kMs + PresentPacer::kMargin_ns);
  // The frame is presented at the plan, less the present call's own time.
  CHECK(pacer.presentAt(100 * kMs) == 100 * kMs + pacer.plan() - 1 * kMs);
}

TEST_CASE("A slow frame raises the plan at once; it shrinks back only after the window and by a margin",
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
