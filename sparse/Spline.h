// C++ face of the shared spline header (sparse/FccSpline.h): GLM vector types, and evaluation over any
// coefficient source.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "FccSpline.h"
#include "FccRay.h"
#include "FccChord.h"

namespace fcc::spline {

// Evaluates the spline at xyz (lattice index space). `coefficientAt(glm::ivec3 ijk) -> float` returns the
// prefiltered coefficient c at FCC site ijk (the background where nothing is stored).
template <class CoefficientAt>
FccSamples gatherSamples(const FccFrame& frame, CoefficientAt&& coefficientAt) {
  FccSamples s;
  for (int i = 0; i < FCC_STENCIL_SIZE; ++i) s.v[i] = coefficientAt(fcc_stencil_site(frame, i));
  return s;
}

template <class CoefficientAt>
float evaluate(const glm::vec3& xyz, CoefficientAt&& coefficientAt) {
  const FccFrame frame = fcc_locate(xyz);
  return fcc_value(gatherSamples(frame, coefficientAt), frame);
}

template <class CoefficientAt>
FccValueGradient evaluateWithGradient(const glm::vec3& xyz, CoefficientAt&& coefficientAt) {
  const FccFrame frame = fcc_locate(xyz);
  return fcc_value_gradient(gatherSamples(frame, coefficientAt), frame);
}

// Bounds of the spline on the unit cube at `corner`: min and max over the BB-coefficients of its five
// tetrahedral pieces (conservative by the convex-hull property).
template <class CoefficientAt>
FccRange cubeBounds(const glm::ivec3& corner, CoefficientAt&& coefficientAt) {
  FccRange bounds{std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()};
  for (int piece = 0; piece < 5; ++piece) {
    const FccFrame frame = fcc_locate(fcc_piece_centroid(corner, piece));
    const FccRange r = fcc_cubic_range(fcc_cubic(gatherSamples(frame, coefficientAt), frame.type));
    bounds.lo = std::min(bounds.lo, r.lo);
    bounds.hi = std::max(bounds.hi, r.hi);
  }
  return bounds;
}

inline bool isFccSite(const glm::ivec3& ijk) { return ((ijk.x + ijk.y + ijk.z) & 1) == 0; }

// q_fcc applied at one site: `sampleAt(ijk)` returns the raw sample V.
template <class SampleAt>
float prefilterAt(const glm::ivec3& ijk, SampleAt&& sampleAt) {
  float neighbourSum = 0.0f;
  for (int n = 0; n < 12; ++n) neighbourSum += sampleAt(ijk + fcc_neighbour_offset(n));
  return fcc_prefilter(sampleAt(ijk), neighbourSum);
}

}  // namespace fcc::spline
