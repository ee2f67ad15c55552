#version 450 core
// The raycaster's premultiplied linear colour over the background, sRGB-encoded: the same pixels
// `fccvdb render` writes to PNG (io/ImageOutput.cpp), into an RGBA8 image with row 0 at the bottom
// (OpenGL's framebuffer order) that viewer/Presenter blits to the screen. A compute pass, not a
// fragment shader: compute GPUs such as the H100/H200 have little fixed-function graphics hardware.
layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba32f) uniform readonly image2D uImage;   // row 0 at the top
layout(binding = 1, rgba8) uniform writeonly image2D uDisplay;  // row 0 at the bottom
uniform vec3 uBackground;                                       // linear
uniform ivec2 uRegionMin, uRegionMax;  // the pixels drawn, [min, max), rows from the bottom

float srgbFromLinear(float v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(max(v, 0.0), 1.0 / 2.4) - 0.055;
}

void main() {
  ivec2 size = imageSize(uImage);
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy) + uRegionMin;
  if (any(greaterThanEqual(pixel, uRegionMax))) return;
  vec4 c = imageLoad(uImage, ivec2(pixel.x, size.y - 1 - pixel.y));
  vec3 linear = c.rgb + (1.0 - c.a) * uBackground;
  imageStore(uDisplay, pixel,
             vec4(srgbFromLinear(linear.r), srgbFromLinear(linear.g), srgbFromLinear(linear.b), 1.0));
}
