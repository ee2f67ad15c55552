// sRGB encoding of linear colours, as shaders/present.frag and `fccvdb render`'s PNG apply it, and its
// inverse: the panel edits colours as they appear on screen (sRGB) while the renderer keeps them linear.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace fcc::render {

inline float srgbFromLinear(float v) {
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(std::max(v, 0.0f), 1.0f / 2.4f) - 0.055f;
}

inline float linearFromSrgb(float v) {
  return v <= 0.04045f ? v / 12.92f : std::pow((std::max(v, 0.0f) + 0.055f) / 1.055f, 2.4f);
}

inline glm::vec3 srgbFromLinear(const glm::vec3& c) { return {srgbFromLinear(c.r), srgbFromLinear(c.g), srgbFromLinear(c.b)}; }
inline glm::vec3 linearFromSrgb(const glm::vec3& c) { return {linearFromSrgb(c.r), linearFromSrgb(c.g), linearFromSrgb(c.b)}; }

}  // namespace fcc::render
