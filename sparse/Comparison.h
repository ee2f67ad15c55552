// The measurement behind `fccvdb compare`: an analytic field sampled on the CC, BCC and FCC lattices at
// equal sample budgets, reconstructed by every reconstruction of the layer, and measured against the
// field itself at seeded random points.
//
// A budget N is the number of sites inside the domain (the field's box [-e, e], [-1, 1]^3 for the
// analytic fields; volume V = 8 e.x e.y e.z): a lattice of density rho sites per unit of index volume
// gets the spacing h = (V rho / N)^(1/3) world units per index unit (site ijk is at h * ijk). Samples outside the domain are taken too (the stencils and prefilters read them), so no
// reconstruction is measured against a boundary.
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "AnalyticFields.h"
#include "Reconstruction.h"

namespace fcc {

// One lattice at one budget.
struct LatticeSampling {
  Lattice lattice;
  int64_t budget;
  double worldPerIndex;  // h
  int64_t samples;       // sites inside the domain
  glm::ivec3 reach;      // those sites: the lattice's sites ijk with |ijk| <= reach per axis
  glm::ivec3 boxMin, boxDims;  // the sampled index box, padded for stencils and prefilters
};
// The largest sampled box (integer points) a comparison holds: 2^26, whose samples take 256 MiB and
// the renders' cell bounds 1 GiB more (CellBounds: 16 bytes a point while built). About 13 M samples
// on BCC (the box holds 4 points a site and the padding), 27 M on FCC, 55 M on CC. ValueError beyond.
inline constexpr int64_t kMaxComparisonBoxPoints = int64_t(1) << 26;
// The largest render (pixels) a comparison makes: 2048^2.
inline constexpr int64_t kMaxComparisonPixels = int64_t(2048) * 2048;
// The domain is [-halfExtent, halfExtent] (the field's).
LatticeSampling samplingFor(Lattice lattice, int64_t budget, const glm::dvec3& halfExtent = glm::dvec3(1.0));
// World distance between nearest sites: h times 1 (CC), sqrt(3) (BCC), sqrt(2) (FCC).
double nearestSiteDistance(const LatticeSampling& sampling);

struct CompareOptions {
  std::vector<int64_t> budgets;
  double iso = 0.5;
  int points = 20000;   // uniform points for value and gradient errors, and points on the isosurface
  uint64_t seed = 1;
  std::vector<std::string> reconstructions;  // empty: all of them
  int width = 0, height = 0;  // renders of this size against the field's own (0: none)
  bool keepImages = true;     // keep each row's images (false: only their measurements)
};

// The camera every render of a comparison uses (world space): the domain seen from above at a slant,
// from a distance proportional to its size.
struct CompareCamera {
  explicit CompareCamera(const glm::dvec3& halfExtent = glm::dvec3(1.0))
      : eye(glm::dvec3(1.9, -2.7, 2.3) * std::max(halfExtent.x, std::max(halfExtent.y, halfExtent.z))) {}
  glm::dvec3 eye, lookAt{0.0}, up{0.0, 0.0, 1.0};
  double fovDeg = 38.0;
};

// An 8-bit RGB image, row 0 at the top.
struct RgbImage {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
};

struct CompareRow {
  std::string lattice;
  std::string reconstruction;
  int64_t budget = 0;
  int64_t samples = 0;
  double spacing = 0.0;  // nearestSiteDistance
  int stencil = 0;
  // |s - f| at uniform random points of the domain.
  double valueRmsError = 0.0, valueMaxError = 0.0;
  // Angle between grad s and grad f at the same points (degrees; points where grad f vanishes are left
  // out). NaN (JSON null) where no point was measured.
  double gradientErrorMeanDeg = 0.0, gradientErrorP95Deg = 0.0, gradientErrorMaxDeg = 0.0;
  // The same angle at points on the true isosurface f = iso: the surface normal's error.
  double normalErrorMeanDeg = 0.0, normalErrorP95Deg = 0.0, normalErrorMaxDeg = 0.0;
  int surfacePoints = 0;
  // From a render against the field's own render (same camera): the angle between the normals where
  // both hit, pixels where only one hits, and the mean distance between the hits along the ray.
  std::optional<double> renderNormalErrorMeanDeg, renderNormalErrorP95Deg, renderDepthErrorMean;
  int64_t renderHitMissPixels = 0, renderBothHitPixels = 0;
  RgbImage shaded, normalError;  // the method's isosurface, and its normal error as a heat map
  std::optional<double> fps;  // none: no GPU timing
};

// Seeded points on the isosurface f = iso inside 0.95 times the domain (Newton steps from uniform points).
std::vector<glm::dvec3> isosurfacePoints(const AnalyticField& field, double iso, int count, uint64_t seed);

// Every row; ValueError before any work for an unknown reconstruction, a budget beyond memory, renders
// too large, or an isovalue the field does not take. With renders, `truthImage` (if given) receives
// the field's own isosurface (the first row of the image grid).
std::vector<CompareRow> compareReconstructions(const AnalyticField& field, const CompareOptions& options,
                                               RgbImage* truthImage = nullptr);

}  // namespace fcc
