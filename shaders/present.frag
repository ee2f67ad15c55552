#version 450 core
// The raycaster's premultiplied linear colour over the background, sRGB-encoded: the same pixels
// `fccvdb render` writes to PNG (io/ImageOutput.cpp), for the viewer's window.
layout(binding = 0) uniform sampler2D uImage;  // row 0 at the top, one texel per framebuffer pixel
uniform vec3 uBackground;                       // linear
uniform ivec2 uOrigin;                          // the viewport's lower left corner in the framebuffer
out vec4 fragColor;

float srgbFromLinear(float v) {
  return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(max(v, 0.0), 1.0 / 2.4) - 0.055;
}

void main() {
  ivec2 size = textureSize(uImage, 0);
  ivec2 pixel = ivec2(gl_FragCoord.xy) - uOrigin;
  vec4 c = texelFetch(uImage, ivec2(pixel.x, size.y - 1 - pixel.y), 0);
  vec3 linear = c.rgb + (1.0 - c.a) * uBackground;
  fragColor = vec4(srgbFromLinear(linear.r), srgbFromLinear(linear.g), srgbFromLinear(linear.b), 1.0);
}
