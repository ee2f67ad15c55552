// What lies under the viewer's cursor: the surface point the ray through a pixel hit (from the depth
// the raycaster writes), in world space (pWorld) and the lattice's index space (xyz), the nearest FCC
// site (ijk) and the spline's value there, from bricks read on the CPU (io::BrickStore).
#pragma once

#include <glm/glm.hpp>

#include <map>
#include <memory>
#include <tuple>

#include "Camera.h"
#include "io/BrickStore.h"

namespace fcc::render {

struct CursorProbe {
  bool hit = false;
  bool values = false;         // ijk and the values below are known (an FCC store: probeSurface)
  glm::dvec3 pWorld{0.0};
  glm::dvec3 xyz{0.0};
  glm::ivec3 ijk{0};           // the FCC site nearest xyz
  float valueAtSite = 0.0f;    // the spline at ijk: for a prefiltered file, the data's sample there
  float valueAtPoint = 0.0f;   // the spline at xyz: the isovalue, to rounding (a check of the depth)
};

// The FCC site (even coordinate sum) nearest xyz.
glm::ivec3 nearestFccSite(const glm::dvec3& xyz);

// Evaluates the spline of a brick store on the CPU, keeping the few bricks it read.
class SplineProbe {
 public:
  explicit SplineProbe(const io::BrickStore& store) : store_(store) {}
  float valueAt(const glm::dvec3& xyz);
  float coefficientAt(const glm::ivec3& ijk);

 private:
  const io::BrickStore& store_;
  std::map<std::tuple<int, int, int>, std::unique_ptr<io::BrickValues>> bricks_;  // a handful: cleared when large
};

// The probe of pixel (px, py) (row 0 at the top) of a width x height image of `camera` whose depth
// there (distance along the unit ray, +inf on a miss) is `depth`.
// probePoint: the point only (any lattice; values false).
CursorProbe probePoint(const glm::dmat4& indexFromWorld, const Camera& camera, int px, int py, int width, int height,
                       float depth);
CursorProbe probeSurface(SplineProbe& spline, const glm::dmat4& indexFromWorld, const Camera& camera, int px, int py,
                         int width, int height, float depth);

}  // namespace fcc::render
