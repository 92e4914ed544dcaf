#include <catch2/catch.hpp>

#include <array>
#include <vector>

#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/net/transport.hpp"

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
  CHECK(e.address == 0x7F000001);
  CHECK(e.port == 47800);
  CHECK(toString(e) == "127.0.0.1:47800");
  CHECK_THROWS_WITH(parseEndpoint("localhost", "--bind"), Catch::Contains("--bind") && Catch::Contains("ADDR:PORT"));
  CHECK_THROWS_AS(parseEndpoint("127.0.0.1:70000"), vt::Error);
  CHECK_THROWS_AS(parseEndpoint("127.0.0.x:1"), vt::Error);
  CHECK_THROWS_AS(parseEndpoint("127.0.0.1:"), vt::Error);
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
