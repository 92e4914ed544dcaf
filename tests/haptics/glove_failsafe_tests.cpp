#include <catch2/catch.hpp>

#include <csignal>

#include "vt/core/clock.hpp"
#include "vt/core/stop.hpp"
#include "vt/haptics/devices/failsafe.hpp"

using namespace vt::haptics;

TEST_CASE("Failsafe watchdog trips when the heartbeat stops and recovers when it moves") {
  vt::ManualClock clock(1'000'000'000);
  Failsafe failsafe(clock, FailsafeConfig{20'000'000});
  CHECK(failsafe.evaluate(1) == FailsafeReason::None);
  clock.advance(20'000'000);
  CHECK(failsafe.evaluate(1) == FailsafeReason::None);  // exactly at the timeout: still fine
  clock.advance(1'000'000);
  CHECK(failsafe.evaluate(1) == FailsafeReason::Stall);
  CHECK(failsafe.lastReason() == FailsafeReason::Stall);
  CHECK(failsafe.evaluate(2) == FailsafeReason::None);
  // A heartbeat that keeps moving never trips, however long it runs.
  for (std::uint64_t beat = 3; beat < 1000; ++beat) {
    clock.advance(5'000'000);
    REQUIRE(failsafe.evaluate(beat) == FailsafeReason::None);
  }
}

TEST_CASE("Failsafe link loss and shutdown silence output") {
  vt::ManualClock clock;
  Failsafe failsafe(clock);
  failsafe.setLinkLost(true);
  CHECK(failsafe.evaluate(1) == FailsafeReason::LinkLost);
  failsafe.setLinkLost(false);
  CHECK(failsafe.evaluate(2) == FailsafeReason::None);
  failsafe.setLinkLost(true);
  failsafe.requestShutdown();  // shutdown wins and stays
  CHECK(failsafe.evaluate(3) == FailsafeReason::Shutdown);
  failsafe.setLinkLost(false);
  CHECK(failsafe.evaluate(4) == FailsafeReason::Shutdown);
  CHECK(failsafeReasonName(FailsafeReason::LinkLost) == "link-lost");
}

TEST_CASE("Failsafe SIGTERM handler only sets a flag") {
  vt::clearStop();
  vt::installStopSignals();
  vt::ManualClock clock;
  Failsafe failsafe(clock);
  CHECK(failsafe.evaluate(1) == FailsafeReason::None);
  REQUIRE(std::raise(SIGTERM) == 0);  // the process survives: the handler only records it
  CHECK(vt::stopSignal() == SIGTERM);
  CHECK(failsafe.evaluate(2) == FailsafeReason::Signal);
  vt::clearStop();
  CHECK(failsafe.evaluate(3) == FailsafeReason::None);
}
