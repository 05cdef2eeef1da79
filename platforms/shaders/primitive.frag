// Every fragment of a primitive in the primitive's colour (a 24-bit counter; vulkan_device.cpp).
#version 450

layout(push_constant) uniform Draw {
  mat4 clip_from_object;
  vec4 colour;
} draw;
layout(location = 0) out vec4 colour;

void main() { colour = draw.colour; }
