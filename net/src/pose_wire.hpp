#pragma once
// The quantised hand of a pose message (docs/protocol.md "pose"): the palm's position (i32 per
// axis) and orientation (smallest three, i16 each), every other joint's position relative to
// the palm (i16 per axis), all positions in kPoseStep_m steps; radii in 0.01 mm steps (u16).
// The receiver orients the finger joints from their positions.
#include <array>

#include "vt/scene/hand.hpp"
#include "wire.hpp"

namespace vt::net::pose_wire {

/// Radii travel in steps of this (metres).
inline constexpr float kRadiusStep_m = 1e-5f;
/// Palm coordinates beyond this (metres) are refused: float precision would exceed a step.
inline constexpr float kMaxPalm_m = 100.0f;

/// Writes the joints of a valid hand; false (nothing sensible written) when out of range.
bool writeJoints(wire::Writer& w, const HandPose& hand) noexcept;
/// Reads them back (palm and wrist oriented as the palm, fingers along their bones:
/// orientJointsAlongBones); false when out of range.
bool readJoints(wire::Reader& r, HandPose& hand) noexcept;

/// 26 radii as u16 steps; false when one is negative, not finite or too large.
bool writeRadii(wire::Writer& w, const std::array<float, kHandJointCount>& radius_m) noexcept;
void readRadii(wire::Reader& r, std::array<float, kHandJointCount>& radius_m) noexcept;
/// The radii as the wire carries them (what the receiver will see).
std::array<float, kHandJointCount> quantisedRadii(const std::array<float, kHandJointCount>& radius_m) noexcept;

}  // namespace vt::net::pose_wire
