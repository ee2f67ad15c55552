// A CPU reference of direct volume rendering (issue 18; docs/DVR.md): the emission-absorption
// integral along a ray through any reconstruction of the layer (sparse/Reconstruction.h), front to
// back, in double precision, with a fixed longest step. It is what the GPU's DVR mode is checked
// against, as ReferenceRaycast is for the isosurface.
//
// Model: along the ray, extinction sigma(t) and premultiplied emission sigma(t) rgb(t) per world unit
// come from the medium at the reconstructed value s(t). Colour C = integral of T(t) sigma rgb dt, opacity
// 1 - T(t1), with transmittance T(t) = exp(-integral of sigma from t0 to t). Quadrature: each sub-step
// of length h <= step takes the medium at its midpoint as constant and is composited exactly
// (opacity 1 - exp(-sigma h), colour rgb times that): second order in the step for a smooth medium,
// first order across a discontinuity of the transfer function (bounds in docs/DVR.md).
//
// Skipping: with cell bounds (ReferenceRaycast.h's CellBounds, index space), a unit cell whose value
// range the medium maps to zero extinction everywhere is stepped over (it contributes nothing, exactly);
// the sub-steps of the other cells end at the cell's faces.
#pragma once

#include <glm/glm.hpp>

#include <functional>
#include <limits>
#include <vector>

#include "Reconstruction.h"
#include "ReferenceRaycast.h"
#include "TransferFunction.h"

