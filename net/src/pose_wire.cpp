#include "pose_wire.hpp"

#include <cmath>
#include <cstdint>
#include <limits>

#include "vt/net/protocol.hpp"

namespace vt::net::pose_wire {

namespace {

constexpr float kQuatScale = 32767.0f * 1.41421356f;  // components of the smallest three lie in +-1/sqrt(2)
constexpr std::size_t kPalm = std::size_t(HandJoint::Palm);

bool quantise(float v, float step, float limit, long& out) noexcept {
  if (!std::isfinite(v)) return false;
  const float q = std::round(v / step);
  if (std::abs(q) > limit) return false;
  out = long(q);
  return true;
}

}  // namespace

bool writeJoints(wire::Writer& w, const HandPose& hand) noexcept {
  const glm::vec3 palm = hand.position[kPalm];
  long palmSteps[3];
  for (int a = 0; a < 3; ++a)
    if (!quantise(palm[a], kPoseStep_m, kMaxPalm_m / kPoseStep_m, palmSteps[a])) return false;
  for (long s : palmSteps) w.i32(std::int32_t(s));
  // Relative positions from the palm as the receiver reconstructs it (no drift between the two).
  const glm::vec3 palmWire{float(palmSteps[0]) * kPoseStep_m, float(palmSteps[1]) * kPoseStep_m,
                           float(palmSteps[2]) * kPoseStep_m};
  glm::quat q = hand.orientation[kPalm];
  const float norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  if (!std::isfinite(norm) || norm < 1e-6f) return false;
  q = q / norm;
  const float c[4] = {q.w, q.x, q.y, q.z};
  int largest = 0;
  for (int i = 1; i < 4; ++i)
    if (std::abs(c[i]) > std::abs(c[largest])) largest = i;
  const float sign = c[largest] < 0.0f ? -1.0f : 1.0f;  // q and -q are the same rotation
  w.u8(std::uint8_t(largest));
  for (int i = 0; i < 4; ++i) {
    if (i == largest) continue;
    long s = 0;
    if (!quantise(sign * c[i] * kQuatScale, 1.0f, 32767.0f, s)) return false;
    w.i16(std::int16_t(s));
  }
  for (int j = 0; j < kHandJointCount; ++j) {
    if (std::size_t(j) == kPalm) continue;
    const glm::vec3 d = hand.position[std::size_t(j)] - palmWire;
    for (int a = 0; a < 3; ++a) {
      long s = 0;
      if (!quantise(d[a], kPoseStep_m, 32767.0f, s)) return false;
      w.i16(std::int16_t(s));
    }
  }
  return true;
}

bool readJoints(wire::Reader& r, HandPose& hand) noexcept {
  glm::vec3 palm;
  bool good = true;
  for (int a = 0; a < 3; ++a) {
    const std::int32_t s = r.i32();
    good = good && std::abs(float(s)) <= kMaxPalm_m / kPoseStep_m;
    palm[a] = float(s) * kPoseStep_m;
  }
  const std::uint8_t largest = r.u8();
  good = good && largest < 4;
  float c[4] = {};
  float sum = 0.0f;
  for (int i = 0; i < 4; ++i) {
    if (i == largest) continue;
    const std::int16_t q = r.i16();
    good = good && q != INT16_MIN;  // the range is symmetric: what decodes also encodes
    c[i] = float(q) / kQuatScale;
    sum += c[i] * c[i];
  }
  good = good && sum <= 1.0f;
  if (largest < 4) c[largest] = std::sqrt(std::max(0.0f, 1.0f - sum));
  const glm::quat q(c[0], c[1], c[2], c[3]);
  hand.position[kPalm] = palm;
  for (int j = 0; j < kHandJointCount; ++j) {
    hand.orientation[std::size_t(j)] = q;
    if (std::size_t(j) == kPalm) continue;
    glm::vec3 d;
    for (int a = 0; a < 3; ++a) {
      const std::int16_t step = r.i16();
      good = good && step != INT16_MIN;
      d[a] = float(step) * kPoseStep_m;
    }
    hand.position[std::size_t(j)] = palm + d;
  }
  // Only the palm's orientation travels; the fingers' follow from their joints (the skinned
  // hand of the server's video needs them).
  orientJointsAlongBones(hand);
  return good;
}

bool writeRadii(wire::Writer& w, const std::array<float, kHandJointCount>& radius_m) noexcept {
  for (float radius : radius_m) {
    long s = 0;
    if (!(radius >= 0.0f) || !quantise(radius, kRadiusStep_m, 65535.0f, s)) return false;
    w.u16(std::uint16_t(s));
  }
  return true;
}

void readRadii(wire::Reader& r, std::array<float, kHandJointCount>& radius_m) noexcept {
  for (float& radius : radius_m) radius = float(r.u16()) * kRadiusStep_m;
}

std::array<float, kHandJointCount> quantisedRadii(const std::array<float, kHandJointCount>& radius_m) noexcept {
  std::array<float, kHandJointCount> out{};
  for (std::size_t j = 0; j < out.size(); ++j) {
    const float r = radius_m[j];
    out[j] = std::isfinite(r) && r > 0.0f ? std::min(std::round(r / kRadiusStep_m), 65535.0f) * kRadiusStep_m : 0.0f;
  }
  return out;
}

}  // namespace vt::net::pose_wire
