#version 450
// The image as it is: an sRGB texture sampled to linear, written to the sRGB attachment.
layout(set = 0, binding = 0) uniform sampler2D image;

layout(location = 0) in vec2 inUv;
layout(location = 0) out vec4 outColor;

void main() {
  outColor = vec4(texture(image, inUv).rgb, 1.0);
}
