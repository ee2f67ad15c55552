// worldFromIndex of a grid's transform as a column-vector matrix, for the stores that render grids
// (BrickStore, CartesianBrickStore): the renderer takes affine maps only. And world boxes of index boxes.
#pragma once

#include <glm/glm.hpp>
#include <openvdb/math/Transform.h>

#include <limits>
#include <string>

#include "sparse/Error.h"

namespace fcc::io {

// InputError naming `path` for a transform that is not affine.
inline glm::dmat4 affineWorldFromIndex(const openvdb::math::Transform& xform, const std::string& path) {
  if (!xform.isLinear())
    throw InputError(path + ": the grid's transform (" + xform.mapType() + ") is not affine; the renderer supports linear transforms only");
  // OpenVDB multiplies row vectors (p' = p * M): the column-vector matrix is M transposed.
  const openvdb::Mat4d m = xform.baseMap()->getAffineMap()->getMat4();
  glm::dmat4 out;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out[r][c] = m(r, c);  // glm: out[column][row]; column r = row r of m
  return out;
}

// The world-space bounding box of the index-space box [indexLo, indexHi] (its eight corners mapped).
inline void worldBoxOfIndexBox(const glm::dmat4& worldFromIndex, const glm::dvec3& indexLo, const glm::dvec3& indexHi,
                               glm::dvec3& lo, glm::dvec3& hi) {
  lo = glm::dvec3(std::numeric_limits<double>::max());
  hi = -lo;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 xyz((corner & 1) ? indexHi.x : indexLo.x, (corner & 2) ? indexHi.y : indexLo.y,
                         (corner & 4) ? indexHi.z : indexLo.z);
    const glm::dvec3 pWorld = glm::dvec3(worldFromIndex * glm::dvec4(xyz, 1.0));
    lo = glm::min(lo, pWorld);
    hi = glm::max(hi, pWorld);
  }
}

}  // namespace fcc::io
