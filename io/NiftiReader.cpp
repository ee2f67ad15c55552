// NIfTI-1 single-file volumes (.nii, .nii.gz): a 348-byte binary header, optional extensions, then the
// voxels from vox_offset on. The header's own byte order (told by sizeof_hdr reading 348 one way or the
// other) is the data's byte order too.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "ByteSource.h"
#include "DenseSource.h"
#include "MessageText.h"
#include "SampleDecoding.h"
#include "StoredVoxels.h"
#include "sparse/Error.h"

namespace fcc::io {
namespace {

constexpr size_t kHeaderBytes = 348;

// Byte offsets of the header fields this reader uses (NIfTI-1, nifti1.h).
namespace field {
constexpr size_t sizeofHdr = 0, dim = 40, datatype = 70, pixdim = 76, voxOffset = 108, sclSlope = 112,
                 sclInter = 116, qformCode = 252, sformCode = 254, quatern = 256, qoffset = 268, srowX = 280, srowY = 296,
                 srowZ = 312, magic = 344;
}  // namespace field

struct DatatypeCode {
  int16_t code;
  const char* name;
  bool supported;
  ScalarType type;
};

constexpr DatatypeCode kDatatypes[] = {
    {2, "uint8", true, ScalarType::U8},        {4, "int16", true, ScalarType::I16},
    {8, "int32", true, ScalarType::I32},       {16, "float32", true, ScalarType::F32},
    {64, "float64", true, ScalarType::F64},    {256, "int8", true, ScalarType::I8},
    {512, "uint16", true, ScalarType::U16},    {768, "uint32", true, ScalarType::U32},
    {1, "binary", false, ScalarType::U8},      {32, "complex64", false, ScalarType::U8},
    {128, "rgb24", false, ScalarType::U8},     {1024, "int64", false, ScalarType::U8},
    {1280, "uint64", false, ScalarType::U8},   {1536, "float128", false, ScalarType::U8},
    {1792, "complex128", false, ScalarType::U8}, {2048, "complex256", false, ScalarType::U8},
    {2304, "rgba32", false, ScalarType::U8},
};

ScalarType scalarTypeOf(int16_t code, const std::string& path) {
  std::string known = "unknown";
  for (const DatatypeCode& datatype : kDatatypes) {
    if (datatype.code != code) continue;
    if (datatype.supported) return datatype.type;
    known = datatype.name;
  }
  throw InputError(path + ": datatype " + std::to_string(code) + " (" + known +
                   ") is not supported; supported: 2 (uint8), 256 (int8), 512 (uint16), 4 (int16), "
                   "768 (uint32), 8 (int32), 16 (float32), 64 (float64)");
}

// The header as stored, read in its own byte order.
class Header {
 public:
  Header(const uint8_t* bytes, bool bigEndian) : bytes_(bytes), bigEndian_(bigEndian) {}
  int16_t i16(size_t offset) const { return loadScalar<int16_t>(bytes_ + offset, bigEndian_); }
  float f32(size_t offset) const { return loadScalar<float>(bytes_ + offset, bigEndian_); }

 private:
  const uint8_t* bytes_;
  bool bigEndian_;
};

// Zero or non-finite pixdims occur in files whose writer did not know the spacing; 1 is what every
// other reader then assumes too.
double spacingFrom(float pixdim) { return std::isfinite(pixdim) && pixdim != 0.0f ? std::abs(double(pixdim)) : 1.0; }

glm::dvec3 originFrom(const Header& header) {
  if (header.i16(field::sformCode) > 0)
    return {header.f32(field::srowX + 12), header.f32(field::srowY + 12), header.f32(field::srowZ + 12)};
  if (header.i16(field::qformCode) > 0)
    return {header.f32(field::qoffset), header.f32(field::qoffset + 4), header.f32(field::qoffset + 8)};
  return glm::dvec3(0.0);
}

// The patient's axes in this reader's world frame (world = origin + spacing * ijk: the index axes,
// scaled): the sform's (else the qform's) map from index to RAS, taken from that world frame.
std::optional<PatientAxes> patientFrom(const Header& header, const glm::dvec3& spacing) {
  glm::dmat3 rasFromIndex(1.0);  // glm: [column][row]
  if (header.i16(field::sformCode) > 0) {
    for (int row = 0; row < 3; ++row)
      for (int column = 0; column < 3; ++column)
        rasFromIndex[column][row] = header.f32(field::srowX + 16 * size_t(row) + 4 * size_t(column));
  } else if (header.i16(field::qformCode) > 0) {
    // nifti1.h: the rotation of the unit quaternion (a, b, c, d), a = sqrt(1 - b^2 - c^2 - d^2), times
    // the pixdims, the third one negated where qfac (pixdim[0]) is negative.
    const double b = header.f32(field::quatern), c = header.f32(field::quatern + 4), d = header.f32(field::quatern + 8);
    const double a = std::sqrt(std::max(0.0, 1.0 - (b * b + c * c + d * d)));
    const double rows[3][3] = {{a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)},
                               {2 * (b * c + a * d), a * a + c * c - b * b - d * d, 2 * (c * d - a * b)},
                               {2 * (b * d - a * c), 2 * (c * d + a * b), a * a + d * d - c * c - b * b}};
    const double qfac = header.f32(field::pixdim) < 0.0f ? -1.0 : 1.0;
    for (int column = 0; column < 3; ++column) {
      const float pixdim = header.f32(field::pixdim + 4 * size_t(column + 1));
      // As spacingFrom: an unknown pixdim is 1.
      const double scale = (std::isfinite(pixdim) && pixdim != 0.0f ? double(pixdim) : 1.0) * (column == 2 ? qfac : 1.0);
      for (int row = 0; row < 3; ++row) rasFromIndex[column][row] = rows[row][column] * scale;
    }
  } else {
    return std::nullopt;  // "method 1": no orientation
  }
  // index = (world - origin) / spacing
  const glm::dmat3 indexFromWorld(glm::dvec3(1.0 / spacing.x, 0, 0), glm::dvec3(0, 1.0 / spacing.y, 0),
                                  glm::dvec3(0, 0, 1.0 / spacing.z));
  return patientAxesFrom(rasFromIndex * indexFromWorld, kSuperiorInPatient, kAnteriorInRas);
}

}  // namespace

