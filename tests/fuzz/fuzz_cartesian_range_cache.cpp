// libFuzzer target of the Cartesian bricks' range cache reader (io/CartesianRangeCache.cpp): a file of the
// user's cache folder, which a crash, a full disk or another program may have damaged. The first
// kLayoutBytes input bytes are what the caller passes besides the file — the box the bricks must lie in
// (CartesianBrickStore's active brick box: lo > hi when empty, up to 2^28 bricks an axis from a legitimate
// sparse grid) — and a flag that rewrites the file's trailing FNV-1a checksum over the rest, so that
// mutations reach the count and the records instead of all dying at the checksum. The rest is the file.
//
// A damaged file must read as no cache (nullopt), never a throw, crash or sanitizer report; what is
// accepted must hold the contract (every brick in the box, strictly increasing (z, y, x) order, lo <= hi)
// and be exactly what the writer writes for those ranges (written back, the same bytes).
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "FuzzInputFile.h"
#include "io/CartesianRangeCache.h"

namespace {

constexpr size_t kLayoutBytes = 25;  // box lo (3 x int32), box hi (3 x int32), flags

// The key the seeds (make_seeds.py, cartesian_range_cache_seeds) are written under: CartesianBrickStore's
// shape (magic, canonical path, size and mtime, grid name, geometry).
const std::string kKey =
    std::string("FCCRNG1\n") + "/data/volume.vdb\n123456 1700000000.123456789\ndensity\n" +
    "bricks 16, blocks from -2 of 20 points, leaf slabs 2";

int32_t i32(const uint8_t* p) { return int32_t(uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24); }

uint64_t fnv1a(const uint8_t* data, size_t size) {
  uint64_t h = 1469598103934665603ull;
  for (size_t i = 0; i < size; ++i) {
    h ^= data[i];
    h *= 1099511628211ull;
  }
  return h;
}

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

bool before(const glm::ivec3& a, const glm::ivec3& b) {
  if (a.z != b.z) return a.z < b.z;
  if (a.y != b.y) return a.y < b.y;
  return a.x < b.x;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < kLayoutBytes) return 0;
  const glm::ivec3 boxLo(i32(data), i32(data + 4), i32(data + 8));
  const glm::ivec3 boxHi(i32(data + 12), i32(data + 16), i32(data + 20));
  const bool reseal = data[24] & 1;
  std::string file(reinterpret_cast<const char*>(data + kLayoutBytes), size - kLayoutBytes);
  if (reseal && file.size() >= sizeof(uint64_t)) {
    const size_t end = file.size() - sizeof(uint64_t);
    const uint64_t sum = fnv1a(reinterpret_cast<const uint8_t*>(file.data()), end);
    std::memcpy(file.data() + end, &sum, sizeof sum);
  }
  const fcc::fuzz::InputFolder& folder = fcc::fuzz::inputFolder();
  const std::string path =
      folder.write("volume.vdb-0123456789abcdef.ccranges", reinterpret_cast<const uint8_t*>(file.data()), file.size());

  // Any exception escapes and aborts: the reader promises never to throw.
  const auto ranges = fcc::io::readCartesianRangeCache(path, kKey, boxLo, boxHi);
  if (!ranges) return 0;
  for (size_t i = 0; i < ranges->size(); ++i) {
    const fcc::io::CartesianBrickRange& r = (*ranges)[i];
    if (glm::any(glm::lessThan(r.brick, boxLo)) || glm::any(glm::greaterThan(r.brick, boxHi))) __builtin_trap();
    if (i > 0 && !before((*ranges)[i - 1].brick, r.brick)) __builtin_trap();
    // A range or the empty one (+inf, -inf) of a brick whose values are all NaN (io/CartesianRangeCache.h).
    const bool empty = r.lo == std::numeric_limits<float>::infinity() && r.hi == -std::numeric_limits<float>::infinity();
    if (!(r.lo <= r.hi) && !empty) __builtin_trap();
  }
  // What was accepted is a file the writer writes: the same bytes back.
  const std::string again = path + ".again";
  fcc::io::writeCartesianRangeCache(again, kKey, *ranges);
  if (readAll(again) != file) __builtin_trap();
  return 0;
}
