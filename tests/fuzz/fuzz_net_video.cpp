// The client's video path: datagrams -> decodeStream -> VideoReassembler -> decodeJpeg.
// Input: a sequence of [u16 little-endian length][datagram] records.
#include <cstdint>
#include <span>

#include "vt/core/error.hpp"
#include "vt/net/protocol.hpp"
#include "vt/net/video_stream.hpp"
#include "vt/scene/jpeg.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  constexpr std::size_t kMaxFrame = 64u << 10;  // smaller than the client's limit: faster, same logic
  vt::net::VideoReassembler reassembler({.maxFrameBytes = kMaxFrame, .framesInFlight = 2});
  vt::net::Packet packet;
  std::size_t at = 0;
  std::uint64_t completions = 0;
  while (at + 2 <= size) {
    const std::size_t length = std::size_t(data[at]) | std::size_t(data[at + 1]) << 8;
    at += 2;
    const std::span<const std::uint8_t> datagram(data + at, std::min(length, size - at));
    at += datagram.size();
    if (vt::net::decodeStream(datagram, vt::net::StreamContext{}, packet) != vt::net::DecodeStatus::Ok) continue;
    const auto* video = std::get_if<vt::net::Video>(&packet.message);
    if (!video || !reassembler.push(*video)) continue;
    ++completions;
    const vt::net::VideoFrame& frame = reassembler.completed();
    if (frame.jpeg.empty() || frame.jpeg.size() > kMaxFrame || frame.width < 1 || frame.height < 1) __builtin_trap();
    try {
      const vt::Image8 image = vt::decodeJpeg(frame.jpeg, "fuzzed video frame");
      if (image.channels != 4 || image.pixels.size() != std::size_t(image.width) * image.height * 4) __builtin_trap();
    } catch (const vt::Error&) {
      // Corrupt frames are rejected with a message: that is the expected outcome.
    }
  }
  if (reassembler.stats().completed != completions) __builtin_trap();
  return 0;
}
