#include "StreamPaths.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "BenchOrbit.h"
#include "sparse/Error.h"

namespace fcc::cli {

std::vector<render::Camera> orbitPath(const render::Camera& start, int frames) {
  std::vector<render::Camera> path;
  for (int i = 0; i < frames; ++i) path.push_back(orbitStep(start, i, frames));
  return path;
}

std::vector<render::Camera> zoomPath(const render::Camera& start, const glm::dvec3& target, double brickWorldSize,
                                     int frames) {
  const glm::dvec3 view = start.lookat - start.eye;
  const double d0 = glm::length(view);
  const glm::dvec3 forward = view / d0;
  // The distance at which the view's height at the look-at point is one brick.
  const double d1 = std::min(d0, brickWorldSize / (2.0 * std::tan(glm::radians(start.fovYDegrees) * 0.5)));
  std::vector<render::Camera> path;
  for (int i = 0; i < frames; ++i) {
    const double t = frames > 1 ? double(i) / double(frames - 1) : 0.0;
    const double d = d0 * std::pow(d1 / d0, t);
    // How far along both lines: 0 at d0, 1 at d1 (the eye is lookat - forward * d: linear in f too).
    const double f = d0 > d1 ? (d0 - d) / (d0 - d1) : t;
    render::Camera c = start;
    c.lookat = glm::mix(start.lookat, target, f);
    c.eye = c.lookat - forward * d;
    path.push_back(c);
  }
  return path;
}

glm::dvec3 zoomTarget(const render::BrickSource& source, const glm::dvec3& near, float iso, double& brickWorldSize) {
  const glm::dmat4& worldFromIndex = source.worldFromIndex();
  brickWorldSize = 16.0 * std::cbrt(std::abs(glm::determinant(glm::dmat3(worldFromIndex))));
  glm::dvec3 best = near, bestAny = near;
  double bestDistance = std::numeric_limits<double>::infinity(), bestAnyDistance = bestDistance;
  source.forEachVaryingBrick([&](const glm::ivec3& brick, float lo, float hi) {
    const glm::dvec3 centre = glm::dvec3(worldFromIndex * glm::dvec4((glm::dvec3(brick) + 0.5) * 16.0, 1.0));
    const double distance = glm::length(centre - near);
    if (distance < bestAnyDistance) bestAnyDistance = distance, bestAny = centre;
    if (lo <= iso && iso <= hi && distance < bestDistance) bestDistance = distance, best = centre;
  });
  return std::isfinite(bestDistance) ? best : bestAny;
}

std::vector<render::Camera> jumpsPath(const render::Camera& start, const glm::dvec3& lo, const glm::dvec3& hi,
                                      int frames, int holdFrames, uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double d0 = glm::length(start.eye - start.lookat);
  std::vector<render::Camera> path;
  render::Camera c = start;
  for (int i = 0; i < frames; ++i) {
    if (i % std::max(holdFrames, 1) == 0) {
      c = start;
      c.lookat = lo + (hi - lo) * glm::dvec3(0.25 + 0.5 * unit(random), 0.25 + 0.5 * unit(random), 0.25 + 0.5 * unit(random));
      glm::dvec3 direction;
      do {  // uniform on the sphere; not along up, which would make the camera degenerate
        const double z = 2.0 * unit(random) - 1.0, phi = 2.0 * M_PI * unit(random), r = std::sqrt(1.0 - z * z);
        direction = {r * std::cos(phi), r * std::sin(phi), z};
      } while (glm::length(glm::cross(direction, glm::normalize(c.up))) < 1e-3);
      c.eye = c.lookat + direction * d0 * (0.25 + 0.75 * unit(random));
    }
    path.push_back(c);
  }
  return path;
}

std::vector<render::Camera> recordedPath(const render::CameraPath& path, double frameSeconds, int frames) {
  if (path.points.empty()) throw ValueError("camera path: no frames");
  const double duration = path.duration(), t0 = path.points.front().seconds;
  std::vector<render::Camera> out;
  if (!(duration > 0.0)) {  // no time passed: the cameras in order, spread over the frames asked for
    const std::size_t n = path.points.size();
    const int count = frames > 0 ? frames : int(n);
    for (int i = 0; i < count; ++i) {
      const std::size_t at = count > 1 ? std::size_t(std::llround(double(i) * double(n - 1) / double(count - 1))) : 0;
      out.push_back(path.points[at].camera);
    }
    return out;
  }
  const int count = frames > 0 ? frames : int(std::floor(duration / frameSeconds + 1e-9)) + 1;
  const double step = frames > 0 ? (count > 1 ? duration / double(count - 1) : 0.0) : frameSeconds;
  for (int i = 0; i < count; ++i) out.push_back(render::cameraAt(path, t0 + step * double(i)));
  return out;
}

}  // namespace fcc::cli
