#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <vector>

#include "vt/net/protocol.hpp"
#include "vt/net/video_stream.hpp"

using namespace vt::net;

namespace {

std::vector<std::uint8_t> randomBytes(std::size_t size, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::uint8_t> bytes(size);
  for (auto& b : bytes) b = std::uint8_t(rng());
  return bytes;
}

std::vector<Video> fragments(const std::vector<std::uint8_t>& jpeg, std::uint32_t frameId, int w = 480, int h = 480) {
  std::vector<Video> out;
  REQUIRE(fragmentVideoFrame(jpeg, frameId, w, h, [&](const Video& v) { out.push_back(v); }));
  return out;
}

}  // namespace

TEST_CASE("A video frame survives fragmentation, the wire and reassembly") {
  const auto jpeg = randomBytes(5000, 1);
  const auto parts = fragments(jpeg, 42);
  REQUIRE(parts.size() == 4);
  CHECK(videoFragmentCount(5000) == 4);
  VideoReassembler reassembler;
  int completions = 0;
  for (const Video& part : parts) {
    std::array<std::uint8_t, kMaxDatagram> datagram{};
    const std::size_t size = encodeStream(part, 1, StreamContext{}, Direction::ServerToClient, datagram);
    REQUIRE(size > 0);
    REQUIRE(size <= kMaxDatagram);
    Packet packet;
    REQUIRE(decodeStream(std::span(datagram.data(), size), StreamContext{}, packet) == DecodeStatus::Ok);
    completions += reassembler.push(std::get<Video>(packet.message));
  }
  CHECK(completions == 1);
  CHECK(reassembler.completed().frameId == 42);
  CHECK(reassembler.completed().width == 480);
  CHECK(reassembler.completed().jpeg == jpeg);
  CHECK(reassembler.stats().completed == 1);
  CHECK(reassembler.stats().rejected == 0);
}

TEST_CASE("Fragments in any order rebuild the frame") {
  const auto jpeg = randomBytes(20000, 2);
  auto parts = fragments(jpeg, 7);
  std::shuffle(parts.begin(), parts.end(), std::mt19937(3));
  VideoReassembler reassembler;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) CHECK_FALSE(reassembler.push(parts[i]));
  REQUIRE(reassembler.push(parts.back()));
  CHECK(reassembler.completed().jpeg == jpeg);
}

TEST_CASE("Two interleaved frames both complete when the older finishes first") {
  const auto a = randomBytes(5000, 4), b = randomBytes(3000, 5);
  const auto pa = fragments(a, 10), pb = fragments(b, 11);
  VideoReassembler reassembler;
  CHECK_FALSE(reassembler.push(pb[0]));
  CHECK_FALSE(reassembler.push(pa[0]));
  CHECK_FALSE(reassembler.push(pb[1]));
  CHECK_FALSE(reassembler.push(pa[1]));
  CHECK_FALSE(reassembler.push(pa[2]));
  REQUIRE(reassembler.push(pa[3]));
  CHECK(reassembler.completed().jpeg == a);
  REQUIRE(reassembler.push(pb[2]));
  CHECK(reassembler.completed().jpeg == b);
  CHECK(reassembler.stats().completed == 2);
  CHECK(reassembler.stats().abandoned == 0);
}

TEST_CASE("A lost fragment costs only its own frame") {
  VideoReassembler reassembler;
  std::vector<std::uint32_t> shown;
  for (std::uint32_t id = 1; id <= 5; ++id) {
    const auto parts = fragments(randomBytes(6000, id), id);
    for (std::size_t i = 0; i < parts.size(); ++i) {
      if (id == 3 && i == 2) continue;  // lost
      if (reassembler.push(parts[i])) shown.push_back(reassembler.completed().frameId);
    }
  }
  CHECK(shown == std::vector<std::uint32_t>{1, 2, 4, 5});
  CHECK(reassembler.stats().completed == 4);
  CHECK(reassembler.stats().abandoned == 1);
  CHECK(reassembler.stats().rejected == 0);
}

