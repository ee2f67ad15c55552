// A Cartesian volume held in memory as float samples, and the readers that fill it from raw, NRRD and
// NIfTI-1 files (DenseSource.h's sources read whole: a conversion reads them in slabs instead). Every
// reader converts its stored scalar type to float, so later stages handle one type.
// Every bad input is an fcc::InputError (sparse/Error.h) whose one-line message names the file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace fcc::io {

// Where a patient's superior (head) and anterior (face) sides point in a volume's world frame, as unit
// world directions: known for formats that tie the world to a patient (NIfTI: RAS; DICOM: LPS; NRRD with
// an anatomical "space"; MetaImage with an AnatomicalOrientation: LPS). `convert` records them (io/PatientMetadata.h) and the default camera shows
// such data upright, anterior towards the viewer.
struct PatientAxes {
  glm::dvec3 superior{0.0, 0.0, 1.0};
  glm::dvec3 anterior{0.0, 1.0, 0.0};
};

// The patient axes of a world frame whose vectors the linear map `patientFromWorld` takes to a patient
// frame in which superior and anterior are `superiorInPatient` and `anteriorInPatient` (RAS: +z and +y;
// LPS: +z and -y): the world vectors the map takes to them, normalised. Empty where the map is singular
// or not finite (no orientation to trust).
std::optional<PatientAxes> patientAxesFrom(const glm::dmat3& patientFromWorld, const glm::dvec3& superiorInPatient,
                                           const glm::dvec3& anteriorInPatient);
// Superior and anterior in the patient frames of the formats: RAS (NIfTI; NRRD's RAS and LAS) and LPS
// (DICOM; NRRD's LPS).
inline const glm::dvec3 kSuperiorInPatient{0.0, 0.0, 1.0};
inline const glm::dvec3 kAnteriorInRas{0.0, 1.0, 0.0};
inline const glm::dvec3 kAnteriorInLps{0.0, -1.0, 0.0};

struct DenseVolume {
  glm::ivec3 dims{0};       // voxels, x fastest, then y, then z
  glm::dvec3 spacing{1.0};  // world units per voxel along x, y, z
  glm::dvec3 origin{0.0};   // world position of voxel (0,0,0)
  // World directions of the index axes (columns, unit length): world = origin + direction * (spacing * ijk).
  // Identity unless the format records an orientation (DICOM, MetaImage).
  glm::dmat3 direction{1.0};
  // Where the patient's superior and anterior sides point in this world frame; empty for data that is
  // not a patient's (or whose file does not say).
  std::optional<PatientAxes> patient;
  std::vector<float> values;  // dims.x*dims.y*dims.z values

  // Position of voxel (i, j, k) in `values`, x fastest.
  size_t index(int i, int j, int k) const;
  // Value of voxel (i, j, k); the voxel must be inside (see contains).
  float at(int i, int j, int k) const;
  bool contains(int i, int j, int k) const;
};

// Scalar types a file can store; readers convert all of them to float.
enum class ScalarType { U8, I8, U16, I16, U32, I32, F32, F64 };

// "u8|i8|u16|i16|u32|i32|f32|f64" (the command line's spelling); ValueError listing the valid names otherwise.
ScalarType parseScalarType(const std::string& name);
// The command line's spelling of `type` ("u8", ...), for messages.
const char* scalarTypeName(ScalarType type);
// Bytes one stored sample of `type` takes.
size_t scalarTypeSize(ScalarType type);

// Largest volume a reader accepts: 2^34 voxels is 64 GiB of float values, beyond any machine this tool
// targets, and a header that claims more is far likelier corrupt than real.
inline constexpr uint64_t kMaxVoxelCount = uint64_t(1) << 34;

// dims.x*dims.y*dims.z, computed without overflow. InputError naming `path` if a dimension is below 1 or
// the product exceeds kMaxVoxelCount — readers call it before sizing anything from a header's dims.
uint64_t checkedVoxelCount(const glm::ivec3& dims, const std::string& path);

// How a headerless raw file is laid out; everything comes from the command line.
struct RawLayout {
  glm::ivec3 dims{0};
  ScalarType type = ScalarType::U8;
  bool bigEndian = false;
  glm::dvec3 spacing{1.0};
  uint64_t headerBytes = 0;  // bytes before the first voxel (e.g. 62 for a VolPack .den)
};

// Reads a raw volume. Gzip-compressed input (a .gz name, or the gzip magic) is inflated transparently.
// The (decompressed) file must hold exactly headerBytes + the voxels' bytes: any other size means the
// layout is wrong, and guessing would render garbage.
DenseVolume readRaw(const std::string& path, const RawLayout& layout);

// Reads a 3-D NRRD: .nrrd (data attached after the header) or .nhdr (detached, "data file:"); encodings
// raw and gzip; types: every NRRD spelling of the 8 ScalarTypes; spacing from "spacings" or axis-aligned
// "space directions" (the diagonal's magnitude); origin from "space origin"; `patient` from an anatomical
// "space" (RAS, LAS, LPS or their long names), with the directions' signs.
DenseVolume readNrrd(const std::string& path);

// Reads a single-file NIfTI-1 volume (.nii or .nii.gz, magic "n+1"), either byte order; scl_slope and
// scl_inter are applied when the slope is nonzero; spacing = |pixdim[1..3]|; origin from the sform's
// translation if sform_code > 0, else qoffset if qform_code > 0, else 0. The world axes stay the index
// axes (the rotation is not applied); the sform's (else the qform's) orientation gives `patient`: where
// RAS's superior and anterior lie in that world frame (none when both codes are 0).
DenseVolume readNifti(const std::string& path);

// Reads through ITK's ImageIO layer (io/ItkReader.cpp): a DICOM series (a folder of slices, or one
// slice: the series it belongs to in its folder; sorted by position, GDCM applying the rescale slope and
// intercept) or a MetaImage (.mha, or .mhd with its data file). Spacing, origin and direction from the
// headers; every sample as float. A DICOM series' world is the patient's LPS frame (`patient` says so);
// a MetaImage has no `patient`.
DenseVolume readDicom(const std::string& path);
DenseVolume readMetaImage(const std::string& path);

enum class Format { Vdb, Raw, Nrrd, Nifti, Dicom, MetaImage };

// By extension, case-insensitive: .vdb, .nrrd/.nhdr, .nii/.nii.gz, .mha/.mhd, .dcm/.ima; a folder or a
// file with DICOM's "DICM" marker is DICOM; anything else is Raw.
Format detectFormat(const std::string& path);

}  // namespace fcc::io
