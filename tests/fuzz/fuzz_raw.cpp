// libFuzzer target of the raw reader (io/RawReader.cpp). A raw file has no header: its layout comes from
// the command line. Here the first kLayoutBytes input bytes choose it (dims, type, byte order, header
// bytes, a .gz name, a bad spacing) and the rest is the file, so the fuzzer explores the reader's own
// decisions: the size checks, the gzip detection by magic or name, the header skip and the trailing bytes.
#include <cstdint>
#include <cstring>
#include <string>

#include "FuzzInputFile.h"
#include "io/DenseVolume.h"
#include "sparse/Error.h"

namespace {

constexpr size_t kLayoutBytes = 9;

uint16_t u16(const uint8_t* p) { return uint16_t(p[0] | (p[1] << 8)); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < kLayoutBytes) return 0;
  fcc::io::RawLayout layout;
  // Dims up to 65535 each: enough to ask for more than kMaxVoxelCount, and 0 is a bad dimension.
  layout.dims = glm::ivec3(u16(data), u16(data + 2), u16(data + 4));
  layout.type = fcc::io::ScalarType(data[6] % 8);
  const uint8_t flags = data[7];
  layout.bigEndian = flags & 1;
  const bool gzName = flags & 2;
  if (flags & 4) layout.spacing = glm::dvec3(1.0, (flags & 8) ? 0.0 : -2.5, 1.0);  // refused: ValueError
  layout.headerBytes = data[8] | ((flags & 0x10) ? uint64_t(1) << 40 : 0);      // a header beyond the file
  const std::string path =
      fcc::fuzz::inputFolder().write(gzName ? "volume.raw.gz" : "volume.raw", data + kLayoutBytes, size - kLayoutBytes);
  try {
    const fcc::io::DenseVolume volume = fcc::io::readRaw(path, layout);
    if (volume.values.size() != fcc::io::checkedVoxelCount(volume.dims, path)) __builtin_trap();
  } catch (const fcc::InputError&) {
  } catch (const fcc::ValueError&) {
  }
  return 0;
}
