// libFuzzer target of the NRRD reader (io/NrrdReader.cpp): the input is a .nrrd file — its text header,
// then attached raw or gzip data; or a detached header, whose "data file:" may name the input itself
// (volume.nrrd, with "byte skip" or "line skip" to reach the data). InputError and ValueError are
// refusals; anything else (another exception, a crash, a sanitizer report, a hang, an allocation beyond
// -malloc_limit_mb) is a bug.
#include <cstdint>
#include <string>

#include "FuzzInputFile.h"
#include "io/DenseVolume.h"
#include "sparse/Error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = fcc::fuzz::inputFolder().write("volume.nrrd", data, size);
  try {
    const fcc::io::DenseVolume volume = fcc::io::readNrrd(path);
    // What a reader returns must hold together: one value per voxel.
    if (volume.values.size() != fcc::io::checkedVoxelCount(volume.dims, path)) __builtin_trap();
  } catch (const fcc::InputError&) {
  } catch (const fcc::ValueError&) {
  }
  return 0;
}
