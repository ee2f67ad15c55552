#include "PatientMetadata.h"

#include <cmath>

#include "MessageText.h"
#include "sparse/Error.h"

namespace fcc::io {

void recordPatientAxes(openvdb::GridBase& grid, const PatientAxes& axes) {
  const auto vec = [](const glm::dvec3& v) { return openvdb::Vec3DMetadata(openvdb::Vec3d(v.x, v.y, v.z)); };
  grid.insertMeta(meta::kPatientSuperior, vec(axes.superior));
  grid.insertMeta(meta::kPatientAnterior, vec(axes.anterior));
}

std::optional<PatientAxes> patientAxesOf(const openvdb::GridBase& grid, const std::string& path) {
  const auto superior = grid.getMetadata<openvdb::Vec3DMetadata>(meta::kPatientSuperior);
  const auto anterior = grid.getMetadata<openvdb::Vec3DMetadata>(meta::kPatientAnterior);
  if (!superior && !anterior) return std::nullopt;
  if (!superior || !anterior)
    throw InputError(path + ": metadata " + (superior ? meta::kPatientSuperior : meta::kPatientAnterior) + " without " +
                     (superior ? meta::kPatientAnterior : meta::kPatientSuperior) + "; the file is damaged");
  const auto text = [](const glm::dvec3& v) { return numberText(v.x) + "," + numberText(v.y) + "," + numberText(v.z); };
  const auto toGlm = [](const openvdb::Vec3d& v) { return glm::dvec3(v.x(), v.y(), v.z()); };
  PatientAxes axes{toGlm(superior->value()), toGlm(anterior->value())};
  const auto finite = [](const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  const double s = glm::length(axes.superior), a = glm::length(axes.anterior);
  if (!finite(axes.superior) || !finite(axes.anterior) || !(s > 0.0) || !(a > 0.0) || !std::isfinite(s * a) ||
      !(glm::length(glm::cross(axes.superior / s, axes.anterior / a)) > 1e-6))
    throw InputError(path + ": metadata " + meta::kPatientSuperior + " (" + text(axes.superior) + ") and " +
                     meta::kPatientAnterior + " (" + text(axes.anterior) +
                     ") must be finite, nonzero and not parallel; the file is damaged");
  axes.superior /= s;
  axes.anterior /= a;
  return axes;
}

}  // namespace fcc::io
