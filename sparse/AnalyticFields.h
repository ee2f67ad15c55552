// Analytic test fields for `compare`: a value and an exact gradient at any point of their domain
// [-1, 1]^3 (world space), so reconstructions from samples can be measured against the truth.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace fcc {

class AnalyticField {
 public:
  virtual ~AnalyticField() = default;
  virtual std::string_view name() const = 0;
  virtual double value(const glm::dvec3& pWorld) const = 0;
  virtual glm::dvec3 gradient(const glm::dvec3& pWorld) const = 0;
  // The isovalue its surface is usually shown at.
  virtual double defaultIso() const = 0;
  // The domain is [-halfExtent, halfExtent] (world space).
  virtual glm::dvec3 halfExtent() const { return glm::dvec3(1.0); }
  // A step short enough for a raycast of the field to cross no pair of roots: a 25th of the analytic
  // fields' shortest wavelength (marschner-lobb's radial detail is about 1/9.4 of a unit), a quarter voxel
  // of a volume.
  virtual double rootSeparatingStep() const { return 0.004; }
};

// The valid names: "marschner-lobb" (Marschner and Lobb 1994, f_M = 6, alpha = 0.25: its detail runs
// along z-aligned cylinders, which is known to favour some lattices) and "random-waves" (an isotropic,
// band-limited field: 64 plane waves of one frequency, 3 cycles per unit, in seeded random directions
// and phases).
const std::vector<std::string>& analyticFieldNames();
// ValueError listing the valid names for an unknown one.
std::unique_ptr<AnalyticField> makeAnalyticField(std::string_view name, uint64_t seed = 1);

// A Cartesian volume taken as the truth: its interpolating tricubic B-spline (it passes through the
// samples; C2, exact gradient), scaled so that its longest side spans [-1, 1] (world = spacing-aware
// voxel position, centred). The default isovalue is Otsu's threshold of its values, the value of its
// first voxel (usually the air around a scan) left out.
std::unique_ptr<AnalyticField> makeVolumeField(std::string name, const glm::ivec3& dims, const glm::dvec3& spacing,
                                               const std::vector<float>& values);

}  // namespace fcc
