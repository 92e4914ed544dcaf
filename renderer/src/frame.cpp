#include "vt/renderer/frame.hpp"

#include <algorithm>

namespace vt::renderer {

void appendHandPrimitives(const HandPose& pose, glm::vec4 color, std::vector<HandPrimitive>& out) {
  if (!pose.valid) return;
  for (int j = 0; j < kHandJointCount; ++j) {
    const auto joint = HandJoint(j);
    const float radius = pose.radius_m[std::size_t(j)];
    out.push_back({pose.at(joint), pose.at(joint), radius, color});
    const HandJoint parent = parentJoint(joint);
    if (joint == HandJoint::Palm || joint == HandJoint::Wrist || parent == joint) continue;
    // Bones are a little thinner than the joints they connect so the joints read as knuckles.
    const float boneRadius = 0.8f * std::min(radius, pose.radius_m[std::size_t(parent)]);
    out.push_back({pose.at(parent), pose.at(joint), boneRadius, color});
  }
}

void appendHand(const HandPose& pose, HandStyle style, FrameDesc& frame, bool left) {
  if (!pose.valid) return;
  if (style == HandStyle::Skeleton) appendHandPrimitives(pose, kHandColor, frame.hand);
  else frame.hands.push_back({pose, left, kHandColor});
}

}  // namespace vt::renderer
