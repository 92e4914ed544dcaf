// Each message body decoder on its own: the first byte picks the type, the session's actuator
// count and its frames per codec block (so the fuzzer reaches every body parser without first
// building a header).
#include <cstdint>
#include <span>

#include "vt/net/protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto type = vt::net::MessageType(1 + data[0] % 9);
  vt::net::StreamContext context;
  context.actuatorCount = 1 + (data[0] >> 3) % 10;
  constexpr int kFramesPerBlock[] = {1, 4, 32};
  context.framesPerBlock = kFramesPerBlock[data[0] / 80 % 3];
  context.radius_m.fill(0.008f);
  vt::net::Message message;
  const auto status = vt::net::decodePayload(type, std::span(data + 1, size - 1), context, message);
  if (status == vt::net::DecodeStatus::Ok && vt::net::typeOf(message) != type) __builtin_trap();
  return 0;
}
