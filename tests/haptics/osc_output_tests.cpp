#include <catch2/catch.hpp>

#include <lo/lo.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "vt/core/error.hpp"
#include "vt/haptics/devices/osc_output.hpp"

using namespace vt;
using namespace vt::haptics;

namespace {

template <typename T>
T argumentAs(const lo_arg* argument) {
  T value;
  std::memcpy(&value, argument, sizeof value);
  return value;
}

/// A loopback OSC receiver on a free port, keeping every message's float arguments by path.
struct Receiver {
  lo_server server = lo_server_new_with_proto(nullptr, LO_UDP, nullptr);
  std::map<std::string, std::vector<std::vector<float>>> messages;
  std::map<std::string, std::vector<int>> rates;
  Receiver() {
    REQUIRE(server);
    lo_server_add_method(server, nullptr, nullptr, &Receiver::handle, this);
  }
  ~Receiver() { lo_server_free(server); }
  int port() const { return lo_server_get_port(server); }
  void drain() {
    while (lo_server_recv_noblock(server, 0) > 0) {}
  }
  static int handle(const char* path, const char* types, lo_arg** argv, int argc, lo_message, void* self) {
    auto& r = *static_cast<Receiver*>(self);
    std::vector<float> values;
    for (int i = 0; i < argc; ++i) {
      // OSC aligns arguments to 4 bytes but lo_arg is an 8-byte union: copy, never dereference.
      if (types[i] == 'f') values.push_back(argumentAs<float>(argv[i]));
      if (types[i] == 'i') r.rates[path].push_back(argumentAs<std::int32_t>(argv[i]));
    }
    r.messages[path].push_back(std::move(values));
    return 0;
  }
};

ActuatorFrame frameWithLevels(float index, std::uint64_t sequence) {
  ActuatorFrame frame;
  frame.sequence = sequence;
  frame.actuatorCount = 5;
  frame.blockLength = 8;
  frame.sampleRate_hz = 8000;
  frame.intensity[1] = index;
  frame.frequency_hz[1] = 180.0f;
  for (int i = 0; i < 8; ++i) frame.block[1][std::size_t(i)] = float(i) / 8.0f - float(sequence % 2);
  return frame;
}

}  // namespace

TEST_CASE("parseOscUrl reads host, port and ?blocks, and names what is wrong") {
  const OscOutputConfig a = parseOscUrl("osc://127.0.0.1:9000");
  CHECK(a.host == "127.0.0.1");
  CHECK(a.port == "9000");
  CHECK_FALSE(a.blocks);
  const OscOutputConfig b = parseOscUrl("osc://[::1]:57120?blocks");
  CHECK(b.host == "::1");
  CHECK(b.port == "57120");
  CHECK(b.blocks);
  CHECK_THROWS_WITH(parseOscUrl("udp://x:1"), Catch::Contains("expected osc://HOST:PORT"));
  CHECK_THROWS_WITH(parseOscUrl("osc://host:99999"), Catch::Contains("port '99999' is not 1..65535"));
  CHECK_THROWS_WITH(parseOscUrl("osc://host:1?loud"), Catch::Contains("unknown option 'loud'"));
}

