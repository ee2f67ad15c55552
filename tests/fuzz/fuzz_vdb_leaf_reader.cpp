// libFuzzer target of the brick reader (io/VdbLeafReader): the input is a .vdb file. It lists the grids
// from the descriptors, opens each grid by name (our parse of header, metadata structure, topology and
// buffer section; OpenVDB's of the metadata values, transform and topology) and reads every leaf.
// InputError and ValueError are the reader refusing damage, as it should; anything else — another
// exception, a crash, a sanitizer report, a hang, an allocation beyond -malloc_limit_mb — is a bug.
#include <cstdint>
#include <string>
#include <vector>

#include "FuzzInputFile.h"
#include "io/VdbLeafReader.h"
#include "sparse/Error.h"
#include "sparse/FccGrid.h"

namespace {

// Every leaf of one grid; the index must also find each leaf by its origin.
void readEveryLeaf(const fcc::io::VdbLeafReader& reader) {
  std::vector<float> values(512 * size_t(reader.components()));
  for (size_t i = 0; i < reader.leafCount(); ++i) {
    if (reader.leafIndexAt(reader.leafOrigin(i)) != i) __builtin_trap();  // an index that contradicts itself
    try {
      reader.readLeaf(i, values.data());
    } catch (const fcc::InputError&) {
      // a damaged leaf: refused, the next one may still read
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  fcc::initializeVdb();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = fcc::fuzz::inputFolder().write("input.vdb", data, size);
  std::vector<fcc::io::VdbGridEntry> grids;
  try {
    grids = fcc::io::VdbLeafReader::listGrids(path);
  } catch (const fcc::InputError&) {
    return 0;
  }
  for (const auto& grid : grids) {
    try {
      const fcc::io::VdbLeafReader reader(path, grid.name, {});
      readEveryLeaf(reader);
    } catch (const fcc::InputError&) {
    } catch (const fcc::ValueError&) {
    }
  }
  return 0;
}
