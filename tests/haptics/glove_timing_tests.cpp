// The glove's documented goals (docs/PERFORMANCE.md "Glove"): every actuator silent within 50 ms
// of a stop, a signal or a stalled haptic thread, and levels reports at 1 kHz. The driver runs on
// a SteppedClock: the test plays its ticks one by one and reads times off the simulated clock, so
// the assertions hold the driver's logic to the goals exactly, at any load. Real-time figures for
// the same paths: `vt_bench glove` (bench/glove_bench.cpp).
#include <catch2/catch.hpp>

#include <cmath>
#include <csignal>
#include <memory>
#include <thread>

#include "glove_rig.hpp"
#include "stepped_clock.hpp"
#include "test_support.hpp"
#include "vt/core/stop.hpp"

using namespace vt::haptics;
using namespace vt::haptics::glove;
using namespace vt::haptics::glove::test;

namespace {

using vt::test::kMs;
constexpr std::int64_t kSilenceGoal_ns = 50 * kMs;

struct SteppedRig : SimRig {
  vt::test::SteppedClock clock{1'000'000'000};
  std::unique_ptr<GloveDriver> driver;

  SteppedRig() {
    driver = std::make_unique<GloveDriver>(backend, config(), clock);
    // Until connected, the reader thread sleeps on the clock too; once it reads the device it does
    // not, so from then on every sleep is the writer's end of a tick.
    const std::int64_t start = clock.now_ns();
    const bool settled = vt::test::eventually([&] {
      if (driver->status().connected && clock.sleepers() == 1 && clock.now_ns() >= start + 10 * kMs &&
          clock.nextDeadline() > clock.now_ns()) {
        return true;
      }
      clock.advanceTo(clock.now_ns() + kMs);
      return false;
    });
    REQUIRE(settled);
  }
  ~SteppedRig() {
    clock.runFree();  // the threads finish on their own from here
    driver.reset();
  }
  /// Plays the writer's next tick: time moves to its deadline, and the tick runs until it sleeps.
  void tick() {
    const std::uint64_t sleeps = clock.sleeps();
    clock.advanceTo(clock.nextDeadline());
    REQUIRE(clock.waitForSleepsAbove(sleeps));
  }
  /// Ticks (at most 1 s of simulated time) until the glove is silent; the simulated time taken.
  std::int64_t ticksToSilence() {
    const std::int64_t start = clock.now_ns();
    while (!allZero(glove) && clock.now_ns() - start < 1000 * kMs) tick();
    return clock.now_ns() - start;
  }
  /// Drives the index actuator at `level` with a beating heartbeat until the glove shows it.
  void drive(float level) {
    driver->submit(frameWith(level, 1));
    for (int i = 0; i < 100 && std::abs(indexLevel(glove) - level) > 1e-3f; ++i) {
      beat.fetch_add(1);
      tick();
    }
    REQUIRE(indexLevel(glove) == Approx(level).margin(1e-3));
  }
};

}  // namespace

TEST_CASE("Glove driver sends one levels report per 1 ms tick: 1 kHz in simulated time") {
  SteppedRig rig;
  const std::uint64_t sentBefore = rig.driver->status().reportsSent;
  const std::int64_t start = rig.clock.now_ns();
  constexpr int kTicks = 2000;
  for (int i = 1; i <= kTicks; ++i) {
    // A new frame every tick, as the 1 kHz haptic loop publishes them.
    rig.driver->submit(frameWith(float(i % 100 + 1) / 128.0f, std::uint64_t(i)));
    rig.beat.fetch_add(1);
    rig.tick();
  }
  const GloveStatus status = rig.driver->status();
  CHECK(rig.clock.now_ns() - start == kTicks * kMs);  // the writer's period is 1 ms
  CHECK(status.reportsSent - sentBefore == kTicks);   // and every tick sent its frame
  CHECK(status.framesDropped == 0);
  CHECK(status.sendRate_hz == Approx(1000.0).margin(1.0));  // the driver's own figure agrees
  CHECK(rig.glove.stats().accepted() == status.reportsSent);
  CHECK(rig.glove.stats().rejected() == 0);
}

TEST_CASE("Glove driver silences a stalled haptic thread within 50 ms in simulated time") {
  SteppedRig rig;
  rig.drive(0.6f);
  // The heartbeat stops: silence must come after the stall timeout (20 ms), within the goal.
  const std::int64_t toSilence = rig.ticksToSilence();
  CHECK(toSilence > GloveDriverConfig{}.failsafe.stallTimeout_ns);
  CHECK(toSilence <= kSilenceGoal_ns);
  CHECK(rig.driver->status().failsafe == FailsafeReason::Stall);
  CHECK_FALSE(rig.glove.silenced());  // zeros were sent, not left to the device's keep-alive
}

TEST_CASE("Glove driver silences on SIGINT within 50 ms in simulated time") {
  SteppedRig rig;
  vt::clearStop();
  vt::installStopSignals();
  rig.drive(0.8f);
  REQUIRE(std::raise(SIGINT) == 0);
  rig.beat.fetch_add(1);  // the haptic thread still beats: the signal alone must silence
  CHECK(rig.ticksToSilence() <= kSilenceGoal_ns);
  CHECK(rig.driver->status().failsafe == FailsafeReason::Signal);
  vt::clearStop();
}

TEST_CASE("Glove driver stop() leaves the glove silent within 50 ms in simulated time") {
  SteppedRig rig;
  rig.drive(1.0f);
  const std::int64_t start = rig.clock.now_ns();
  std::thread stopper([&] { rig.driver->stop(); });
  // The writer's last tick sends zeros and ends the thread, so step time without waiting for it
  // to sleep again.
  REQUIRE(vt::test::eventually([&] {
    if (allZero(rig.glove)) return true;
    if (rig.clock.sleepers() > 0) rig.clock.advanceTo(rig.clock.nextDeadline());
    return false;
  }));
  CHECK(rig.clock.now_ns() - start <= kSilenceGoal_ns);
  rig.clock.runFree();
  stopper.join();
  CHECK_FALSE(rig.glove.silenced());
}
