// Stored samples to float: byte order and scalar type conversion, shared by every reader so there is one
// conversion loop, and header fields read in a file's byte order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "ByteSource.h"
#include "DenseVolume.h"

namespace fcc::io {

inline bool hostIsBigEndian() { return __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__; }

// The T stored at `bytes` in the given byte order (bytes need not be aligned).
template <class T>
T loadScalar(const uint8_t* bytes, bool bigEndian) {
  uint8_t ordered[sizeof(T)];
  if (bigEndian == hostIsBigEndian()) {
    std::memcpy(ordered, bytes, sizeof(T));
  } else {
    for (size_t b = 0; b < sizeof(T); ++b) ordered[b] = bytes[sizeof(T) - 1 - b];
  }
  T value;
  std::memcpy(&value, ordered, sizeof(T));
  return value;
}

// Converts `count` samples of `type` stored at `bytes` in the given byte order to float.
void decodeSamples(const uint8_t* bytes, size_t count, ScalarType type, bool bigEndian, float* out);

// Reads up to `count` samples from `source` and appends them, converted to float, to `values`. The vector
// grows only as data arrives (never beyond `count` new values), so a file that claims more voxels than it
// holds cannot cause a large allocation. Returns the number of whole samples read: fewer than `count`
// means the data ended early (the caller words the error, it knows what the layout was).
uint64_t readSamples(ByteSource& source, ScalarType type, bool bigEndian, uint64_t count, std::vector<float>& values);

}  // namespace fcc::io
