// libFuzzer target of the NIfTI-1 reader (io/NiftiReader.cpp): the input is a .nii file, plain or gzip
// (the reader tells them by the gzip magic, as for a .nii.gz), either byte order: its 348-byte header,
// extensions, the voxels from vox_offset. InputError and ValueError are refusals; anything else (another
// exception, a crash, a sanitizer report, a hang, an allocation beyond -malloc_limit_mb) is a bug.
#include <cstdint>
#include <string>

#include "FuzzInputFile.h"
#include "io/DenseVolume.h"
#include "sparse/Error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = fcc::fuzz::inputFolder().write("volume.nii", data, size);
  try {
    const fcc::io::DenseVolume volume = fcc::io::readNifti(path);
    if (volume.values.size() != fcc::io::checkedVoxelCount(volume.dims, path)) __builtin_trap();
  } catch (const fcc::InputError&) {
  } catch (const fcc::ValueError&) {
  }
  return 0;
}
