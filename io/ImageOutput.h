// Writing rendered frames: OpenEXR (float, zip) with channels R, G, B, A (premultiplied), Z (distance
// along the unit ray, +inf on a miss) and N.X, N.Y, N.Z (unit world gradient direction); PNG (8-bit
// shaded colour over a background). Both through a temporary file renamed into place.
#pragma once

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace fcc::io {

struct RenderedImage {
  int width = 0, height = 0;
  const std::vector<float>* rgba = nullptr;         // 4 per pixel, row 0 at the top
  const std::vector<float>* normalDepth = nullptr;  // 4 per pixel: N.X, N.Y, N.Z, Z
  bool normals = true;  // false: the EXR gets R, G, B, A and Z only (direct volume rendering)
};

// True for the outputs that store depth and normals (EXR), false for colour only (PNG).
bool imageHoldsNormalDepth(const std::string& path);
// By extension: ".exr" or ".png" (case-insensitive); anything else is a ValueError listing both.
void writeRenderedImage(const std::string& path, const RenderedImage& image, const glm::vec3& background);

// An 8-bit sRGB RGB image as shown on screen (the viewer's window), row 0 at the top, to PNG.
void writeScreenPng(const std::string& path, int width, int height, const std::vector<unsigned char>& rgb);

// Throws ValueError unless `path` ends in .exr or .png.
void checkImageExtension(const std::string& path);

}  // namespace fcc::io
