#include <catch2/catch.hpp>

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/net/transport.hpp"
#include "test_support.hpp"

using namespace vt::net;

namespace {

std::int64_t now() { return vt::SteadyClock::instance().now_ns(); }

/// Sends `count` numbered datagrams and collects what arrives (bounded wait).
std::vector<std::uint32_t> exchange(Transport& receiver, int count) {
  Transport sender(parseEndpoint("127.0.0.1:0"));
  for (std::uint32_t i = 0; i < std::uint32_t(count); ++i) {
    const std::array<std::uint8_t, 4> bytes{std::uint8_t(i), std::uint8_t(i >> 8), 0, 0};
    REQUIRE(sender.send(bytes, receiver.localEndpoint()));
  }
  std::vector<std::uint32_t> got;
  std::array<std::uint8_t, kMaxDatagram + 1> buffer{};
  Endpoint from;
  const std::int64_t end = now() + 2'000'000'000;
  while (int(got.size()) < count && now() < end) {
    const std::size_t n = receiver.receive(buffer, from, std::min(end, now() + 200'000'000));
    if (n == 0) break;  // 200 ms of silence: everything that survived has arrived
    REQUIRE(n == 4);
    CHECK(from == sender.localEndpoint());
    got.push_back(std::uint32_t(buffer[0] | (buffer[1] << 8)));
  }
  return got;
}

}  // namespace

TEST_CASE("Endpoints parse and print and bad ones are named in the error") {
  const Endpoint e = parseEndpoint("127.0.0.1:47800");
  CHECK(e == Endpoint::ipv4(0x7F000001, 47800));
  CHECK(e.isIpv4());
  CHECK(e.isLoopback());
  CHECK(toString(e) == "127.0.0.1:47800");
  CHECK_THROWS_WITH(parseEndpoint("localhost", "--bind"), Catch::Contains("--bind") && Catch::Contains("HOST:PORT"));
  CHECK_THROWS_AS(parseEndpoint("127.0.0.1:70000"), vt::Error);
  CHECK_THROWS_AS(parseEndpoint("127.0.0.1:"), vt::Error);
  CHECK_THROWS_WITH(parseEndpoint(":47800", "--connect"), Catch::Contains("no host"));
  CHECK_THROWS_WITH(parseEndpoint("::1:47800", "--connect"), Catch::Contains("in brackets ([::1]:47800)"));
  CHECK_THROWS_WITH(parseEndpoint("[1.2.3.4]:1", "--connect"), Catch::Contains("'1.2.3.4' is not an IPv6 address"));
  CHECK_THROWS_WITH(parseEndpoint("no-such-host.invalid:1", "--connect"),
                    Catch::Contains("--connect 'no-such-host.invalid:1': cannot resolve 'no-such-host.invalid'"));
}

TEST_CASE("Host names resolve (IPv4 first, as the server binds) and IPv6 addresses parse, print and count as loopback") {
  const Endpoint local = parseEndpoint("localhost:47800", "--connect");
  CHECK(local == Endpoint::ipv4(0x7F000001, 47800));
  const Endpoint v6 = parseEndpoint("[::1]:47800");
  CHECK_FALSE(v6.isIpv4());
  CHECK(v6.isLoopback());
  CHECK(toString(v6) == "[::1]:47800");
  CHECK(toString(parseEndpoint("[2001:db8::7]:9")) == "[2001:db8::7]:9");
  CHECK_FALSE(parseEndpoint("[2001:db8::7]:9").isLoopback());
  CHECK(parseEndpoint("[::ffff:127.0.0.2]:1") == Endpoint::ipv4(0x7F000002, 1));  // mapped: the IPv4 address
  CHECK(parseEndpoint("127.1.2.3:1").isLoopback());
  CHECK_FALSE(parseEndpoint("0.0.0.0:1").isLoopback());
  CHECK_FALSE(parseEndpoint("[::]:1").isLoopback());
  // A client binds its server's family: loopback for a local server, any address otherwise.
  CHECK(localEndpointFor(local) == Endpoint::ipv4(0x7F000001, 0));
  CHECK(localEndpointFor(parseEndpoint("10.77.0.1:1")) == Endpoint::ipv4(0, 0));
  CHECK(toString(localEndpointFor(v6)) == "[::1]:0");
  CHECK(toString(localEndpointFor(parseEndpoint("[2001:db8::7]:9"))) == "[::]:0");
}

TEST_CASE("UDP over IPv6 loopback delivers and reports the sender, and an IPv4 socket cannot send to IPv6") {
  std::unique_ptr<Transport> receiver;
  try {
    receiver = std::make_unique<Transport>(parseEndpoint("[::1]:0"));
  } catch (const vt::Error& e) {
    VT_SKIP(std::string("no IPv6 loopback here: ") + e.what());
  }
  Transport sender(parseEndpoint("[::1]:0"));
  const std::array<std::uint8_t, 3> bytes{1, 2, 3};
  REQUIRE(sender.send(bytes, receiver->localEndpoint()));
  std::array<std::uint8_t, kMaxDatagram + 1> buffer{};
  Endpoint from;
  REQUIRE(receiver->receive(buffer, from, now() + 1'000'000'000) == 3);
  CHECK(from == sender.localEndpoint());
  Transport v4(parseEndpoint("127.0.0.1:0"));
  CHECK_FALSE(v4.send(bytes, receiver->localEndpoint()));
  CHECK(v4.stats().sendFailures == 1);
}

TEST_CASE("Loopback UDP delivers datagrams in order and reports oversized ones") {
  Transport receiver(parseEndpoint("127.0.0.1:0"));
  CHECK(receiver.localEndpoint().port != 0);
  const auto got = exchange(receiver, 100);
  REQUIRE(got.size() == 100);
  for (std::uint32_t i = 0; i < 100; ++i) CHECK(got[i] == i);

  Transport sender(parseEndpoint("127.0.0.1:0"));
  std::vector<std::uint8_t> big(kMaxDatagram + 200, 0xAB);
  REQUIRE(sender.send(big, receiver.localEndpoint()));
  std::array<std::uint8_t, kMaxDatagram + 1> buffer{};
  Endpoint from;
  CHECK(receiver.receive(buffer, from, now() + 1'000'000'000) == big.size());
  // Nothing more: the receive times out at its deadline.
  const std::int64_t start = now();
  CHECK(receiver.receive(buffer, from, start + 20'000'000) == 0);
  CHECK(now() - start >= 19'000'000);
}

TEST_CASE("The impairment layer drops delays and reorders deterministically") {
  Impairment impairment;
  impairment.loss = 0.2;
  impairment.jitter_ns = 1'000'000;
  impairment.reorder = 0.1;
  impairment.seed = 42;
  Transport receiver(parseEndpoint("127.0.0.1:0"), impairment);
  const std::int64_t start = now();
  const auto got = exchange(receiver, 150);
  // 20 % loss of 150: a generous band around 30 drops.
  CHECK(got.size() >= 100);
  CHECK(got.size() <= 140);
  CHECK(receiver.stats().impairedDrops == 150 - got.size());
  int inversions = 0;
  for (std::size_t i = 1; i < got.size(); ++i) inversions += got[i] < got[i - 1] ? 1 : 0;
  CHECK(inversions > 0);
  CHECK(now() - start >= 1'000'000);  // delays were applied
}
