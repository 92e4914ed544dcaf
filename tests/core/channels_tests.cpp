#include <catch2/catch.hpp>

#include <array>
#include <atomic>
#include <thread>

#include "vt/core/clock.hpp"
#include "vt/core/latest_value.hpp"
#include "vt/core/spsc_ring.hpp"

namespace {
struct Snapshot {
  std::uint64_t id;
  std::array<std::uint64_t, 31> copies;  // all equal to id when the read was not torn
};
}  // namespace

TEST_CASE("LatestValue returns nothing before the first publish, then the newest value") {
  vt::LatestValue<int> channel;
  int out = -1;
  CHECK_FALSE(channel.read(out));
  channel.publish(3);
  channel.publish(7);
  REQUIRE(channel.read(out));
  CHECK(out == 7);
  CHECK(channel.version() == 2);
}

TEST_CASE("LatestValue never yields a torn snapshot under a concurrent writer") {
  vt::LatestValue<Snapshot> channel;
  std::atomic<bool> done{false};
  std::thread writer([&] {
    Snapshot s{};
    for (std::uint64_t i = 1; i <= 200000; ++i) {
      s.id = i;
      s.copies.fill(i);
      channel.publish(s);
    }
    done = true;
  });
  std::uint64_t torn = 0, reads = 0, last = 0, backwards = 0;
  Snapshot s{};
  while (!done.load()) {
    if (!channel.read(s)) continue;
    ++reads;
    for (auto c : s.copies) torn += c != s.id;
    backwards += s.id < last;
    last = s.id;
  }
  writer.join();
  CHECK(torn == 0);
  CHECK(backwards == 0);
  CHECK(reads > 0);
}

TEST_CASE("SpscRing keeps order, refuses pushes when full and counts them") {
  vt::SpscRing<int> ring(3);
  REQUIRE(ring.capacity() == 4);
  for (int i = 0; i < 4; ++i) CHECK(ring.push(i));
  CHECK_FALSE(ring.push(99));
  CHECK(ring.dropped() == 1);
  int v = -1;
  for (int i = 0; i < 4; ++i) {
    REQUIRE(ring.pop(v));
    CHECK(v == i);
  }
  CHECK_FALSE(ring.pop(v));
}

TEST_CASE("SpscRing transfers every item across threads in order") {
  vt::SpscRing<std::uint64_t> ring(64);
  constexpr std::uint64_t kCount = 100000;
  std::thread producer([&] {
    for (std::uint64_t i = 0; i < kCount;) {
      if (ring.push(i)) ++i;
    }
  });
  std::uint64_t expected = 0, v = 0, mismatches = 0;
  while (expected < kCount) {
    if (ring.pop(v)) mismatches += v != expected++;
  }
  producer.join();
  CHECK(mismatches == 0);
}

TEST_CASE("ManualClock only moves when told, sleepUntil jumps to the deadline") {
  vt::ManualClock clock(100);
  CHECK(clock.now_ns() == 100);
  clock.advance(50);
  CHECK(clock.now_ns() == 150);
  clock.sleepUntil(1000);
  CHECK(clock.now_ns() == 1000);
  clock.sleepUntil(500);  // past deadlines do not move time backwards
  CHECK(clock.now_ns() == 1000);
  clock.spinUntil(2000);  // a clock that only moves when told: spinning waits as sleeping does
  CHECK(clock.now_ns() == 2000);
}

TEST_CASE("SteadyClock sleepUntil and spinUntil do not return early") {
  const auto& clock = vt::SteadyClock::instance();
  std::int64_t deadline = clock.now_ns() + 2'000'000;
  clock.sleepUntil(deadline);
  CHECK(clock.now_ns() >= deadline);
  deadline = clock.now_ns() + 2'000'000;
  clock.spinUntil(deadline);
  CHECK(clock.now_ns() >= deadline);
  const std::int64_t before = clock.now_ns();
  clock.spinUntil(before - 1);  // a past deadline returns at once
  CHECK(clock.now_ns() - before < 1'000'000'000);
}
