#version 450
// A textured rectangle drawn inside Dear ImGui's pass (ImGuiLayer::image): four strip vertices
// from gl_VertexIndex, no vertex buffer; the rectangle comes in normalised device coordinates.
layout(push_constant) uniform Rect {
  vec2 offset;  // top-left corner
  vec2 scale;   // size
} rect;

layout(location = 0) out vec2 outUv;

void main() {
  const vec2 uv = vec2(gl_VertexIndex & 1, gl_VertexIndex >> 1);
  outUv = uv;
  gl_Position = vec4(rect.offset + uv * rect.scale, 0.0, 1.0);
}