namespace fcc {

// What the integrator reads.
struct DvrMedium {
  // (sigma r, sigma g, sigma b, sigma) per world unit at a value.
  std::function<glm::dvec4(double value)> at;
  // True only if sigma is zero for every value of [lo, hi].
  std::function<bool(double lo, double hi)> emptyOn;
};
// The transfer function itself (exact: its piecewise-linear opacity through extinctionFromOpacity).
// Copies the function.
DvrMedium dvrMedium(const TransferFunction& tf, const OpticalScale& scale);
// The sampled table, as the GPU reads it (lookup, zeroOn). Copies the table.
DvrMedium dvrMedium(const TransferTable& table);

// A ray in the reconstruction's index space whose parameter is the world distance: the point at t is
// o + t d, d being the index-space displacement of one world unit along the ray.
struct DvrRay {
  glm::dvec3 o{0.0};
  glm::dvec3 d{0.0, 0.0, 1.0};
  double t0 = 0.0, t1 = -1.0;  // world distances along the ray; empty when t1 <= t0
};
// A world ray (oWorld + t dWorld, dWorld of unit length) through a grid whose transform is
// worldFromIndex: the same ray in index space with t still the world distance.
DvrRay dvrRayFromWorld(const glm::dmat4& indexFromWorld, const glm::dvec3& oWorld, const glm::dvec3& dWorld, double t0,
                       double t1);

// Gradient shading (docs/DVR.md, shaders/dvr.glsl's FCC_DVR_SHADING): a sub-step's emission times
// kDvrShadingAmbient + (1 - kDvrShadingAmbient) |cos| of the angle between the world gradient of the
// reconstruction at its midpoint and the ray (a headlight, two-sided Lambert), 1 where the gradient is
// 0. gradientIndex: index-space gradient; dIndex: the ray's index displacement per world unit (DvrRay::d);
// normalFromIndex: the world gradient from the index-space one (the transpose of indexFromWorld's
// linear part).
inline constexpr double kDvrShadingAmbient = 0.3;
double dvrShade(const glm::dvec3& gradientIndex, const glm::dvec3& dIndex, const glm::dmat3& normalFromIndex);
// Its specular term: white light strength |cos|^power of the same angle (Blinn-Phong with the light at
// the eye: the half vector is the ray), emitted in proportion to the sub-step's opacity; 0 where the
// gradient is 0 or strength is 0.
double dvrSpecular(const glm::dvec3& gradientIndex, const glm::dvec3& dIndex, const glm::dmat3& normalFromIndex,
                   double strength, double power);

// Gradient shading under a directional light (shaders/dvr.glsl without its headlight): x, the
// emission's factor kDvrShadingAmbient + (1 - kDvrShadingAmbient) |cos| of the angle between the world
// gradient and towardsLightWorld; y, the white specular term strength |cos|^power of its angle with the
// half vector between towardsLightWorld and towardsEyeWorld (none where they are opposite); (1, 0)
// where the gradient is 0. Both directions unit, world space. With both the reversed ray's direction it
// is the headlight's dvrShade and dvrSpecular.
glm::dvec2 dvrShadeLit(const glm::dvec3& gradientIndex, const glm::dmat3& normalFromIndex, const glm::dvec3& towardsLightWorld,
                       const glm::dvec3& towardsEyeWorld, double strength, double power);

// A light of a light kit: the unit world direction towards it and its weight.
struct DvrKitLight {
  glm::dvec3 towardsWorld{0.0, 0.0, 1.0};
  double weight = 0.0;
};
// Gradient shading under a light kit (shaders/dvr.glsl's uDvrLight 2): directional lights `kit` and the
// headlight of weight headWeight, the weights adding up to 1; x and y are the weighted sums of each
// light's (dvrShadeLit's for the directional lights, dvrShade's and dvrSpecular's for the headlight;
// towardsEyeWorld is the reversed ray, unit, world).
glm::dvec2 dvrShadeKit(const glm::dvec3& gradientIndex, const glm::dvec3& dIndex, const glm::dmat3& normalFromIndex,
                       const std::vector<DvrKitLight>& kit, double headWeight, const glm::dvec3& towardsEyeWorld,
                       double strength, double power);

struct DvrOptions {
  double step = 1e-3;                 // world units: the longest sub-step
  bool shading = false;               // gradient shading (dvrShade), with this normalFromIndex
  double specular = 0.0, specularPower = 20.0;  // with shading: dvrSpecular's strength and power
  // With shading, the light (as viewer/DvrLight.h's DvrLight): the headlight (dvrShade, dvrSpecular);
  // the directional light towards lightWorld (unit, world space; dvrShadeLit); or a light kit, its
  // lights `kit` and the headlight of weight kitHeadWeight (dvrShadeKit).
  enum class Light { Headlight, Directional, Kit };
  Light light = Light::Headlight;
  glm::dvec3 lightWorld{0.0, 0.0, 1.0};
  std::vector<DvrKitLight> kit;
  double kitHeadWeight = 0.0;
  glm::dmat3 normalFromIndex{1.0};
  double terminationOpacity = 0.995;  // stop once the accumulated opacity reaches it (>= 1: only when the
                                      // transmittance is exactly 0)
};

struct DvrPixel {
  glm::dvec4 rgba{0.0};  // premultiplied colour, opacity
  // World distance along the ray where the accumulated opacity first reaches 0.5 (exact inside the
  // sub-step); +inf if it never does.
  double depth = std::numeric_limits<double>::infinity();
  long evaluations = 0;  // reconstruction evaluations (what skipping saves)
};

// One ray. `bounds` may be null (no skipping: uniform sub-steps over [t0, t1]). ValueError for a step
// that is not finite and positive.
DvrPixel integrateDvrRay(const Reconstruction& recon, const SiteValue& at, const CellBounds* bounds,
                         const DvrMedium& medium, const DvrRay& ray, const DvrOptions& options = {});

// An image: rayAt(x, y) for each pixel, row-major (index y * width + x), rows in parallel.
std::vector<DvrPixel> renderDvrImage(int width, int height, const std::function<DvrRay(int x, int y)>& rayAt,
                                     const Reconstruction& recon, const SiteValue& at, const CellBounds* bounds,
                                     const DvrMedium& medium, const DvrOptions& options = {});

}  // namespace fcc
