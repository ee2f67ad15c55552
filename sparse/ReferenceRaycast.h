// A slow, exact CPU raycaster over any reconstruction of the layer (sparse/Reconstruction.h): the
// reference the device raycasters are checked against, and what `compare` renders with.
//
// A ray walks the unit cells of index space; a cell whose conservative bounds exclude the isovalue is
// skipped; otherwise it is cut at the reconstruction's piece boundaries (cellSplits), and on each
// sub-segment the piece's polynomial along the ray (degree info().rayDegree) is taken from that many
// + 1 values of the piece, put in Bernstein form, and its first root found by subdivision
// (ReconCommon.h). No fixed step: a root is found or excluded by the polynomial itself.
#pragma once

#include <glm/glm.hpp>

#include <vector>

#include "AnalyticFields.h"
#include "LatticeSamples.h"
#include "Reconstruction.h"

namespace fcc {

// Per unit cell [c, c + 1]^3 of a sampled box: the min and max of every site value within 3 index
// units of it, which bounds every reconstruction of the layer there (each is a convex combination of
// stencil values no further than that; the FCC box spline's and the B-spline's weights are
// non-negative). Cells outside the box read as the background.
class CellBounds {
 public:
  explicit CellBounds(const LatticeSamples& samples);
  // (min, max) of the cell at `cell`, or (background, background) outside.
  glm::vec2 at(const glm::ivec3& cell) const;

 private:
  glm::ivec3 min_, dims_;
  float background_;
  std::vector<glm::vec2> ranges_;
};

struct RayHit {
  bool hit = false;
  float t = 0.0f;
  glm::vec3 gradient{0.0f};  // index space
};

// The first point of {s = iso} on o + t d, t in [t0, t1] (index space).
RayHit firstHit(const Reconstruction& recon, const SiteValue& at, const CellBounds& bounds, const glm::vec3& o,
                const glm::vec3& d, float t0, float t1, float iso);

// The same for an analytic field in world space: steps of `step` with a sign test, then bisection.
// Exact for every root crossed with a sign change; a pair of roots closer than the step is missed.
struct WorldHit {
  bool hit = false;
  double t = 0.0;
  glm::dvec3 gradient{0.0};
};
WorldHit firstHitAnalytic(const AnalyticField& field, const glm::dvec3& o, const glm::dvec3& d, double t0, double t1,
                          double iso, double step);

}  // namespace fcc
