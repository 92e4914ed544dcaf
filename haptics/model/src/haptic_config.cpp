#include "vt/haptics/haptic_config.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "vt/core/error.hpp"

namespace vt::haptics {

float ResponseCurve::apply(float level) const noexcept {
  if (!(level > 0.0f)) return 0.0f;
  const float shaped = gamma == 1.0f ? level : std::pow(std::min(level, 1.0f), gamma);
  return std::min(1.0f, floor + (1.0f - floor) * shaped);
}

HapticConfig HapticConfig::fiveFingertips() {
  HapticConfig config;
  for (int f = 0; f < kFingerCount; ++f) {
    config.contacts.push_back({kFingertips[std::size_t(f)]});
    config.routes.push_back({f, ActuatorId(f)});  // Thumb..Little share the finger order
  }
  return config;
}

HapticConfig HapticConfig::vTouching() {
  HapticConfig config;
  const Finger fingers[] = {Finger::Index, Finger::Middle, Finger::Ring};
  for (int i = 0; i < 3; ++i) {
    const auto f = std::size_t(fingers[i]);
    config.contacts.push_back({kFingertips[f]});
    config.routes.push_back({i, ActuatorId(f)});
  }
  return config;
}

int HapticConfig::blockLength() const noexcept {
  return int(std::lround(tactile.sampleRate_hz / rate_hz));
}

std::uint8_t HapticConfig::actuatorCount() const noexcept {
  int count = 0;
  for (const ActuatorRoute& r : routes) count = std::max(count, int(r.actuator) + 1);
  return std::uint8_t(count);
}

const char* loopPacingName(LoopPacing pacing) noexcept { return pacing == LoopPacing::Spin ? "spin" : "sleep"; }

bool parseLoopPacing(const char* text, LoopPacing& out) noexcept {
  for (LoopPacing p : {LoopPacing::Sleep, LoopPacing::Spin}) {
    if (std::strcmp(text, loopPacingName(p)) == 0) {
      out = p;
      return true;
    }
  }
  return false;
}

void HapticConfig::validate() const {
  if (!(rate_hz >= 250.0f && rate_hz <= 4000.0f)) fail("haptics config: rate_hz ", rate_hz, " outside 250..4000");
  const float block = tactile.sampleRate_hz / rate_hz;
  if (std::abs(block - std::round(block)) > 1e-3f || block < 1.0f || block > float(kMaxBlockSamples)) {
    fail("haptics config: sampleRate_hz ", tactile.sampleRate_hz, " must be 1..", kMaxBlockSamples,
         " whole samples per tick at rate_hz ", rate_hz);
  }
  if (!(tactile.ramp_s >= 0.0f && tactile.ramp_s <= 0.002f)) {
    fail("haptics config: ramp_s ", tactile.ramp_s, " outside 0..0.002 (ramps must finish within 2 ms)");
  }
  if (sampling.timeout_ns < 0 || sampling.timeout_ns > PoseSamplingConfig::kMaxTimeout_ns) {
    fail("haptics config: pose timeout ", double(sampling.timeout_ns) / 1e6, " ms outside 0..",
         double(PoseSamplingConfig::kMaxTimeout_ns) / 1e6);
  }
  if (sampling.maxPrediction_ns < 0 || sampling.maxPrediction_ns > 200'000'000) {
    fail("haptics config: prediction horizon ", double(sampling.maxPrediction_ns) / 1e6, " ms outside 0..200");
  }
  if (outputLatency_ns < 0 || outputLatency_ns > 200'000'000) {
    fail("haptics config: output latency ", double(outputLatency_ns) / 1e6, " ms outside 0..200");
  }
  if (pacing != LoopPacing::Sleep && pacing != LoopPacing::Spin) fail("haptics config: pacing ", int(pacing), " is not sleep or spin");
  if (realtimePriority < 0 || realtimePriority > 99) {
    fail("haptics config: realtimePriority ", realtimePriority, " outside 0..99");
  }
  if (contacts.empty() || contacts.size() > std::size_t(kMaxContactPoints)) {
    fail("haptics config: ", contacts.size(), " contact points, expected 1..", kMaxContactPoints);
  }
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    if (int(contacts[i].joint) >= kHandJointCount) fail("haptics config: contacts[", i, "].joint out of range");
    if (!(contacts[i].radius_m >= 0.0f && contacts[i].radius_m < 0.1f)) {
      fail("haptics config: contacts[", i, "].radius_m ", contacts[i].radius_m, " outside 0..0.1");
    }
  }
  for (std::size_t i = 0; i < routes.size(); ++i) {
    const ActuatorRoute& r = routes[i];
    if (r.contact < 0 || std::size_t(r.contact) >= contacts.size()) {
      fail("haptics config: routes[", i, "].contact ", r.contact, " of ", contacts.size(), " contact points");
    }
    if (int(r.actuator) >= kMaxActuators) fail("haptics config: routes[", i, "].actuator out of range");
    if (!(r.gain >= 0.0f && r.gain <= 10.0f)) fail("haptics config: routes[", i, "].gain ", r.gain, " outside 0..10");
    if (!(r.curve.gamma > 0.0f) || !(r.curve.floor >= 0.0f && r.curve.floor < 1.0f)) {
      fail("haptics config: routes[", i, "].curve needs gamma > 0 and floor in 0..1");
    }
  }
}

}  // namespace vt::haptics
