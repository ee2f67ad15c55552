#version 450 core
// viewer/Presenter: the raycaster's premultiplied linear colour over the background, sRGB-encoded:
// the same pixels `fccvdb render` writes to PNG (io/ImageOutput.cpp). The framebuffer stores the
// encoded bytes as they are (GL_FRAMEBUFFER_SRGB stays off).
layout(binding = 0, rgba32f) uniform readonly image2D uImage;  // row 0 at the top
uniform vec3 uBackground;                                      // linear

out vec4 fragColor;

float srgbFromLinear(float v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(max(v, 0.0), 1.0 / 2.4) - 0.055;
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);  // row 0 at the bottom
  vec4 c = imageLoad(uImage, ivec2(pixel.x, imageSize(uImage).y - 1 - pixel.y));
  vec3 linear = c.rgb + (1.0 - c.a) * uBackground;
  fragColor = vec4(srgbFromLinear(linear.r), srgbFromLinear(linear.g), srgbFromLinear(linear.b), 1.0);
}
