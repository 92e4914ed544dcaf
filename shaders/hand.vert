#version 450
#extension GL_EXT_multiview : require
#extension GL_GOOGLE_include_directive : require
// Instanced hand primitives: the unit capsule mesh (radius 1, lower cap centred at y = 0, upper cap
// lifted to y = 1) stretched between two points a and b with a radius (a == b gives a sphere).
#include "frame.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 3) in vec4 inA;      // xyz: segment start (world), w: radius (m)
layout(location = 4) in vec4 inB;      // xyz: segment end (world)
layout(location = 5) in vec4 inColor;  // linear RGB

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec3 outColor;

void main() {
  const vec3 axis = inB.xyz - inA.xyz;
  const float len = length(axis);
  const vec3 y = len > 1e-6 ? axis / len : vec3(0.0, 1.0, 0.0);
  const vec3 helper = abs(y.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 0.0, 1.0);
  const vec3 x = normalize(cross(helper, y));
  const vec3 z = cross(x, y);
  const mat3 R = mat3(x, y, z);
  const bool upper = inPosition.y > 0.5;
  const vec3 local = inPosition - vec3(0.0, upper ? 1.0 : 0.0, 0.0);  // back to the unit sphere
  const vec3 world = (upper ? inB.xyz : inA.xyz) + R * (local * inA.w);
  gl_Position = frame.viewProj[gl_ViewIndex] * vec4(world, 1.0);
  outNormal = R * inNormal;
  outColor = inColor.rgb;
}
