#pragma once
// What the network tests share: one haptic block's period and a loopback endpoint on a free port.
#include <cstdint>

#include "vt/net/transport.hpp"

inline constexpr std::int64_t kPeriod = 4'000'000;  // one block: 32 samples at 8 kHz
inline const vt::net::Endpoint kAnyPort = vt::net::parseEndpoint("127.0.0.1:0");
