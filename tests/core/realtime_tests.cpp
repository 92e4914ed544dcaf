#include <catch2/catch.hpp>

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <string>
#include <thread>

#include "vt/core/realtime.hpp"

namespace {

/// Asks on a fresh thread (the grant is per thread) and returns what was recorded for it.
vt::ThreadGrant askOnThread(const std::string& name, int priority) {
  std::thread([&] { vt::requestRealtime(name, priority); }).join();
  const auto grants = vt::realtimeGrants();
  const auto it = std::find_if(grants.begin(), grants.end(), [&](const vt::ThreadGrant& g) { return g.thread == name; });
  REQUIRE(it != grants.end());
  return *it;
}

}  // namespace

TEST_CASE("requestRealtime records what the thread got and minimises its timer slack") {
  const vt::ThreadGrant g = askOnThread("realtime test", 5);
  if (g.grant.granted()) {
    CHECK(g.grant.policy != SCHED_OTHER);
    CHECK(g.grant.priority >= 1);
    CHECK(g.grant.timerSlack_ns <= 1);  // the kernel gives real-time threads no slack at all
    CHECK(g.refusal.empty());
  } else {
    CHECK(g.grant.policy == SCHED_OTHER);
    CHECK(g.grant.timerSlack_ns == 1);
    CHECK(g.refusal.find("SCHED_FIFO: ") != std::string::npos);
    CHECK(g.refusal.find("RealtimeKit: ") != std::string::npos);
  }
  CHECK(vt::describeRealtimeGrants().find("realtime test: ") != std::string::npos);
}

TEST_CASE("requestRealtime refuses a priority outside 1..99 and says so") {
  const vt::ThreadGrant g = askOnThread("bad priority", 100);
  CHECK_FALSE(g.grant.granted());
  CHECK(g.grant.policy == SCHED_OTHER);
  CHECK(g.refusal == "priority 100 outside 1..99");
}

// Run by ctest through tests/core/rtkit/rtkit_session.sh (a private system bus, rtkit-daemon and
// an unprivileged user): hidden from the ordinary run, which has neither.
TEST_CASE("RealtimeKit makes an unprivileged thread real-time", "[.rtkit]") {
  REQUIRE(geteuid() != 0);  // root would get SCHED_FIFO directly and never ask RealtimeKit
  const vt::ThreadGrant g = askOnThread("rtkit test", 15);
  INFO(g.refusal);
  REQUIRE(g.grant.method == vt::RealtimeMethod::RealtimeKit);
  CHECK((g.grant.policy == SCHED_RR || g.grant.policy == SCHED_FIFO));
  CHECK(g.grant.priority == 15);  // within rtkit-daemon's default maximum (20)
  CHECK(vt::describeRealtimeGrants().find(" 15 via RealtimeKit") != std::string::npos);
}

TEST_CASE("Without RealtimeKit an unprivileged thread keeps normal scheduling and the reason", "[.no-rtkit]") {
  REQUIRE(geteuid() != 0);
  const vt::ThreadGrant g = askOnThread("refused test", 15);
  CHECK_FALSE(g.grant.granted());
  CHECK(g.refusal.find("SCHED_FIFO: Operation not permitted") != std::string::npos);
  CHECK(g.refusal.find("RealtimeKit: ") != std::string::npos);
  CHECK(g.grant.timerSlack_ns == 1);
}
