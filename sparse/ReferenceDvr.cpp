#include "ReferenceDvr.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include <tbb/parallel_for.h>

#include "Error.h"

namespace fcc {

DvrMedium dvrMedium(const TransferFunction& tf, const OpticalScale& scale) {
  validateOpticalScale(scale);
  auto function = std::make_shared<const TransferFunction>(tf);
  DvrMedium medium;
  medium.at = [function, scale](double v) {
    const double sigma = extinctionFromOpacity(function->opacity(v), scale);
    return glm::dvec4(sigma * function->color(v), sigma);
  };
  medium.emptyOn = [function, scale](double lo, double hi) {
    return function->maxExtinctionOn(lo, hi, scale) <= 0.0;
  };
  return medium;
}

DvrMedium dvrMedium(const TransferTable& table) {
  auto copy = std::make_shared<const TransferTable>(table);
  DvrMedium medium;
  medium.at = [copy](double v) { return glm::dvec4(copy->lookup(v)); };
  medium.emptyOn = [copy](double lo, double hi) { return copy->zeroOn(lo, hi); };
  return medium;
}

DvrRay dvrRayFromWorld(const glm::dmat4& indexFromWorld, const glm::dvec3& oWorld, const glm::dvec3& dWorld, double t0,
                       double t1) {
  DvrRay ray;
  ray.o = glm::dvec3(indexFromWorld * glm::dvec4(oWorld, 1.0));
  ray.d = glm::dvec3(indexFromWorld * glm::dvec4(dWorld, 0.0));
  ray.t0 = t0;
  ray.t1 = t1;
  return ray;
}

namespace {

// Front-to-back compositing of constant sub-steps.
struct Accumulator {
  const DvrOptions& options;
  DvrPixel pixel;
  double transmittance = 1.0;
  glm::dvec3 towardsEyeWorld{0.0};  // the ray's unit world direction reversed (a directional light's half vector)

  // Nothing further can show once the transmittance is 0; otherwise the termination opacity (>= 1: never).
  bool done() const {
    return transmittance <= 0.0 || (options.terminationOpacity < 1.0 && 1.0 - transmittance >= options.terminationOpacity);
  }

