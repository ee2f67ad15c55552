#include "SampleDecoding.h"

#include <algorithm>

namespace fcc::io {
namespace {

template <class T>
void decodeAs(const uint8_t* bytes, size_t count, bool bigEndian, float* out) {
  for (size_t i = 0; i < count; ++i) out[i] = static_cast<float>(loadScalar<T>(bytes + i * sizeof(T), bigEndian));
}

// Bytes read per step: large enough that the per-call cost vanishes, small enough to stay in cache.
constexpr size_t kChunkBytes = size_t(1) << 20;

}  // namespace

void decodeSamples(const uint8_t* bytes, size_t count, ScalarType type, bool bigEndian, float* out) {
  switch (type) {
    case ScalarType::U8: return decodeAs<uint8_t>(bytes, count, bigEndian, out);
    case ScalarType::I8: return decodeAs<int8_t>(bytes, count, bigEndian, out);
    case ScalarType::U16: return decodeAs<uint16_t>(bytes, count, bigEndian, out);
    case ScalarType::I16: return decodeAs<int16_t>(bytes, count, bigEndian, out);
    case ScalarType::U32: return decodeAs<uint32_t>(bytes, count, bigEndian, out);
    case ScalarType::I32: return decodeAs<int32_t>(bytes, count, bigEndian, out);
    case ScalarType::F32: return decodeAs<float>(bytes, count, bigEndian, out);
    case ScalarType::F64: return decodeAs<double>(bytes, count, bigEndian, out);
  }
}

uint64_t readSamples(ByteSource& source, ScalarType type, bool bigEndian, uint64_t count, std::vector<float>& values) {
  const size_t sampleBytes = scalarTypeSize(type);
  const uint64_t limit = values.size() + count;
  std::vector<uint8_t> chunk(kChunkBytes);
  uint64_t done = 0;
  while (done < count) {
    const size_t wanted = size_t(std::min<uint64_t>(count - done, kChunkBytes / sampleBytes));
    const size_t gotBytes = source.read(chunk.data(), wanted * sampleBytes);
    const size_t got = gotBytes / sampleBytes;
    if (values.capacity() < values.size() + got)  // double, but never past what `count` asks for
      values.reserve(size_t(std::min<uint64_t>(limit, std::max<uint64_t>(values.size() + got, 2 * values.capacity()))));
    const size_t at = values.size();
    values.resize(at + got);
    decodeSamples(chunk.data(), got, type, bigEndian, values.data() + at);
    done += got;
    if (got < wanted) break;
  }
  return done;
}

}  // namespace fcc::io
