#include "vt/net/map_frame_source.hpp"

#include <algorithm>
#include <cmath>

#include "vt/core/error.hpp"
#include "vt/haptics/codec/test_signals.hpp"

namespace vt::net {

namespace {
constexpr float kStripePeriod_m = 0.002f;  // textureHeight's stripe spacing
}  // namespace

MapFrameSource::MapFrameSource(int actuatorCount, int blockLength, int sampleRate_hz)
    : m_actuators(actuatorCount), m_blockLength(blockLength), m_sampleRate_hz(sampleRate_hz) {
  if (actuatorCount < 1 || actuatorCount > kFingerCount) fail("map frame source: actuatorCount ", actuatorCount, " not in 1..5");
  if (blockLength < 1 || blockLength > haptics::kMaxBlockSamples)
    fail("map frame source: blockLength ", blockLength, " not in 1..", haptics::kMaxBlockSamples);
  if (sampleRate_hz < 1) fail("map frame source: sampleRate_hz must be positive");
}

void MapFrameSource::render(const HandPose& pose, haptics::ActuatorFrame& frame) noexcept {
  frame.actuatorCount = std::uint8_t(m_actuators);
  frame.blockLength = std::uint16_t(m_blockLength);
  frame.sampleRate_hz = std::uint32_t(m_sampleRate_hz);
  frame.block = {};
  frame.intensity = {};
  frame.frequency_hz = {};
  const float blockDuration_s = float(m_blockLength) / float(m_sampleRate_hz);
  for (int a = 0; a < m_actuators; ++a) {
    const auto tip = std::size_t(kFingertips[std::size_t(a)]);
    const glm::vec3 now = pose.valid ? pose.position[tip] : glm::vec3(0.0f, 0.0f, 1.0f);
    const glm::vec3 before = m_havePrevious ? m_previous[std::size_t(a)] : now;
    m_previous[std::size_t(a)] = now;
    const float radius = pose.radius_m[tip] > 0.0f ? pose.radius_m[tip] : kDefaultFingertipRadius_m;
    if (!pose.valid || std::fabs(now.z) > radius) continue;
    double energy = 0.0;
    auto& block = frame.block[std::size_t(a)];
    for (int i = 0; i < m_blockLength; ++i) {
      const glm::vec3 p = glm::mix(before, now, float(i + 1) / float(m_blockLength));
      block[std::size_t(i)] = 0.8f * (2.0f * haptics::textureHeight(p.x, p.y) - 1.0f);
      energy += double(block[std::size_t(i)]) * block[std::size_t(i)];
    }
    frame.intensity[std::size_t(a)] = std::min(1.0f, float(std::sqrt(2.0 * energy / m_blockLength)));
    frame.frequency_hz[std::size_t(a)] = glm::length(glm::vec2(now - before)) / blockDuration_s / kStripePeriod_m;
  }
  m_havePrevious = pose.valid;
}

HandPose slidingHand(float x_m, float y_m, std::int64_t t_ns, std::uint64_t sequence) {
  // Only the fingertips matter to MapFrameSource; the other joints stay at the origin.
  HandPose pose;
  pose.t_ns = t_ns;
  pose.sequence = sequence;
  pose.valid = true;
  for (int f = 0; f < kFingerCount; ++f) {
    const auto tip = std::size_t(kFingertips[std::size_t(f)]);
    pose.position[tip] = {x_m + 0.02f * float(f - 2), y_m - 0.08f, 0.0f};
    pose.radius_m[tip] = kDefaultFingertipRadius_m;
  }
  for (auto& q : pose.orientation) q = glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  return pose;
}

}  // namespace vt::net
