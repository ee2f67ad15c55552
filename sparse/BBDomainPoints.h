// The distinct BB domain points of the spline's tetrahedral partition, derived from the shared header
// (fcc_locate, fcc_cubic, fcc_stencil_site): what makes the per-brick bounds cheap.
//
// A unit cube's five pieces carry 5 x 20 BB-coefficients, but pieces share faces and edges, and a
// C^2 spline's BB-coefficients agree where domain points coincide: per 2x2x2 cell (one packed voxel,
// the partition's period) there are only 184 distinct domain points (23 per cube), each a sum of
// 4 to 13 coefficients with small integer weights (5.5 on average, against about 9 per piece
// coefficient). The min/max over them equals the min/max over every piece's BB-coefficients, up to
// the rounding of the different summation order.
#pragma once

#include <map>
#include <tuple>
#include <vector>

#include "Spline.h"

namespace fcc::spline {

struct BBTerm {
  glm::ivec3 site;  // FCC site relative to the cell's corner 2q (lattice index space)
  float weight;     // times FCC_CUBIC_DENOM
};

struct BBDomainPoint {
  glm::ivec3 position;  // in thirds of a lattice unit, relative to the cell's corner: [0, 6)^3
  std::vector<BBTerm> terms;
};

// The domain points of the cell [0, 2)^3 (half-open: those on its far faces belong to the next
// cell), each with the coefficient functional that gives its BB-coefficient.
inline std::vector<BBDomainPoint> bbDomainPointsOfCell() {
  auto less = [](const glm::ivec3& a, const glm::ivec3& b) { return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z); };
  std::map<glm::ivec3, std::map<glm::ivec3, float, decltype(less)>, decltype(less)> points(less);
  for (int cz = 0; cz < 2; ++cz)
    for (int cy = 0; cy < 2; ++cy)
      for (int cx = 0; cx < 2; ++cx)
        for (int piece = 0; piece < 5; ++piece) {
          const FccFrame f = fcc_locate(fcc_piece_centroid(glm::ivec3(cx, cy, cz), piece));
          const glm::ivec3 v0 = f.type == 0 ? glm::ivec3(0, 0, 0) : glm::ivec3(1, 0, 0);
          const glm::ivec3 v1 = f.type == 0 ? glm::ivec3(1, 0, 0) : glm::ivec3(0, 1, 0);
          const glm::ivec3 v2 = f.type == 0 ? glm::ivec3(0, 1, 0) : glm::ivec3(0, 0, 1);
          const glm::ivec3 v3 = f.type == 0 ? glm::ivec3(0, 0, 1) : glm::ivec3(1, 1, 1);
          int b = 0;  // BB index order of FccSplineTables.h: i from 3 down, then j, then k
          for (int i = 3; i >= 0; --i)
            for (int j = 3 - i; j >= 0; --j)
              for (int k = 3 - i - j; k >= 0; --k, ++b) {
                const int l = 3 - i - j - k;
                const glm::ivec3 position = 3 * f.origin + f.axis * (i * v0 + j * v1 + k * v2 + l * v3);
                if (glm::any(glm::greaterThanEqual(position, glm::ivec3(6)))) continue;
                auto& terms = points.try_emplace(position, less).first->second;
                if (!terms.empty()) continue;  // shared with a piece seen before
                for (int s = 0; s < FCC_STENCIL_SIZE; ++s) {
                  FccSamples impulse{};
                  impulse.v[s] = 1.0f;
                  const float w = fcc_cubic(impulse, f.type).b[b];
                  if (w != 0.0f) terms[fcc_stencil_site(f, s)] += w;
                }
              }
        }
  std::vector<BBDomainPoint> out;
  for (const auto& [position, terms] : points) {
    BBDomainPoint p{position, {}};
    for (const auto& [site, w] : terms) p.terms.push_back({site, w});
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace fcc::spline
