#version 450
#extension GL_EXT_multiview : require
#extension GL_GOOGLE_include_directive : require
// The skinned hand mesh: linear blend skinning by up to four joints per vertex. The joint
// matrices of every hand of the frame (T_world_joint * inverseBind) are in one uniform block.
#include "frame.glsl"

const int kJointsPerHand = 26;
const int kMaxHands = 2;  // mirrors renderer::kMaxSkinnedHands

layout(set = 1, binding = 0) uniform Joints {
  mat4 skin[kJointsPerHand * kMaxHands];
} joints;

layout(push_constant) uniform Hand {
  vec4 color;       // linear RGB
  uint firstJoint;  // this hand's first matrix in joints.skin
} hand;

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in uvec4 inJoints;
layout(location = 3) in vec4 inWeights;

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec3 outColor;

void main() {
  const uint b = hand.firstJoint;
  const mat4 m = inWeights.x * joints.skin[b + inJoints.x] + inWeights.y * joints.skin[b + inJoints.y] +
                 inWeights.z * joints.skin[b + inJoints.z] + inWeights.w * joints.skin[b + inJoints.w];
  gl_Position = frame.viewProj[gl_ViewIndex] * (m * vec4(inPosition, 1.0));
  outNormal = mat3(m) * inNormal;  // joints are rigid or uniformly scaled; hand.frag normalises
  outColor = hand.color.rgb;
}
