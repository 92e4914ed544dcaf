#version 450
#extension GL_EXT_multiview : require
#extension GL_GOOGLE_include_directive : require
// Contact rings: one instanced square (a 4-vertex strip from gl_VertexIndex) lying on the touched
// surface, lifted a little along its normal so it never z-fights with the surface.
#include "frame.glsl"

layout(location = 0) in vec4 inCentre;  // xyz: contact point (world), w: ring radius (m)
layout(location = 1) in vec4 inNormal;  // xyz: surface normal (world), w: intensity 0..1

layout(location = 0) out vec2 outLocal;  // -1..1 across the square; the ring is at length 1
layout(location = 1) out float outIntensity;

const float kLift_m = 0.0015;

void main() {
  const vec2 corner = vec2(gl_VertexIndex & 1, gl_VertexIndex >> 1) * 2.0 - 1.0;
  const vec3 n = normalize(inNormal.xyz);
  const vec3 helper = abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 0.0, 1.0);
  const vec3 u = normalize(cross(helper, n));
  const vec3 v = cross(n, u);
  const vec3 world = inCentre.xyz + n * kLift_m + (u * corner.x + v * corner.y) * inCentre.w;
  gl_Position = frame.viewProj[gl_ViewIndex] * vec4(world, 1.0);
  outLocal = corner;
  outIntensity = inNormal.w;
}
