#include "modes/hand_control.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "vt/haptics/actuator_frame.hpp"

namespace vt::app {
namespace {

glm::mat4 palmFrame(glm::vec3 palm_m, float yaw_rad) {
  return glm::rotate(glm::translate(glm::mat4(1.0f), palm_m), yaw_rad, glm::vec3(0.0f, 1.0f, 0.0f));
}

// How deep the deepest of the index..little fingertips sinks into the scene (0: none touches).
// These are the tips the flat hand rests on; the thumb curls below the palm's plane and the
// palm's sphere is a rough 2 cm proxy, so neither decides where the hand stops.
float deepestPenetration_m(const HandPose& hand, const collision::CollisionScene& world) {
  float deepest = 0.0f;
  for (int f = 1; f < kFingerCount; ++f) {
    const auto j = std::size_t(kFingertips[std::size_t(f)]);
    const collision::SphereContact c = world.sphereContact({hand.position[j], hand.radius_m[j]});
    if (c.hit()) deepest = std::max(deepest, c.depth_m);
  }
  return deepest;
}

}  // namespace

void DesktopHand::move(glm::vec3 delta_m, float yaw_rad, const collision::CollisionScene& world) {
  constexpr float kStep_m = 0.002f, kStep_rad = 0.02f;
  const int steps = std::max(1, int(std::ceil(std::max(glm::length(delta_m) / kStep_m, std::abs(yaw_rad) / kStep_rad))));
  float depth = deepestPenetration_m(poseHand(palmFrame(m_palm_m, m_yaw_rad), m_curls), world);
  for (int i = 0; i < steps; ++i) {
    const glm::vec3 palm = m_palm_m + delta_m / float(steps);
    const float yaw = m_yaw_rad + yaw_rad / float(steps);
    const float next = deepestPenetration_m(poseHand(palmFrame(palm, yaw), m_curls), world);
    if (next > kClickPress_m && next > depth) return;  // a surface: stop here
    m_palm_m = palm, m_yaw_rad = yaw, depth = next;
  }
}

void DesktopHand::reset() {
  m_palm_m = {0.0f, kDefaultFingertipRadius_m + kHover_m, 0.08f};
  m_yaw_rad = 0.0f;
  m_press_m = 0.0f;
  m_curls = {0.35f, 0.0f, 0.0f, 0.0f, 0.0f};  // thumb slightly in, like a hand laid flat
  m_curlTargets = m_curls;
}

void DesktopHand::placeIndexTipOver(glm::vec3 surface_world) {
  // Offset of the index tip from the palm for the current yaw and curls, measured on the model.
  const HandPose model = poseHand(palmFrame({0.0f, 0.0f, 0.0f}, m_yaw_rad), m_curls);
  const glm::vec3 tip = model.at(HandJoint::IndexTip);
  const float tipRadius = model.radius_m[std::size_t(HandJoint::IndexTip)];
  m_palm_m = {surface_world.x - tip.x, surface_world.y - tip.y + tipRadius + kHover_m, surface_world.z - tip.z};
}

void DesktopHand::addPress(float delta_m) { m_press_m = std::clamp(m_press_m + delta_m, 0.0f, kMaxPress_m); }

void DesktopHand::toggleCurl(int finger) {
  if (finger < 0 || finger >= kFingerCount) return;
  float& target = m_curlTargets[std::size_t(finger)];
  target = target > 0.5f ? 0.0f : 0.9f;
}

void DesktopHand::update(float dt_s) {
  const float step = std::min(1.0f, dt_s * 6.0f);
  for (int f = 0; f < kFingerCount; ++f) {
    m_curls[std::size_t(f)] += (m_curlTargets[std::size_t(f)] - m_curls[std::size_t(f)]) * step;
  }
}

float DesktopHand::press_m(bool pressing) const {
  return std::min(kMaxPress_m, m_press_m + (pressing ? kClickPress_m : 0.0f));
}

HandPose DesktopHand::pose(bool pressing, std::int64_t t_ns) const {
  // Pressing lowers the palm by hover + press: fingertips go `press` metres below the surface.
  const glm::vec3 palm = m_palm_m - glm::vec3(0.0f, (pressing || m_press_m > 0.0f) ? kHover_m + press_m(pressing) : 0.0f, 0.0f);
  return poseHand(palmFrame(palm, m_yaw_rad), m_curls, false, t_ns);
}

int fingerOfTip(HandJoint joint) noexcept {
  for (int f = 0; f < kFingerCount; ++f) {
    if (kFingertips[std::size_t(f)] == joint) return f;
  }
  return 1;
}

const char* fingerName(int finger) noexcept {
  // One spelling per finger: the fingertip actuators carry the fingers' names (string literals,
  // so the view's data is terminated).
  return haptics::actuatorName(haptics::ActuatorId(std::clamp(finger, 0, kFingerCount - 1))).data();
}

HandPose visualProxy(const HandPose& physical, const collision::CollisionScene& world) {
  HandPose drawn = physical;
  if (!physical.valid) return drawn;
  // A joint pressed deeper than its radius has its centre behind the surface, where the closest
  // point can be the far side of a thin plate. So each joint is first lowered from kLift_m above
  // along the press direction (the palm's -Y) until its sphere meets a surface, then any remaining
  // shallow overlap (sloped surfaces, side contacts) is resolved along the contact normal.
  constexpr float kLift_m = 0.05f;
  const glm::vec3 down = glm::normalize(physical.orientation[std::size_t(HandJoint::Palm)] * glm::vec3(0.0f, -1.0f, 0.0f));
  for (int j = 0; j < kHandJointCount; ++j) {
    const float radius = physical.radius_m[std::size_t(j)];
    glm::vec3 p = physical.position[std::size_t(j)];
    const glm::vec3 start = p - down * kLift_m;
    const collision::RayHit hit = world.intersect({start, down, 0.0f, kLift_m + radius});
    if (hit.hit()) p = start + down * std::min(kLift_m, hit.t - radius);
    const collision::SphereContact c = world.sphereContact({p, radius});
    if (c.hit() && c.depth_m > 0.0f && c.depth_m < radius) p = c.point + c.normal * radius;
    drawn.position[std::size_t(j)] = p;
  }
  return drawn;
}

glm::vec3 pickSurface(const collision::CollisionScene& world, glm::vec3 origin, glm::vec3 direction) {
  const collision::RayHit hit = world.intersect({origin, direction, 0.0f, 100.0f});
  if (hit.hit()) return origin + direction * hit.t;
  if (std::abs(direction.y) > 1e-6f) {
    const float t = -origin.y / direction.y;
    if (t > 0.0f) return origin + direction * t;
  }
  return {origin.x, 0.0f, origin.z};
}

}  // namespace vt::app
