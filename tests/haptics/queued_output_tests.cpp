#include <catch2/catch.hpp>

#include <atomic>
#include <cstdint>
#include <string>

#include "vt/core/clock.hpp"
#include "vt/haptics/devices/queued_output.hpp"

using namespace vt;
using namespace vt::haptics;

namespace {

// The smallest output: its writer pops frames, reports the heartbeat it sees and an error, and
// ends when stopped.
class ProbeOutput final : public QueuedOutput {
 public:
  explicit ProbeOutput(const std::atomic<std::uint64_t>* heartbeat)
      : QueuedOutput(SteadyClock::instance(), {}, heartbeat, 16) {
    startWriter("probe output");
  }
  ~ProbeOutput() override { stop(); }

  std::string name() const override { return "probe"; }
  std::int64_t latency_ns() const override { return 0; }
  std::string statusLine() const override { return lastError(); }

  std::atomic<std::uint64_t> popped{0}, lastHeartbeat{0};
  std::atomic<bool> sawStop{false};

 private:
  void writerLoop() noexcept override {
    ActuatorFrame frame;
    std::uint64_t count = 0;
    while (true) {
      const bool ending = stopping();
      while (m_queue.pop(frame)) ++count;
      popped.store(count);
      lastHeartbeat.store(heartbeat(count));
      if (count > 0) setLastError("popped", std::to_string(count));
      if (ending) break;
      m_clock.sleepUntil(m_clock.now_ns() + 200'000);
    }
    sawStop.store(true);
  }
};

template <class Done>
bool waitFor(Done done) {
  const std::int64_t end = SteadyClock::instance().now_ns() + 2'000'000'000;
  while (!done()) {
    if (SteadyClock::instance().now_ns() > end) return false;
    SteadyClock::instance().sleepUntil(SteadyClock::instance().now_ns() + 1'000'000);
  }
  return true;
}

}  // namespace

TEST_CASE("QueuedOutput runs its writer on the queue, counts popped frames as the heartbeat without a tick counter, and stop() ends it") {
  ProbeOutput out(nullptr);
  CHECK(out.thread() == SinkThread::Realtime);
  CHECK(out.statusLine().empty());
  for (int i = 0; i < 3; ++i) REQUIRE(out.queue().push(ActuatorFrame::silent(5, i)));
  REQUIRE(waitFor([&] { return out.popped.load() == 3; }));
  REQUIRE(waitFor([&] { return out.lastHeartbeat.load() == 3; }));
  REQUIRE(waitFor([&] { return out.statusLine() == "popped: 3"; }));
  out.stop();
  CHECK(out.sawStop.load());
  CHECK(out.failsafe().evaluate(3) == FailsafeReason::Shutdown);
  out.stop();  // idempotent
}

TEST_CASE("QueuedOutput takes the haptic loop's tick counter as the heartbeat when given one") {
  std::atomic<std::uint64_t> ticks{41};
  ProbeOutput out(&ticks);
  REQUIRE(waitFor([&] { return out.lastHeartbeat.load() == 41; }));
  ticks.store(42);
  REQUIRE(waitFor([&] { return out.lastHeartbeat.load() == 42; }));
  CHECK(out.popped.load() == 0);
}