std::unique_ptr<DenseSource> openNifti(const std::string& path) {
  ByteSource source(path, 0, Compression::Detect);
  uint8_t bytes[kHeaderBytes] = {};
  const size_t got = source.read(bytes, kHeaderBytes);

  // sizeof_hdr is 348 in the writer's byte order; reading it both ways tells that order.
  const int32_t sizeLittle = loadScalar<int32_t>(bytes + field::sizeofHdr, false);
  const int32_t sizeBig = loadScalar<int32_t>(bytes + field::sizeofHdr, true);
  if (got < 4 || (sizeLittle != 348 && sizeBig != 348)) {
    if (got >= 4 && (sizeLittle == 540 || sizeBig == 540))
      throw InputError(path + ": NIfTI-2 is not supported; only NIfTI-1 (sizeof_hdr 348)");
    throw InputError(path + ": not a NIfTI-1 file: sizeof_hdr is " +
                     (got < 4 ? std::string("missing") : std::to_string(sizeLittle)) + ", must be 348");
  }
  if (got < kHeaderBytes)
    throw InputError(path + ": truncated NIfTI-1 header: file holds " + std::to_string(got) + " bytes" +
                     (source.gzip() ? " once decompressed" : "") + ", the header needs 348");
  const bool bigEndian = sizeLittle != 348;
  const Header header(bytes, bigEndian);

  const std::string_view magic(reinterpret_cast<const char*>(bytes + field::magic), 4);
  if (magic == std::string_view("ni1\0", 4))
    throw InputError(path + ": two-file NIfTI-1 (.hdr/.img, magic \"ni1\") is not supported; use a single-file .nii");
  if (magic != std::string_view("n+1\0", 4))
    throw InputError(path + ": bad NIfTI-1 magic " + quotedText(magic) + "; a single-file .nii has \"n+1\\0\"");

  // dim[0] axes; beyond the third they must be 1 (a 3-D volume stored as one time point, say).
  const int16_t rank = header.i16(field::dim);
  if (rank < 3 || rank > 7)
    throw InputError(path + ": dim[0] is " + std::to_string(rank) + "; only 3-D volumes are supported (dim[0] 3, or more with size 1)");
  for (int axis = 4; axis <= rank; ++axis)
    if (header.i16(field::dim + 2 * axis) != 1)
      throw InputError(path + ": dim[" + std::to_string(axis) + "] is " + std::to_string(header.i16(field::dim + 2 * axis)) +
                       "; only 3-D volumes are supported (every dimension past the third must be 1)");
  const glm::ivec3 dims(header.i16(field::dim + 2), header.i16(field::dim + 4), header.i16(field::dim + 6));
  const uint64_t voxels = checkedVoxelCount(dims, path);
  const ScalarType type = scalarTypeOf(header.i16(field::datatype), path);
  const uint64_t payload = voxels * scalarTypeSize(type);

  const float voxOffsetStored = header.f32(field::voxOffset);
  // Bounded so the cast is defined; a real offset is a few hundred bytes plus extensions.
  if (!(voxOffsetStored >= float(kHeaderBytes) && voxOffsetStored < 1e15f))
    throw InputError(path + ": vox_offset " + numberText(voxOffsetStored) + " is invalid; it must be at least 348");
  const uint64_t voxOffset = uint64_t(voxOffsetStored);

  const bool gzip = source.gzip();
  auto sizeError = [=](uint64_t holds) {
    return InputError(path + ": file holds " + std::to_string(holds) + " bytes" + (gzip ? " once decompressed" : "") +
                      " but dims " + commaList(dims) + " of datatype " + scalarTypeName(type) + " need " +
                      std::to_string(payload) + " from vox_offset " + std::to_string(voxOffset));
  };
  if (source.knownSize() && *source.knownSize() < voxOffset + payload) throw sizeError(*source.knownSize());

  DenseVolume volume;
  volume.dims = dims;
  volume.spacing = {spacingFrom(header.f32(field::pixdim + 4)), spacingFrom(header.f32(field::pixdim + 8)),
                    spacingFrom(header.f32(field::pixdim + 12))};
  volume.origin = originFrom(header);
  volume.patient = patientFrom(header, volume.spacing);

  StoredVoxels stored;
  stored.path = path;
  stored.gzip = gzip;
  stored.skipBytes = voxOffset;  // the header and its extensions
  stored.type = type;
  stored.bigEndian = bigEndian;
  // A slope of 0 (or NaN) means "unscaled" in NIfTI-1.
  const float slope = header.f32(field::sclSlope);
  if (std::isfinite(slope) && slope != 0.0f) {
    const float intercept = header.f32(field::sclInter);
    stored.scale = std::make_pair(slope, std::isfinite(intercept) ? intercept : 0.0f);
  }
  stored.sizeError = sizeError;
  return openStoredVoxels(volume, std::move(stored));
}

DenseVolume readNifti(const std::string& path) { return readAllVoxels(*openNifti(path)); }

}  // namespace fcc::io
