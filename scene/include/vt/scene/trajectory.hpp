#pragma once
// Scripted hand paths for offscreen runs, tests and experiments (docs/trajectory-format.md).
#include <filesystem>
#include <vector>

#include "vt/scene/hand.hpp"

namespace vt {

/// One key pose: palm position (world, metres), palm rotation (yaw, pitch, roll in degrees;
/// 0,0,0 = palm facing down, fingers along -Z) and finger curls.
struct TrajectoryKey {
  double t_s = 0.0;
  glm::vec3 palm_m{0.0f};
  glm::vec3 rotation_deg{0.0f};
  FingerCurls curls{};
};

/// Keys sorted by time; poses between keys are interpolated (linear, slerp for rotation).
struct Trajectory {
  std::vector<TrajectoryKey> keys;
  bool leftHand = false;

  double duration_s() const noexcept { return keys.empty() ? 0.0 : keys.back().t_s - keys.front().t_s; }
  /// The hand at time t_s, clamped to the first/last key (its stamp too). Any thread.
  HandPose poseAt(double t_s) const;
};

/// Palm frame from a position and yaw/pitch/roll in degrees.
glm::mat4 palmTransform(glm::vec3 palm_m, glm::vec3 rotation_deg);

/// Loads .json or .csv. Throws vt::Error naming the file, line/key and problem
/// (non-increasing time, NaN, curls outside 0..1, missing columns).
Trajectory loadTrajectory(const std::filesystem::path& path);

/// Parses CSV text; `source` names it in errors.
Trajectory parseTrajectoryCsv(const std::string& text, const std::string& source);
/// Parses JSON text; `source` names it in errors.
Trajectory parseTrajectoryJson(const std::string& text, const std::string& source);

}  // namespace vt