TEST_CASE("Inconsistent, duplicate, stale and oversized fragments are rejected and counted") {
  VideoReassembler reassembler({.maxFrameBytes = 10000, .framesInFlight = 2});
  const auto parts = fragments(randomBytes(4000, 6), 20);
  REQUIRE_FALSE(reassembler.push(parts[0]));
  CHECK_FALSE(reassembler.push(parts[0]));  // duplicate
  Video resized = parts[1];
  resized.width = 640;
  CHECK_FALSE(reassembler.push(resized));
  Video recounted = parts[1];
  recounted.fragmentCount = 5;
  CHECK_FALSE(reassembler.push(recounted));
  Video shortMiddle = parts[1];
  shortMiddle.dataSize = 100;  // only the last fragment may be short
  CHECK_FALSE(reassembler.push(shortMiddle));
  CHECK(reassembler.stats().rejected == 4);

  Video huge = parts[0];
  huge.frameId = 21;
  huge.fragmentCount = 9;  // at least 8 x 1340 + 1 bytes > 10000
  CHECK_FALSE(reassembler.push(huge));
  CHECK(reassembler.stats().rejected == 5);

  for (std::size_t i = 1; i < parts.size() - 1; ++i) CHECK_FALSE(reassembler.push(parts[i]));
  REQUIRE(reassembler.push(parts.back()));
  CHECK(reassembler.completed().jpeg.size() == 4000);
  const auto old = fragments(randomBytes(2000, 7), 19);
  CHECK_FALSE(reassembler.push(old[0]));  // older than a frame already shown
  CHECK_FALSE(reassembler.push(parts[1]));  // a late copy of the shown frame
  CHECK(reassembler.stats().rejected == 7);
  CHECK(reassembler.stats().completed == 1);
}

TEST_CASE("Frames in flight are bounded: a newer frame evicts the oldest incomplete one") {
  VideoReassembler reassembler({.maxFrameBytes = kMaxVideoFrameBytes, .framesInFlight = 2});
  const auto p1 = fragments(randomBytes(3000, 8), 1), p2 = fragments(randomBytes(3000, 9), 2),
             p3 = fragments(randomBytes(3000, 10), 3);
  reassembler.push(p1[0]);
  reassembler.push(p2[0]);
  reassembler.push(p3[0]);  // evicts frame 1
  CHECK(reassembler.stats().abandoned == 1);
  CHECK_FALSE(reassembler.push(p1[1]));  // older than everything in flight: no slot
  CHECK(reassembler.stats().rejected == 1);
  reassembler.push(p3[1]);
  REQUIRE(reassembler.push(p3[2]));
  CHECK(reassembler.stats().abandoned == 2);  // frame 2 is now stale
  CHECK(reassembler.completed().frameId == 3);
}

TEST_CASE("Frame ids wrap around") {
  VideoReassembler reassembler;
  for (std::uint32_t id : {0xFFFFFFFEu, 0xFFFFFFFFu, 0u, 1u}) {
    const auto parts = fragments(randomBytes(1500, id), id);
    bool done = false;
    for (const Video& v : parts) done = reassembler.push(v);
    CHECK(done);
  }
  CHECK(reassembler.stats().completed == 4);
}

TEST_CASE("fragmentVideoFrame refuses empty and oversized frames") {
  const auto none = [](const Video&) { FAIL("nothing should be emitted"); };
  CHECK_FALSE(fragmentVideoFrame({}, 1, 480, 480, none));
  const std::vector<std::uint8_t> big(kMaxVideoFrameBytes + 1, 1);
  CHECK_FALSE(fragmentVideoFrame(big, 1, 480, 480, none));
  CHECK_FALSE(fragmentVideoFrame(randomBytes(100, 1), 1, 0, 480, none));
  const std::vector<std::uint8_t> largest(kMaxVideoFrameBytes, 1);
  VideoReassembler reassembler;
  bool done = false;
  CHECK(fragmentVideoFrame(largest, 1, 480, 480, [&](const Video& v) { done = reassembler.push(v); }));
  CHECK(done);
  CHECK(reassembler.completed().jpeg == largest);
}

TEST_CASE("LatestVideoFrame hands over only newer frames") {
  LatestVideoFrame latest;
  VideoFrame out;
  std::uint64_t version = 0;
  CHECK_FALSE(latest.readNewer(out, version));
  VideoFrame frame{5, 480, 480, {1, 2, 3}};
  latest.publish(frame);
  REQUIRE(latest.readNewer(out, version));
  CHECK(out.frameId == 5);
  CHECK(out.jpeg == std::vector<std::uint8_t>{1, 2, 3});
  CHECK(version == 1);
  CHECK_FALSE(latest.readNewer(out, version));
}
