// Headerless raw volumes: the layout comes from the command line, so the file's size is the only check
// there is — it must match exactly, or the dims, type or header size are wrong.
#include <cmath>
#include <limits>

#include "ByteSource.h"
#include "DenseSource.h"
#include "MessageText.h"
#include "StoredVoxels.h"
#include "sparse/Error.h"

namespace fcc::io {
namespace {

bool hasGzipSuffix(const std::string& path) {
  return path.size() >= 3 && (path.compare(path.size() - 3, 3, ".gz") == 0 || path.compare(path.size() - 3, 3, ".GZ") == 0);
}

}  // namespace

std::unique_ptr<DenseSource> openRaw(const std::string& path, const RawLayout& layout) {
  const uint64_t voxels = checkedVoxelCount(layout.dims, path);
  for (int axis = 0; axis < 3; ++axis)
    if (!(std::isfinite(layout.spacing[axis]) && layout.spacing[axis] > 0.0))
      throw ValueError(path + ": spacing " + numberText(layout.spacing[axis]) + " along axis " +
                       std::to_string(axis) + " is invalid: it must be positive and finite");
  const uint64_t payload = voxels * scalarTypeSize(layout.type);  // at most 2^37: no overflow
  if (layout.headerBytes > std::numeric_limits<uint64_t>::max() - payload)
    throw InputError(path + ": header size " + std::to_string(layout.headerBytes) + " bytes is beyond any file");
  const uint64_t needed = layout.headerBytes + payload;

  // Says what to try: bytes beyond the voxels are most often a header (brainsmall.den: 62 bytes).
  auto sizeError = [=](uint64_t holds, bool decompressed) {
    std::string hint;
    if (holds > needed)
      hint = ": " + std::to_string(holds - needed) + " extra bytes; if they are a header, try --header-bytes " +
             std::to_string(holds - payload) + ", else check --dims and --type";
    else
      hint = ": " + std::to_string(needed - holds) + " bytes short; check --dims, --type and --header-bytes";
    return InputError(path + ": file holds " + std::to_string(holds) + " bytes" + (decompressed ? " once decompressed" : "") +
                      " but --dims " + commaList(layout.dims) + " --type " + scalarTypeName(layout.type) + " needs " +
                      std::to_string(payload) + " (+" + std::to_string(layout.headerBytes) + " header bytes)" + hint);
  };

  // A .gz name is always gzip. Otherwise the gzip magic decides, except that a plain file of exactly the
  // right size is raw even if it starts with 1f 8b 08 (a 16-bit sample can).
  Compression compression = Compression::Gzip;
  if (!hasGzipSuffix(path)) {
    const ByteSource probe(path, 0, Compression::Plain);
    compression = probe.knownSize() == needed ? Compression::Plain : Compression::Detect;
  }
  const ByteSource source(path, 0, compression);  // checks the gzip magic of a .gz name
  if (source.knownSize() && *source.knownSize() != needed) throw sizeError(*source.knownSize(), false);

  DenseVolume geometry;
  geometry.dims = layout.dims;
  geometry.spacing = layout.spacing;
  StoredVoxels stored;
  stored.path = path;
  stored.gzip = source.gzip();
  stored.skipBytes = layout.headerBytes;
  stored.type = layout.type;
  stored.bigEndian = layout.bigEndian;
  stored.exactEnd = true;
  stored.sizeError = [sizeError, gzip = source.gzip()](uint64_t holds) { return sizeError(holds, gzip); };
  return openStoredVoxels(geometry, std::move(stored));
}

DenseVolume readRaw(const std::string& path, const RawLayout& layout) { return readAllVoxels(*openRaw(path, layout)); }

}  // namespace fcc::io
