// Damaging one leaf of a .vdb in place, for the tests of damaged files: the damage lies inside the leaf's
// compressed values, which opening the file does not read, so the file opens and that leaf alone fails
// to read (VdbLeafReader::readLeaf throws "leaf at (x, y, z) is damaged").
#pragma once

#include <openvdb/openvdb.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/VdbFile.h"
#include "io/VdbLeafReader.h"

namespace fcc::test {

// Damages the leaf at `origin` (a multiple of 8) of the first grid of `types` in `path`: in the payload of
// its compressed values (blosc or zip; the payload ends the record and its Int64 size prefix says so), the
// second byte of blosc's uncompressed size — or of the zlib stream. Throws std::runtime_error when the
// file has no such leaf or no compressed payload.
inline void damageLeafValues(const std::string& path, const std::vector<std::string>& types, const openvdb::Coord& origin) {
  const std::string where = "(" + std::to_string(origin.x()) + ", " + std::to_string(origin.y()) + ", " + std::to_string(origin.z()) + ")";
  uint64_t recordBegin = 0, recordEnd = 0;
  {
    initializeVdb();
    const io::VdbLeafReader reader(path, "", types);
    const std::optional<size_t> leaf = reader.leafIndexAt(origin);
    if (!leaf) throw std::runtime_error(path + ": no leaf at " + where);
    recordBegin = reader.leafOffset(*leaf);
    recordEnd = recordBegin + reader.leafBytes(*leaf);
  }
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  size_t payload = 0;
  for (uint64_t p = recordBegin + 65; p + 8 <= recordEnd && !payload; ++p) {
    int64_t size = 0;
    std::memcpy(&size, bytes.data() + p, 8);
    if (size > 16 && uint64_t(size) == recordEnd - (p + 8)) payload = size_t(p + 8);
  }
  if (!payload) throw std::runtime_error(path + ": the leaf at " + where + " has no compressed payload");
  bytes[payload + 5] = char(bytes[payload + 5] ^ 0x40);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

}  // namespace fcc::test
