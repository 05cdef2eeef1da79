// One point, segment or triangle of the Vulkan platforms (vulkan_device.cpp). The matrix takes
// object coordinates to Vulkan clip coordinates: the view's projection x modelview with y negated
// and z' = (z + w) / 2, formed in double on the CPU, so that the clip volume, the window position
// and the pixel a fragment lands in are GL's (see vulkan_device.cpp).
#version 450

layout(location = 0) in vec4 position;
layout(push_constant) uniform Draw {
  mat4 clip_from_object;
  vec4 colour;
} draw;

void main() {
  gl_Position = draw.clip_from_object * position;
  gl_PointSize = 1.0;  // Vulkan's point is a square of the size the shader writes
}
