#version 450
#extension GL_EXT_multiview : require
#extension GL_GOOGLE_include_directive : require
// Scene meshes: world position, normal and texture coordinates for the textured and overlay passes.
#include "frame.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;

layout(push_constant) uniform Object {
  mat4 T_world_object;
  vec4 baseColor;
  vec4 uvRow0;  // material uvTransform rows: uv' = (dot(row0, (u,v,1)), dot(row1, (u,v,1)))
  vec4 uvRow1;
} object;

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec2 outTexcoord;

void main() {
  const vec4 world = object.T_world_object * vec4(inPosition, 1.0);
  // The overlay pass redraws these surfaces with this same shader and depth test LESS_OR_EQUAL,
  // so it gets the same depth values (no `invariant`: lavapipe warns about it on gl_Position).
  gl_Position = frame.viewProj[gl_ViewIndex] * world;
  outNormal = transpose(inverse(mat3(object.T_world_object))) * inNormal;
  const vec3 uv1 = vec3(inUv, 1.0);
  const vec2 uv = vec2(dot(object.uvRow0.xyz, uv1), dot(object.uvRow1.xyz, uv1));
  // Scene images store row 0 = top = v 1, while Vulkan's t = 0 is row 0.
  outTexcoord = vec2(uv.x, 1.0 - uv.y);
}
