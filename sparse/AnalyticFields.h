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
};

// The valid names: "marschner-lobb" (Marschner and Lobb 1994, f_M = 6, alpha = 0.25: its detail runs
// along z-aligned cylinders, which is known to favour some lattices) and "random-waves" (an isotropic,
// band-limited field: 64 plane waves of one frequency, 3 cycles per unit, in seeded random directions
// and phases).
const std::vector<std::string>& analyticFieldNames();
// ValueError listing the valid names for an unknown one.
std::unique_ptr<AnalyticField> makeAnalyticField(std::string_view name, uint64_t seed = 1);

}  // namespace fcc
