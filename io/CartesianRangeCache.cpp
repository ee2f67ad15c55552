#include "CartesianRangeCache.h"

#include <sys/stat.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <iterator>

#include "AtomicOutput.h"
#include "sparse/Error.h"

namespace fcc::io {
namespace {

// The range of no value: the empty range's start (+inf, -inf), left as it was by values that are all NaN.
bool isEmptyRange(float lo, float hi) {
  return lo == std::numeric_limits<float>::infinity() && hi == -std::numeric_limits<float>::infinity();
}

namespace fs = std::filesystem;

// Bumped when the layout changes or ranges taken the same way would differ.
constexpr char kMagic[8] = {'F', 'C', 'C', 'R', 'N', 'G', '1', '\n'};
constexpr uint32_t kByteOrderMark = 0x01020304u;  // written in this machine's order; another order reads as another file
constexpr std::size_t kRecordBytes = 3 * sizeof(int32_t) + 2 * sizeof(float);
// A key is a path and a few numbers; a longer one is garbage.
constexpr uint32_t kMaxKeyBytes = 1 << 16;

uint64_t fnv1a(const char* data, std::size_t size, uint64_t h = 1469598103934665603ull) {
  for (std::size_t i = 0; i < size; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 1099511628211ull;
  }
  return h;
}

template <class T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
T get(const std::string& in, std::size_t at) {
  T v;
  std::memcpy(&v, in.data() + at, sizeof v);
  return v;
}

// a * b and a + b, or the largest uint64 where they do not fit.
uint64_t saturatingMul(uint64_t a, uint64_t b) { return b != 0 && a > UINT64_MAX / b ? UINT64_MAX : a * b; }
uint64_t saturatingAdd(uint64_t a, uint64_t b) { return a > UINT64_MAX - b ? UINT64_MAX : a + b; }

bool before(const glm::ivec3& a, const glm::ivec3& b) {  // (z, y, x) order: computeBrickRanges's
  if (a.z != b.z) return a.z < b.z;
  if (a.y != b.y) return a.y < b.y;
  return a.x < b.x;
}

}  // namespace

std::string cartesianRangeCacheKey(const std::string& sourcePath, const std::string& gridName, const std::string& geometry) {
  struct stat st {};
  std::error_code ec;
  const fs::path canonical = fs::canonical(sourcePath, ec);
  if (ec || ::stat(canonical.c_str(), &st) != 0) return {};
  return std::string(kMagic, sizeof kMagic) + canonical.string() + '\n' + std::to_string(st.st_size) + ' ' +
         std::to_string(st.st_mtim.tv_sec) + '.' + std::to_string(st.st_mtim.tv_nsec) + '\n' + gridName + '\n' + geometry;
}

std::string cartesianRangeCachePath(const std::string& dir, const std::string& sourcePath, const std::string& key) {
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", (unsigned long long)fnv1a(key.data(), key.size()));
  return (fs::path(dir) / (fs::path(sourcePath).filename().string() + "-" + hash + ".ccranges")).string();
}

std::optional<std::vector<CartesianBrickRange>> readCartesianRangeCache(const std::string& file, const std::string& key,
                                                                       const glm::ivec3& boxLo, const glm::ivec3& boxHi) {
  std::error_code ec;
  const uintmax_t size = fs::file_size(file, ec);
  // The header, the key and the count, then the records and the checksum; at most one record a brick
  // of the box (whose volume bounds any honest file). A legitimate sparse grid's box can span 2^28
  // bricks an axis, whose volume overflows 64 bits: the products saturate.
  const std::size_t fixed = sizeof kMagic + 2 * sizeof(uint32_t) + sizeof(uint64_t) + sizeof(uint64_t);
  const glm::i64vec3 extent = glm::i64vec3(boxHi) - glm::i64vec3(boxLo) + int64_t(1);  // each at most 2^32
  const uint64_t maxBricks =
      glm::any(glm::lessThan(extent, glm::i64vec3(1)))
          ? 0
          : saturatingMul(saturatingMul(uint64_t(extent.x), uint64_t(extent.y)), uint64_t(extent.z));
  const uint64_t maxSize = saturatingAdd(fixed + kMaxKeyBytes, saturatingMul(maxBricks, kRecordBytes));
  if (ec || size < fixed || size > maxSize) return std::nullopt;
  std::string bytes;
  try {
    std::ifstream in(file, std::ios::binary);
    if (!in) return std::nullopt;
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } catch (const std::exception&) {  // a file too large for memory is no cache either (never a throw)
    return std::nullopt;
  }
  if (bytes.size() != size || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) return std::nullopt;
  std::size_t at = sizeof kMagic;
  if (get<uint32_t>(bytes, at) != kByteOrderMark) return std::nullopt;
  const uint32_t keyBytes = get<uint32_t>(bytes, at + 4);
  at += 8;
  if (keyBytes != key.size() || at + keyBytes + 2 * sizeof(uint64_t) > bytes.size() ||
      bytes.compare(at, keyBytes, key) != 0)
    return std::nullopt;
  at += keyBytes;
  const uint64_t count = get<uint64_t>(bytes, at);
  at += sizeof(uint64_t);
  // The records fit before the checksum (so count * kRecordBytes cannot wrap around to the file's size).
  const std::size_t recordBytes = bytes.size() - at - sizeof(uint64_t);
  if (count > maxBricks || count > recordBytes / kRecordBytes || count * kRecordBytes != recordBytes) return std::nullopt;
  const std::size_t end = bytes.size() - sizeof(uint64_t);
  if (get<uint64_t>(bytes, end) != fnv1a(bytes.data(), end)) return std::nullopt;
  std::vector<CartesianBrickRange> ranges(count);
  for (uint64_t i = 0; i < count; ++i, at += kRecordBytes) {
    CartesianBrickRange& r = ranges[i];
    r.brick = glm::ivec3(get<int32_t>(bytes, at), get<int32_t>(bytes, at + 4), get<int32_t>(bytes, at + 8));
    r.lo = get<float>(bytes, at + 12);
    r.hi = get<float>(bytes, at + 16);
    if (glm::any(glm::lessThan(r.brick, boxLo)) || glm::any(glm::greaterThan(r.brick, boxHi))) return std::nullopt;
    if (i > 0 && !before(ranges[i - 1].brick, r.brick)) return std::nullopt;
    // lo <= hi, neither NaN: the leaves' pass never writes a NaN (its min and max pass over them).
    // The one exception is what that pass gives a brick whose every value is NaN, lo = +inf and
    // hi = -inf (nothing was added to the empty range): read as written, so that such a grid's ranges
    // are cached like any other's instead of being computed and written again on every open.
    if (!(r.lo <= r.hi) && !isEmptyRange(r.lo, r.hi)) return std::nullopt;
  }
  return ranges;
}

void writeCartesianRangeCache(const std::string& file, const std::string& key, const std::vector<CartesianBrickRange>& ranges) {
  std::string bytes(kMagic, sizeof kMagic);
  put(bytes, kByteOrderMark);
  put(bytes, uint32_t(key.size()));
  bytes += key;
  put(bytes, uint64_t(ranges.size()));
  for (const CartesianBrickRange& r : ranges) {
    put(bytes, int32_t(r.brick.x));
    put(bytes, int32_t(r.brick.y));
    put(bytes, int32_t(r.brick.z));
    put(bytes, r.lo);
    put(bytes, r.hi);
  }
  put(bytes, fnv1a(bytes.data(), bytes.size()));
  AtomicOutput out(file, /*overwrite=*/true);
  {
    std::ofstream f(out.tempPath(), std::ios::binary | std::ios::trunc);
    f.write(bytes.data(), std::streamsize(bytes.size()));
    f.close();
    if (!f) throw OutputError("cannot write " + file);
  }
  out.commit();
}

}  // namespace fcc::io
