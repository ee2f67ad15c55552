// The patient's axes on an FCC grid (docs/FORMAT.md): `convert` records where a medical volume's
// superior and anterior sides point in the grid's world frame, and the default camera of `render`,
// `view` and `bench` reads them to show the data upright, anterior towards the viewer.
#pragma once

#include <openvdb/openvdb.h>

#include <optional>
#include <string>

#include "DenseVolume.h"

namespace fcc::meta {
inline constexpr const char* kPatientSuperior = "fcc_patient_superior";  // Vec3d: world direction, unit
inline constexpr const char* kPatientAnterior = "fcc_patient_anterior";  // Vec3d: world direction, unit
}  // namespace fcc::meta

namespace fcc::io {

void recordPatientAxes(openvdb::GridBase& grid, const PatientAxes& axes);

// The grid's patient axes; empty when it has none (data that is not a patient's, files from before).
// InputError naming `path` when only one of the two is there, or they are not finite, zero or parallel.
std::optional<PatientAxes> patientAxesOf(const openvdb::GridBase& grid, const std::string& path);

}  // namespace fcc::io