  void add(const glm::dvec4& e, double t, double h) {
    const double sigma = e.a;
    if (sigma <= 0.0) {
      // Emission without absorption (only a medium that is not a transfer function has it).
      pixel.rgba += glm::dvec4(transmittance * h * glm::dvec3(e), 0.0);
      return;
    }
    const double alpha = opacityOfSegment(sigma, h);
    if (transmittance > 0.5 && transmittance * (1.0 - alpha) <= 0.5 && std::isinf(pixel.depth))
      pixel.depth = t + std::min(h, std::log(2.0 * transmittance) / sigma);
    pixel.rgba += glm::dvec4(transmittance * alpha * glm::dvec3(e) / sigma, 0.0);
    transmittance *= 1.0 - alpha;
    pixel.rgba.a = 1.0 - transmittance;
  }
};

// Midpoint sub-steps of at most options.step over [ta, tb].
void integrateSpan(const Reconstruction& recon, const SiteValue& at, const DvrMedium& medium, const DvrRay& ray,
                   double ta, double tb, Accumulator& acc) {
  const double length = tb - ta;
  if (!(length > 0.0)) return;
  const double count = std::ceil(length / acc.options.step);
  const long n = std::max(1L, long(count));
  const double h = length / double(n);
  for (long k = 0; k < n && !acc.done(); ++k) {
    const double t = ta + double(k) * h;
    const glm::dvec3 p = ray.o + (t + 0.5 * h) * ray.d;
    const spline::FccValueGradient vg = recon.evaluate(glm::vec3(p), at);
    ++acc.pixel.evaluations;
    glm::dvec4 e = medium.at(vg.value);
    if (acc.options.shading) {
      // e is premultiplied by the extinction: the white highlight too.
      const glm::dvec3 g(vg.gradient);
      const DvrOptions& o = acc.options;
      glm::dvec2 lit;
      switch (o.light) {
        case DvrOptions::Light::Headlight:
          lit = glm::dvec2(dvrShade(g, ray.d, o.normalFromIndex),
                           dvrSpecular(g, ray.d, o.normalFromIndex, o.specular, o.specularPower));
          break;
        case DvrOptions::Light::Directional:
          lit = dvrShadeLit(g, o.normalFromIndex, o.lightWorld, acc.towardsEyeWorld, o.specular, o.specularPower);
          break;
        case DvrOptions::Light::Kit:
          lit = dvrShadeKit(g, ray.d, o.normalFromIndex, o.kit, o.kitHeadWeight, acc.towardsEyeWorld, o.specular,
                            o.specularPower);
          break;
      }
      e = glm::dvec4(glm::dvec3(e) * lit.x + e.a * lit.y, e.a);
    }
    acc.add(e, t, h);
  }
}

}  // namespace

double dvrShade(const glm::dvec3& gradientIndex, const glm::dvec3& dIndex, const glm::dmat3& normalFromIndex) {
  const double len = glm::length(normalFromIndex * gradientIndex);
  if (!(len > 0.0)) return 1.0;
  return kDvrShadingAmbient + (1.0 - kDvrShadingAmbient) * std::min(std::abs(glm::dot(gradientIndex, dIndex)) / len, 1.0);
}

double dvrSpecular(const glm::dvec3& gradientIndex, const glm::dvec3& dIndex, const glm::dmat3& normalFromIndex,
                   double strength, double power) {
  const double len = glm::length(normalFromIndex * gradientIndex);
  if (!(len > 0.0) || !(strength > 0.0)) return 0.0;
  return strength * std::pow(std::min(std::abs(glm::dot(gradientIndex, dIndex)) / len, 1.0), power);
}

glm::dvec2 dvrShadeLit(const glm::dvec3& gradientIndex, const glm::dmat3& normalFromIndex, const glm::dvec3& towardsLightWorld,
                       const glm::dvec3& towardsEyeWorld, double strength, double power) {
  const glm::dvec3 n = normalFromIndex * gradientIndex;
  const double len = glm::length(n);
  if (!(len > 0.0)) return glm::dvec2(1.0, 0.0);
  const double cLight = std::min(std::abs(glm::dot(n, towardsLightWorld)) / len, 1.0);
  const glm::dvec3 sum = towardsLightWorld + towardsEyeWorld;
  const double sumLength = glm::length(sum);
  const double cHalf = sumLength > 0.0 ? std::min(std::abs(glm::dot(n, sum)) / (len * sumLength), 1.0) : 0.0;
  return glm::dvec2(kDvrShadingAmbient + (1.0 - kDvrShadingAmbient) * cLight,
                    strength > 0.0 ? strength * std::pow(cHalf, power) : 0.0);
}

glm::dvec2 dvrShadeKit(const glm::dvec3& gradientIndex, const glm::dvec3& dIndex, const glm::dmat3& normalFromIndex,
                       const std::vector<DvrKitLight>& kit, double headWeight, const glm::dvec3& towardsEyeWorld,
                       double strength, double power) {
  glm::dvec2 sum = headWeight * glm::dvec2(dvrShade(gradientIndex, dIndex, normalFromIndex),
                                           dvrSpecular(gradientIndex, dIndex, normalFromIndex, strength, power));
  for (const DvrKitLight& light : kit)
    sum += light.weight * dvrShadeLit(gradientIndex, normalFromIndex, light.towardsWorld, towardsEyeWorld, strength, power);
  return sum;
}

DvrPixel integrateDvrRay(const Reconstruction& recon, const SiteValue& at, const CellBounds* bounds,
                         const DvrMedium& medium, const DvrRay& ray, const DvrOptions& options) {
  if (!std::isfinite(options.step) || !(options.step > 0.0))
    throw ValueError("the DVR reference step must be a positive number of world units, not " + std::to_string(options.step));
  Accumulator acc{options, DvrPixel{}};
  // The world direction: ray.d is indexFromWorld's linear part (normalFromIndex's transpose) times it.
  if (options.shading && options.light != DvrOptions::Light::Headlight)
    acc.towardsEyeWorld = -glm::normalize(glm::inverse(glm::transpose(options.normalFromIndex)) * ray.d);
  if (!(ray.t1 > ray.t0)) return acc.pixel;
  if (!std::isfinite(ray.t0) || !std::isfinite(ray.t1))
    throw ValueError("a DVR reference ray needs a finite interval [t0, t1]");
  if (!bounds) {
    integrateSpan(recon, at, medium, ray, ray.t0, ray.t1, acc);
    return acc.pixel;
  }
  // Unit cells of index space by DDA (as firstHit), in double.
  glm::dvec3 d = ray.d;
  for (int i = 0; i < 3; ++i)
    if (std::abs(d[i]) < 1e-300) d[i] = 1e-300;
  const glm::dvec3 invD = 1.0 / d;
  glm::ivec3 cell(glm::floor(ray.o + ray.t0 * d));
  const glm::ivec3 stepDir(glm::sign(d));
  glm::dvec3 tMax = (glm::dvec3(cell) + glm::dvec3(glm::greaterThan(d, glm::dvec3(0.0))) - ray.o) * invD;
  const glm::dvec3 tDelta = glm::abs(invD);
  double tCell = ray.t0;
  while (tCell < ray.t1 && !acc.done()) {
    const double tExit = std::min(std::min(std::min(tMax.x, tMax.y), tMax.z), ray.t1);
    if (tExit > tCell) {
      const glm::vec2 range = bounds->at(cell);
      if (!medium.emptyOn(range.x, range.y)) integrateSpan(recon, at, medium, ray, tCell, tExit, acc);
    }
    if (tExit >= ray.t1) break;
    tCell = std::max(tCell, tExit);
    if (tMax.x <= tMax.y && tMax.x <= tMax.z) {
      cell.x += stepDir.x;
      tMax.x += tDelta.x;
    } else if (tMax.y <= tMax.z) {
      cell.y += stepDir.y;
      tMax.y += tDelta.y;
    } else {
      cell.z += stepDir.z;
      tMax.z += tDelta.z;
    }
  }
  return acc.pixel;
}

std::vector<DvrPixel> renderDvrImage(int width, int height, const std::function<DvrRay(int x, int y)>& rayAt,
                                     const Reconstruction& recon, const SiteValue& at, const CellBounds* bounds,
                                     const DvrMedium& medium, const DvrOptions& options) {
  std::vector<DvrPixel> image(size_t(std::max(width, 0)) * size_t(std::max(height, 0)));
  tbb::parallel_for(0, std::max(height, 0), [&](int y) {
    for (int x = 0; x < width; ++x)
      image[size_t(y) * size_t(width) + size_t(x)] = integrateDvrRay(recon, at, bounds, medium, rayAt(x, y), options);
  });
  return image;
}

}  // namespace fcc
