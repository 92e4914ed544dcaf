#pragma once
// A minimal tactile frame source standing in for the haptic loop where a scene is not wanted
// (protocol tests, vt_bench net): every fingertip within its
// radius of the plane z = 0 drives its actuator (thumb..little = ids 0..4) with the procedural
// texture map (haptics::textureHeight) sampled along the tip's path since the previous pose.
// Deterministic for a given pose sequence; one thread.
#include <array>

#include <glm/glm.hpp>

#include "vt/haptics/actuator_frame.hpp"
#include "vt/scene/hand.hpp"

namespace vt::net {

/// Pose -> frame by sampling the texture map along each fingertip's path.
class MapFrameSource {
 public:
  /// actuatorCount 1..5 (fingertips), blockLength 1..kMaxBlockSamples.
  MapFrameSource(int actuatorCount = kFingerCount, int blockLength = haptics::kMaxBlockSamples, int sampleRate_hz = 8000);
  /// Renders one frame (shape, waveform, levels) from `pose`; sequence and times are the caller's.
  void render(const HandPose& pose, haptics::ActuatorFrame& frame) noexcept;

 private:
  int m_actuators;
  int m_blockLength;
  int m_sampleRate_hz;
  std::array<glm::vec3, kFingerCount> m_previous{};
  bool m_havePrevious = false;
};

/// A hand whose fingertips lie on the plane z = 0 around (x, y) (fingers along -y), for scripted slides.
HandPose slidingHand(float x_m, float y_m, std::int64_t t_ns, std::uint64_t sequence);

}  // namespace vt::net
