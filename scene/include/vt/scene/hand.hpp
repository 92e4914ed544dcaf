#pragma once
// The tracked hand: the 26-joint set of OpenXR XR_EXT_hand_tracking, and a kinematic
// model that poses it from a palm pose and per-finger curl (desktop, controllers, glove).
#include <array>
#include <cstdint>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace vt {

/// Joint indices in XR_EXT_hand_tracking order (XrHandJointEXT values).
enum class HandJoint : std::uint8_t {
  Palm = 0, Wrist,
  ThumbMetacarpal, ThumbProximal, ThumbDistal, ThumbTip,
  IndexMetacarpal, IndexProximal, IndexIntermediate, IndexDistal, IndexTip,
  MiddleMetacarpal, MiddleProximal, MiddleIntermediate, MiddleDistal, MiddleTip,
  RingMetacarpal, RingProximal, RingIntermediate, RingDistal, RingTip,
  LittleMetacarpal, LittleProximal, LittleIntermediate, LittleDistal, LittleTip,
};
inline constexpr int kHandJointCount = 26;
enum class Finger : std::uint8_t { Thumb = 0, Index, Middle, Ring, Little };
inline constexpr int kFingerCount = 5;

/// The tip joint of each finger, thumb first.
inline constexpr std::array<HandJoint, kFingerCount> kFingertips = {
    HandJoint::ThumbTip, HandJoint::IndexTip, HandJoint::MiddleTip, HandJoint::RingTip, HandJoint::LittleTip};

/// One timestamped hand snapshot in world space (metres). Trivially copyable: it travels
/// through lock-free channels and over the network as is.
struct HandPose {
  std::int64_t t_ns = 0;  // when the pose was sampled (source clock = SteadyClock)
  std::uint64_t sequence = 0;
  bool valid = false;
  std::array<glm::vec3, kHandJointCount> position{};
  std::array<glm::quat, kHandJointCount> orientation{};
  std::array<float, kHandJointCount> radius_m{};

  const glm::vec3& at(HandJoint joint) const noexcept { return position[std::size_t(joint)]; }
};

/// A fingertip's contact radius when a pose carries none (an adult index fingertip pad).
inline constexpr float kDefaultFingertipRadius_m = 0.008f;

/// Finger flexion, 0 = straight, 1 = fully curled, thumb first.
using FingerCurls = std::array<float, kFingerCount>;

/// Poses a right hand (mirrored in X when `left`) whose palm frame is T_world_palm:
/// fingers point along the palm's -Z, the back of the hand is +Y (as OpenXR's palm joint).
HandPose poseHand(const glm::mat4& T_world_palm, const FingerCurls& curls, bool left = false,
                  std::int64_t t_ns = 0);

/// Sets every finger joint's orientation from the joint positions and the palm's orientation,
/// as poseHand orients them: -Z along the bone to the next joint (a tip continues its bone), +Y
/// the back of the finger, the finger's flexion axis taken across its metacarpal and the palm's
/// +Y. For a hand known by positions only (a pose from the network): the skinned mesh needs
/// orientations. A bone too short to have a direction keeps its parent's. Any thread.
void orientJointsAlongBones(HandPose& pose) noexcept;

/// The parent joint of each joint along the bone chain (Palm and Wrist map to Wrist).
HandJoint parentJoint(HandJoint joint) noexcept;

}  // namespace vt