TEST_CASE("OscOutput sends levels, frequencies and blocks to a loopback receiver, then zero levels") {
  Receiver receiver;
  OscOutputConfig config = parseOscUrl(str("osc://127.0.0.1:", receiver.port(), "?blocks"));
  config.levelRate_hz = 1000;
  config.failsafe.stallTimeout_ns = 500'000'000;
  OscOutput output(config);
  for (std::uint64_t s = 1; s <= 20; ++s) {
    REQUIRE(output.queue().push(frameWithLevels(0.75f, s)));
    SteadyClock::instance().sleepUntil(SteadyClock::instance().now_ns() + 1'000'000);
    receiver.drain();
  }
  REQUIRE(vt::test::eventually([&] {
    receiver.drain();
    return receiver.messages["/vtouching/block/index"].size() == 20;
  }));
  output.stop();
  REQUIRE(vt::test::eventually([&] {
    receiver.drain();
    return !receiver.messages["/vtouching/levels"].empty() && receiver.messages["/vtouching/levels"].back()[1] == 0.0f;
  }));
  const auto& levels = receiver.messages["/vtouching/levels"];
  REQUIRE(levels.size() >= 2);
  CHECK(levels.front().size() == 5);
  // The last driven level, then only silence (the stall failsafe may silence the output before
  // stop() does, when the receiver's waits above outlast its timeout on a slow sanitized run).
  const auto lastDriven = std::find_if(levels.rbegin(), levels.rend(), [](const auto& l) { return l[1] != 0.0f; });
  REQUIRE(lastDriven != levels.rend());
  CHECK((*lastDriven)[1] == 0.75f);
  CHECK(receiver.messages["/vtouching/frequencies"].front()[1] == 180.0f);
  const auto& index = receiver.messages["/vtouching/actuator/index"];
  REQUIRE(!index.empty());
  CHECK(index.front() == std::vector<float>{0.75f, 180.0f});
  CHECK(index.back() == std::vector<float>{0.0f, 0.0f});
  const auto& blocks = receiver.messages["/vtouching/block/index"];
  CHECK(blocks[0] == std::vector<float>{-1.0f, -0.875f, -0.75f, -0.625f, -0.5f, -0.375f, -0.25f, -0.125f});  // sequence 1
  CHECK(blocks[1][3] == 0.375f);                                                                            // sequence 2
  CHECK(receiver.rates["/vtouching/block/index"].front() == 8000);
  CHECK(receiver.messages.count("/vtouching/block/thumb") == 1);
  const OscOutputStatus s = output.status();
  CHECK(s.sendErrors == 0);
  CHECK(s.messagesSent >= 20 * 5 + 2 * (2 + 5));
}

TEST_CASE("OscOutput sends zero levels when the loop stalls, before it is stopped") {
  Receiver receiver;
  OscOutputConfig config = parseOscUrl(str("osc://127.0.0.1:", receiver.port()));
  config.levelRate_hz = 1000;
  config.failsafe.stallTimeout_ns = 30'000'000;
  OscOutput output(config);
  REQUIRE(output.queue().push(frameWithLevels(0.5f, 1)));
  // No more frames: within the stall timeout plus a level period the listener hears zeros.
  REQUIRE(vt::test::eventually([&] {
    receiver.drain();
    const auto& levels = receiver.messages["/vtouching/levels"];
    return levels.size() >= 2 && levels.front()[1] == 0.5f && levels.back()[1] == 0.0f;
  }));
  CHECK(output.status().failsafe == FailsafeReason::Stall);
  const std::size_t before = receiver.messages["/vtouching/levels"].size();
  SteadyClock::instance().sleepUntil(SteadyClock::instance().now_ns() + 50'000'000);
  receiver.drain();
  CHECK(receiver.messages["/vtouching/levels"].size() == before);  // zeros once per hold, not a stream
}

// Linux refuses a UDP datagram to port 0 (EINVAL) on every send: a target whose sends all fail,
// as a vanished network route would make them.
TEST_CASE("OscOutput counts failed sends and names their cause in its status, and still stops") {
  OscOutputConfig config;
  config.host = "127.0.0.1";
  config.port = "0";
  config.levelRate_hz = 1000;
  OscOutput output(config);
  for (std::uint64_t i = 0; i < 20; ++i) REQUIRE(output.queue().push(frameWithLevels(0.5f, i)));
  REQUIRE(vt::test::eventually([&] { return output.status().sendErrors >= 7; }));  // one levels period
  output.stop();
  const OscOutputStatus s = output.status();
  CHECK(s.messagesSent == 0);
  CHECK(s.lastError == "send failed: Invalid argument");
  CHECK_THAT(output.statusLine(), Catch::StartsWith("osc://127.0.0.1:0 0 messages, ") &&
                                      Catch::EndsWith(" errors, send failed: Invalid argument"));
}
