#include "SourceFlags.h"

#include "Command.h"
#include "Triple.h"
#include "sparse/Error.h"

namespace fcc::cli {

void addRawFlags(CLI::App& app, SourceFlags& f) {
  f.dimsOption = app.add_option("--dims", f.dims, "Raw input: voxels per axis X,Y,Z (x fastest)")->check(tripleValidator("--dims"));
  f.typeOption = app.add_option("--type", f.type, "Raw input: voxel type")
                     ->check(CLI::IsMember({"u8", "i8", "u16", "i16", "u32", "i32", "f32", "f64"}))
                     ->capture_default_str();
  f.endianOption = app.add_option("--endian", f.endian, "Raw input: byte order")->check(CLI::IsMember({"little", "big"}))->capture_default_str();
  f.spacingOption = app.add_option("--spacing", f.spacing, "Raw input: voxel spacing SX,SY,SZ in world units")
                        ->check(tripleValidator("--spacing"))
                        ->capture_default_str();
  f.headerBytesOption = app.add_option("--header-bytes", f.headerBytes, "Raw input: bytes to skip before the voxels")->capture_default_str();
}

std::optional<io::RawLayout> rawLayoutFromFlags(const SourceFlags& f, const std::string& input) {
  if (io::detectFormat(input) != io::Format::Raw) {
    for (const CLI::Option* o : {f.dimsOption, f.typeOption, f.endianOption, f.spacingOption, f.headerBytesOption})
      if (o && o->count() > 0)
        throw ValueError(o->get_name() + " is for raw input only; " + input +
                         " is read by its own header (.vdb, .nrrd/.nhdr, .nii/.nii.gz, .mha/.mhd, DICOM): drop " +
                         o->get_name());
    return std::nullopt;
  }
  if (f.dims.empty()) return std::nullopt;
  io::RawLayout raw;
  glm::dvec3 dims, spacing;
  parseTriple(f.dims, dims);
  parseTriple(f.spacing, spacing);
  raw.dims = glm::ivec3(dims);
  raw.spacing = spacing;
  raw.type = io::parseScalarType(f.type);
  raw.bigEndian = f.endian == "big";
  raw.headerBytes = f.headerBytes;
  return raw;
}

}  // namespace fcc::cli
