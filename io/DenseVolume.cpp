#include "DenseVolume.h"

#include <filesystem>
#include <fstream>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "MessageText.h"
#include "sparse/Error.h"

namespace fcc::io {
namespace {

struct ScalarTypeInfo {
  ScalarType type;
  const char* name;
  size_t bytes;
};

constexpr ScalarTypeInfo kScalarTypes[] = {
    {ScalarType::U8, "u8", 1},   {ScalarType::I8, "i8", 1},   {ScalarType::U16, "u16", 2}, {ScalarType::I16, "i16", 2},
    {ScalarType::U32, "u32", 4}, {ScalarType::I32, "i32", 4}, {ScalarType::F32, "f32", 4}, {ScalarType::F64, "f64", 8},
};

const ScalarTypeInfo& infoOf(ScalarType type) {
  for (const ScalarTypeInfo& info : kScalarTypes)
    if (info.type == type) return info;
  return kScalarTypes[0];  // unreachable: kScalarTypes lists every enumerator
}

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

bool endsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

size_t DenseVolume::index(int i, int j, int k) const {
  return size_t(i) + size_t(dims.x) * (size_t(j) + size_t(dims.y) * size_t(k));
}

float DenseVolume::at(int i, int j, int k) const { return values[index(i, j, k)]; }

bool DenseVolume::contains(int i, int j, int k) const {
  return i >= 0 && j >= 0 && k >= 0 && i < dims.x && j < dims.y && k < dims.z;
}

ScalarType parseScalarType(const std::string& name) {
  const std::string key = lowercase(name);
  for (const ScalarTypeInfo& info : kScalarTypes)
    if (key == info.name) return info.type;
  throw ValueError("unknown scalar type " + quotedText(name) + "; valid: u8, i8, u16, i16, u32, i32, f32, f64");
}

const char* scalarTypeName(ScalarType type) { return infoOf(type).name; }

size_t scalarTypeSize(ScalarType type) { return infoOf(type).bytes; }

std::optional<PatientAxes> patientAxesFrom(const glm::dmat3& patientFromWorld, const glm::dvec3& superiorInPatient,
                                           const glm::dvec3& anteriorInPatient) {
  const glm::dmat3& m = patientFromWorld;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      if (!std::isfinite(m[c][r])) return std::nullopt;
  // Singular, relative to the columns' lengths (a zero pixdim, a degenerate sform).
  const double scale = glm::length(m[0]) * glm::length(m[1]) * glm::length(m[2]);
  if (!(std::abs(glm::determinant(m)) > 1e-9 * scale)) return std::nullopt;
  const glm::dmat3 worldFromPatient = glm::inverse(m);
  PatientAxes axes;
  axes.superior = glm::normalize(worldFromPatient * superiorInPatient);
  axes.anterior = glm::normalize(worldFromPatient * anteriorInPatient);
  return axes;
}

uint64_t checkedVoxelCount(const glm::ivec3& dims, const std::string& path) {
  if (dims.x < 1 || dims.y < 1 || dims.z < 1)
    throw InputError(path + ": dims " + commaList(dims) + " are invalid: every dimension must be at least 1");
  // Each factor is below 2^31, so x*y fits; compare before the last multiplication so it cannot overflow.
  const uint64_t xy = uint64_t(dims.x) * uint64_t(dims.y);
  if (xy > kMaxVoxelCount / uint64_t(dims.z)) {
    const long double count = static_cast<long double>(xy) * dims.z;
    char countText[32];
    std::snprintf(countText, sizeof countText, "%.3Lg", count);
    throw InputError(path + ": dims " + commaList(dims) + " make " + countText + " voxels; at most " +
                     std::to_string(kMaxVoxelCount) + " (2^34) are supported");
  }
  return xy * uint64_t(dims.z);
}

Format detectFormat(const std::string& path) {
  const std::string name = lowercase(path);
  if (endsWith(name, ".vdb")) return Format::Vdb;
  if (endsWith(name, ".nrrd") || endsWith(name, ".nhdr")) return Format::Nrrd;
  if (endsWith(name, ".nii") || endsWith(name, ".nii.gz")) return Format::Nifti;
  if (endsWith(name, ".mha") || endsWith(name, ".mhd")) return Format::MetaImage;
  if (endsWith(name, ".dcm") || endsWith(name, ".ima")) return Format::Dicom;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return Format::Dicom;
  // DICOM Part 10 files: a 128-byte preamble, then "DICM"; their names often have no extension.
  char marker[4] = {};
  std::ifstream in(path, std::ios::binary);
  if (in.seekg(128) && in.read(marker, 4) && std::string(marker, 4) == "DICM") return Format::Dicom;
  return Format::Raw;
}

}  // namespace fcc::io
