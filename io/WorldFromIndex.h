// worldFromIndex of a grid's transform as a column-vector matrix, for the stores that render grids
// (BrickStore, CartesianBrickStore): the renderer takes affine maps only.
#pragma once

#include <glm/glm.hpp>
#include <openvdb/math/Transform.h>

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

}  // namespace fcc::io
