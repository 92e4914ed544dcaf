#include "vt/scene/hand.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace vt {
namespace {

struct FingerShape {
  glm::vec3 base;            // metacarpal joint in the palm frame
  glm::vec3 knuckle;         // proximal joint in the palm frame
  std::array<float, 3> length_m;  // proximal, intermediate, distal bones
  std::array<float, 3> maxFlex_rad;
  float tipRadius_m;
};

// An adult right hand of average size; the palm frame has its origin at the palm centre.
constexpr std::array<FingerShape, kFingerCount> kShapes = {{
    {{-0.020f, -0.005f, 0.035f}, {-0.045f, -0.010f, 0.000f}, {0.032f, 0.030f, 0.026f}, {0.6f, 0.9f, 0.8f}, 0.0090f},
    {{-0.012f, 0.000f, 0.040f}, {-0.025f, 0.000f, -0.040f}, {0.045f, 0.026f, 0.022f}, {1.4f, 1.6f, 1.1f}, 0.0080f},
    {{-0.002f, 0.000f, 0.040f}, {-0.004f, 0.000f, -0.044f}, {0.050f, 0.031f, 0.024f}, {1.4f, 1.6f, 1.1f}, 0.0080f},
    {{0.010f, 0.000f, 0.040f}, {0.016f, 0.000f, -0.040f}, {0.047f, 0.029f, 0.023f}, {1.4f, 1.6f, 1.1f}, 0.0075f},
    {{0.020f, -0.002f, 0.038f}, {0.034f, -0.003f, -0.032f}, {0.037f, 0.021f, 0.020f}, {1.4f, 1.6f, 1.1f}, 0.0068f},
}};

glm::quat lookRotation(glm::vec3 forward, glm::vec3 up) {
  // Frame whose -Z is `forward` and +Y is as close to `up` as possible (OpenXR joint convention).
  const glm::vec3 z = -glm::normalize(forward);
  const glm::vec3 x = glm::normalize(glm::cross(up, z));
  const glm::vec3 y = glm::cross(z, x);
  return glm::quat_cast(glm::mat3(x, y, z));
}

}  // namespace

HandPose poseHand(const glm::mat4& T_world_palm, const FingerCurls& curls, bool left, std::int64_t t_ns) {
  HandPose pose;
  pose.t_ns = t_ns;
  pose.valid = true;
  const float mirror = left ? -1.0f : 1.0f;
  const glm::quat q_world_palm = glm::quat_cast(glm::mat3(T_world_palm));
  auto toWorld = [&](glm::vec3 p) { return glm::vec3(T_world_palm * glm::vec4(p.x * mirror, p.y, p.z, 1.0f)); };
  // A left hand is the right hand reflected in the palm's YZ plane; M R M keeps frames proper.
  const glm::mat3 reflect(glm::vec3(mirror, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1));
  auto set = [&](HandJoint joint, glm::vec3 p_palm, glm::quat q_palm, float radius) {
    const auto i = std::size_t(joint);
    pose.position[i] = toWorld(p_palm);
    pose.orientation[i] = q_world_palm * glm::quat_cast(reflect * glm::mat3_cast(q_palm) * reflect);
    pose.radius_m[i] = radius;
  };

  set(HandJoint::Palm, {0, 0, 0}, glm::quat(1, 0, 0, 0), 0.02f);
  set(HandJoint::Wrist, {0, 0, 0.06f}, glm::quat(1, 0, 0, 0), 0.02f);

  for (int f = 0; f < kFingerCount; ++f) {
    const FingerShape& s = kShapes[std::size_t(f)];
    const float curl = std::clamp(curls[std::size_t(f)], 0.0f, 1.0f);
    const int firstIndex = f == 0 ? 2 : 6 + 5 * (f - 1);
    // Metacarpal bone, from base to knuckle.
    glm::vec3 dir = glm::normalize(s.knuckle - s.base);
    // Flexion bends toward the palm (-Y) around the axis across the finger.
    const glm::vec3 side = glm::normalize(glm::cross(dir, glm::vec3(0, 1, 0)));
    glm::vec3 p = s.base;
    set(HandJoint(firstIndex), p, lookRotation(dir, {0, 1, 0}), s.tipRadius_m * 1.3f);
    p = s.knuckle;
    float bend = 0.0f;
    for (int b = 0; b < 3; ++b) {
      bend += curl * s.maxFlex_rad[std::size_t(b)];
      const glm::vec3 boneDir = glm::vec3(glm::rotate(glm::mat4(1.0f), -bend, side) * glm::vec4(dir, 0.0f));
      const glm::vec3 boneUp = glm::cross(side, boneDir);
      set(HandJoint(firstIndex + 1 + b), p, lookRotation(boneDir, boneUp), s.tipRadius_m * (1.2f - 0.1f * float(b)));
      p += boneDir * s.length_m[std::size_t(b)];
    }
    const glm::vec3 tipDir = glm::vec3(glm::rotate(glm::mat4(1.0f), -bend, side) * glm::vec4(dir, 0.0f));
    set(HandJoint(firstIndex + 4), p, lookRotation(tipDir, glm::cross(side, tipDir)), s.tipRadius_m);
  }
  return pose;
}

void orientJointsAlongBones(HandPose& pose) noexcept {
  constexpr float kMinBone_m = 1e-5f;
  const glm::quat palm = pose.orientation[std::size_t(HandJoint::Palm)];
  const glm::vec3 palmUp = palm * glm::vec3(0.0f, 1.0f, 0.0f);
  for (int f = 0; f < kFingerCount; ++f) {
    // The thumb has metacarpal, proximal, distal and tip; the other fingers an intermediate too.
    const int first = f == 0 ? int(HandJoint::ThumbMetacarpal) : int(HandJoint::IndexMetacarpal) + 5 * (f - 1);
    const int tip = int(kFingertips[std::size_t(f)]);
    glm::quat previous = palm;
    glm::vec3 side(0.0f);
    for (int j = first; j <= tip; ++j) {
      const int from = j < tip ? j : j - 1;  // the tip continues the last bone
      const glm::vec3 bone = pose.position[std::size_t(from + 1)] - pose.position[std::size_t(from)];
      const float length = glm::length(bone);
      glm::quat q = previous;
      if (std::isfinite(length) && length > kMinBone_m) {
        const glm::vec3 dir = bone / length;
        if (j == first) side = glm::cross(dir, palmUp);
        const glm::vec3 up = j == first ? palmUp : glm::cross(side, dir);
        if (glm::length(glm::cross(up, dir)) > 1e-4f) q = lookRotation(dir, up);
      }
      pose.orientation[std::size_t(j)] = q;
      previous = q;
    }
  }
}

HandJoint parentJoint(HandJoint joint) noexcept {
  const auto j = int(joint);
  if (j <= 1) return HandJoint::Wrist;
  const int withinFinger = j <= 5 ? j - 2 : (j - 6) % 5;  // the thumb has no intermediate joint
  if (withinFinger == 0) return HandJoint::Wrist;
  return HandJoint(j - 1);
}

}  // namespace vt
