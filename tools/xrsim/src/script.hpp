#pragma once
// Scripted input over time: head pose, controller poses and buttons, 26 hand joints per hand.
#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace xrsim {

/// A rigid pose in the stage (world) frame.
struct Pose {
  glm::vec3 position{0.0f};
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};
};

inline constexpr int kJointCount = 26;

/// One hand's controller and tracked-hand state at an instant.
struct HandSample {
  bool controllerTracked = true;
  Pose grip, aim;
  std::map<std::string, float> buttons;         // component name ("trigger", "a", ...) -> 0..1
  std::map<std::string, glm::vec2> axes;        // "thumbstick", "trackpad" -> -1..1
  bool jointsActive = false;
  std::array<Pose, kJointCount> joints{};
  std::array<float, kJointCount> radius_m{};
};

/// Everything the simulated user does at one instant.
struct Sample {
  Pose head;
  std::array<HandSample, 2> hands;  // left, right
  bool trackerTracked = true;       // the VIVE tracker (XR_HTCX_vive_tracker_interaction)
  Pose tracker;
};

/// Keyframes, linearly interpolated (orientations slerped); before the first / after the
/// last keyframe the ends hold.
class Script {
 public:
  /// A still user: head at 1.6 m, controllers in front, no tracked hands.
  Script();
  /// Parses a script file; throws vt::Error naming the file, the keyframe and the field.
  static Script load(const std::filesystem::path& path);
  /// The state at t_s seconds after the session began.
  Sample sample(double t_s) const;
  /// The VIVE tracker's role ("handheld_object", ...), or "" when the script has no tracker.
  const std::string& trackerRole() const { return m_trackerRole; }

 private:
  std::vector<double> m_times;
  std::vector<Sample> m_keys;
  std::string m_trackerRole;
};

}  // namespace xrsim
