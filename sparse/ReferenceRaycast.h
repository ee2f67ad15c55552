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

#include <limits>
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

// Several surfaces {s = isos[k]} at once: every crossing of any of them along o + t d, t in [t0, t1]
// (index space), in order of t, at most maxCrossings. The cells are walked as firstHit walks them
// (skipped where `bounds`, if given, exclude every value); on each piece sub-segment the polynomial is
// taken as firstHit takes it and, per surface, sampled in double at 64 equal steps, every change of
// side (s < iso or not) bisected to double precision; a side at a piece's start other than where the
// previous piece ended is a crossing at the start (firstHit's join rule). Independent of the GPU's
// root finding; a pair of crossings closer than 1/64 of a sub-segment (a touch) is not seen.
struct SurfaceCrossing {
  float t = 0.0f;
  int surface = 0;
  glm::vec3 gradient{0.0f};  // index space
};
std::vector<SurfaceCrossing> surfaceCrossings(const Reconstruction& recon, const SiteValue& at, const CellBounds* bounds,
                                              const glm::vec3& o, const glm::vec3& d, float t0, float t1,
                                              const std::vector<float>& isos, std::size_t maxCrossings = 64);

// The renderer's composite of crossings (viewer/Raycaster.h, several surfaces): each shaded two-sided
// Lambert with 0.15 ambient in its surface's colour, composited front to back with its opacity
// (premultiplied) until the transmittance is at most stopTransmittance. In double.
struct SurfaceLook {
  glm::dvec3 color{1.0};  // linear
  double opacity = 1.0;
};
struct SurfacePixel {
  glm::dvec4 rgba{0.0};  // premultiplied; A = 1 - the transmittance left
  double depth = std::numeric_limits<double>::infinity();  // the first crossing's (world distance)
  glm::dvec3 normal{0.0};                                  // its unit world normal
};
SurfacePixel compositeCrossings(const std::vector<SurfaceCrossing>& crossings, const std::vector<SurfaceLook>& looks,
                                const glm::dmat3& normalFromIndex, const glm::dvec3& dirWorld,
                                const glm::dvec3& lightWorld, double stopTransmittance);

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
