#include "VdbLeafReader.h"

#include <blosc.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include <openvdb/io/DelayedLoadMetadata.h>
#include <openvdb/io/GridDescriptor.h>
#include <openvdb/math/Half.h>

#include "MessageText.h"
#include "sparse/Error.h"
#include "sparse/FccGrid.h"  // FccTree, and RealToHalf<Vec4s>: Vec4f tiles stored as half

namespace fcc::io {
namespace {

using openvdb::Coord;
using Mask3 = openvdb::util::NodeMask<3>;

constexpr int64_t kVdbMagic = 0x56444220;  // OPENVDB_MAGIC: " BDV" and four zero bytes
constexpr uint32_t kMinFileVersion = 222;  // OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION: today's leaf layout
constexpr uint32_t kMaxFileVersion = 224;  // OPENVDB_FILE_VERSION of OpenVDB 10
constexpr size_t kMaxNameBytes = 1 << 16;  // grid names, type names, metadata names: sanity, not format
constexpr uint32_t kKnownCompression =
    openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK | openvdb::io::COMPRESS_BLOSC;
constexpr size_t kMaskBytes = 64;  // a leaf's 512-bit mask
constexpr uint32_t kLeafVoxels = 512;
constexpr size_t kBloscHeader = BLOSC_MIN_HEADER_LENGTH;  // 16
// A record's bytes before its values: mask, metadata byte, two inactive Vec4f, selection mask, Int64 prefix,
// plus blosc's header so that it can be checked while indexing.
constexpr size_t kMaxRecordHead = kMaskBytes + 1 + 2 * 16 + kMaskBytes + 8 + kBloscHeader;
constexpr size_t kIndexChunk = 4 << 20;  // the buffer-section walk reads 4 MiB at a time

const std::string kFloatTreeType = openvdb::FloatTree::treeType();  // "Tree_float_5_4_3"

// Non-printable bytes as \xNN, cut to `maxChars`: names from a damaged file go into one-line messages.
std::string escaped(std::string_view text, size_t maxChars = 64) {
  const std::string q = quotedText(text, maxChars);
  return q.substr(1, q.size() - 2);
}

std::string coordText(const Coord& c) {
  return "(" + std::to_string(c.x()) + ", " + std::to_string(c.y()) + ", " + std::to_string(c.z()) + ")";
}

// Reads exactly n bytes at `offset`; false if the file ends first. InputError for a failing read.
bool preadExact(int fd, const std::string& path, uint64_t offset, void* dst, size_t n) {
  auto* out = static_cast<char*>(dst);
  while (n > 0) {
    const ssize_t r = ::pread(fd, out, n, off_t(offset));
    if (r < 0) {
      if (errno == EINTR) continue;
      throw InputError(path + ": read failed at byte " + std::to_string(offset) + ": " + std::strerror(errno));
    }
    if (r == 0) return false;
    out += r;
    offset += uint64_t(r);
    n -= size_t(r);
  }
  return true;
}

// Sequential reading of [pos, end) of a file through a buffer, by pread.
class Cursor {
 public:
  Cursor(int fd, const std::string& path, uint64_t pos, uint64_t end, size_t capacity)
      : fd_(fd), path_(path), pos_(pos), end_(end), capacity_(capacity) {}
  uint64_t pos() const { return pos_; }
  uint64_t left() const { return end_ > pos_ ? end_ - pos_ : 0; }
  // n bytes at pos() (n <= capacity), or nullptr if fewer than n remain before the end.
  const uint8_t* peek(size_t n) {
    if (n > left()) return nullptr;
    if (pos_ < bufPos_ || pos_ + n > bufPos_ + buf_.size()) {
      const size_t want = size_t(std::min<uint64_t>(std::max(n, capacity_), end_ - pos_));
      buf_.resize(want);
      if (!preadExact(fd_, path_, pos_, buf_.data(), want))
        throw InputError(path_ + ": the file is shorter than its own offsets say (it was truncated while open?)");
      bufPos_ = pos_;
    }
    return buf_.data() + (pos_ - bufPos_);
  }
  void skip(uint64_t n) { pos_ += n; }  // n <= left(): callers check
  void seek(uint64_t pos) { pos_ = pos; }

 private:
  int fd_;
  const std::string& path_;
  uint64_t pos_, end_;
  size_t capacity_;
  std::vector<uint8_t> buf_;
  uint64_t bufPos_ = 0;
};

// Fields of a byte range, each checked against the range's end; failures go to `fail`.
class FieldReader {
 public:
  FieldReader(Cursor& cursor, std::string context) : c_(cursor), context_(std::move(context)) {}
  [[noreturn]] void fail(const std::string& what) const { throw InputError(context_ + what); }

  template <class T>
  T get(const char* what) {
    const uint8_t* p = c_.peek(sizeof(T));
    if (!p) fail(std::string(what) + " runs past " + endName());
    T v;
    std::memcpy(&v, p, sizeof(T));
    c_.skip(sizeof(T));
    return v;
  }
  // A uint32 length and that many bytes.
  std::string string(const char* what) {
    const uint32_t n = get<uint32_t>(what);
    if (n > kMaxNameBytes) fail(std::string(what) + " claims " + std::to_string(n) + " bytes (valid: up to " +
                                std::to_string(kMaxNameBytes) + ")");
    if (n > c_.left()) fail(std::string(what) + " (" + std::to_string(n) + " bytes) runs past " + endName());
    std::string s(n, '\0');
    if (n > 0) std::memcpy(s.data(), c_.peek(n), n);
    c_.skip(n);
    return s;
  }
  void skip(uint64_t n, const std::string& what) {
    if (n > c_.left()) fail(what + " (" + std::to_string(n) + " bytes) runs past " + endName());
    c_.skip(n);
  }
  void setEndName(std::string name) { endName_ = std::move(name); }
  const std::string& endName() const { return endName_; }
  Cursor& cursor() { return c_; }

 private:
  Cursor& c_;
  std::string context_;
  std::string endName_ = "the end of the file";
};

// One entry of a MetaMap as stored: name, type name, and where its value bytes (after the Int32 size) are.
struct MetaEntry {
  std::string name, type;
  uint64_t valuePos = 0;
  uint32_t valueBytes = 0;
};

// MetaMap::writeMeta's layout: Int32 count, then per entry name, type name, Int32 size, value bytes.
std::vector<MetaEntry> parseMetaMap(FieldReader& r, const char* what) {
  const uint32_t count = r.get<uint32_t>(what);
  if (uint64_t(count) * 12 > r.cursor().left())  // each entry has at least three Int32 sizes
    r.fail(std::string(what) + " claims " + std::to_string(count) + " entries, more than fit before " + r.endName());
  std::vector<MetaEntry> entries;
  for (uint32_t i = 0; i < count; ++i) {
    MetaEntry e;
    e.name = r.string("a metadata name");
    e.type = r.string("a metadata type name");
    e.valueBytes = r.get<uint32_t>("a metadata size");
    e.valuePos = r.cursor().pos();
    r.skip(e.valueBytes, "metadata \"" + escaped(e.name) + "\"");
    entries.push_back(std::move(e));
  }
  return entries;
}

struct Descriptor {
  std::string uniqueName, type, instanceParent;
  bool half = false;
  int64_t gridPos = 0, blockPos = 0, endPos = 0;
  std::string displayName() const { return openvdb::io::GridDescriptor::nameAsString(uniqueName); }
};

struct FileHeader {
  uint32_t fileVersion = 0;
  uint32_t libraryMajor = 0, libraryMinor = 0;
  std::vector<Descriptor> grids;
};

constexpr char kHalfSuffix[] = "_HalfFloat";

// Archive::readHeader, the file metadata (skipped) and File::readGridDescriptors, with every field checked.
FileHeader readFileHeader(int fd, const std::string& path, uint64_t fileSize) {
  Cursor c(fd, path, 0, fileSize, 1 << 16);
  {
    const uint8_t* p = c.peek(8);
    int64_t magic = 0;
    if (p) std::memcpy(&magic, p, 8);
    if (magic != kVdbMagic)
      throw InputError(path + ": not an OpenVDB file (no VDB magic number); valid inputs are .vdb files written by OpenVDB");
    c.skip(8);
  }
  FieldReader r(c, path + ": damaged header: ");
  FileHeader h;
  h.fileVersion = r.get<uint32_t>("the file format version");
  if (h.fileVersion < kMinFileVersion || h.fileVersion > kMaxFileVersion)
    throw InputError(path + ": OpenVDB file format version " + std::to_string(h.fileVersion) +
                     " is not supported (valid: " + std::to_string(kMinFileVersion) + " to " +
                     std::to_string(kMaxFileVersion) + ", as written by OpenVDB 3 to 11); re-save it with OpenVDB 10");
  h.libraryMajor = r.get<uint32_t>("the library version");
  h.libraryMinor = r.get<uint32_t>("the library version");
  const char hasGridOffsets = r.get<char>("the grid offsets flag");
  if (hasGridOffsets != 1)
    throw InputError(path + ": written as a stream without grid offsets (flag " + std::to_string(int(hasGridOffsets)) +
                     "); only files written by openvdb::io::File can be read leaf by leaf");
  {
    // Boost's textual UUID: 36 characters, hex digits with dashes after the 4th, 6th, 8th and 10th byte.
    const uint8_t* p = c.peek(36);
    if (!p) r.fail("the UUID runs past the end of the file");
    for (int i = 0; i < 36; ++i) {
      const bool dash = i == 8 || i == 13 || i == 18 || i == 23;
      if (dash ? p[i] != '-' : !std::isxdigit(p[i]))
        r.fail("the UUID " + quotedText(std::string_view(reinterpret_cast<const char*>(p), 36)) +
               " is not in the form xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx");
    }
    c.skip(36);
  }
  (void)parseMetaMap(r, "the file metadata");
  const int32_t gridCount = r.get<int32_t>("the grid count");
  if (gridCount < 0 || uint64_t(gridCount) * 36 > c.left())  // a descriptor: three strings, three Int64
    r.fail("the grid count " + std::to_string(gridCount) + " is not possible in a file of " +
           std::to_string(fileSize) + " bytes");
  for (int32_t i = 0; i < gridCount; ++i) {
    Descriptor d;
    const uint64_t at = c.pos();
    d.uniqueName = r.string("a grid name");
    d.type = r.string("a grid type name");
    const size_t suffix = std::strlen(kHalfSuffix);
    if (d.type.size() > suffix && d.type.compare(d.type.size() - suffix, suffix, kHalfSuffix) == 0) {
      d.half = true;
      d.type.resize(d.type.size() - suffix);
    }
    d.instanceParent = r.string("an instance parent name");
    d.gridPos = r.get<int64_t>("a grid position");
    d.blockPos = r.get<int64_t>("a buffer position");
    d.endPos = r.get<int64_t>("a grid end position");
    // Archive writes the grid right after its descriptor, its buffers after its topology, and the next
    // descriptor at its end. An instance (metadata and transform only) has no buffers: position 0.
    const uint64_t gridPos = c.pos();
    const bool noBuffers = !d.instanceParent.empty() && d.blockPos == 0;
    // Positions in order but past the end: the file was cut short (a copy or download that stopped).
    if (d.gridPos == int64_t(gridPos) && (noBuffers || (d.blockPos >= d.gridPos && d.endPos >= d.blockPos)) &&
        uint64_t(d.endPos) > fileSize)
      throw InputError(path + ": truncated: grid \"" + escaped(d.displayName()) + "\" ends at byte " +
                       std::to_string(d.endPos) + ", but the file has " + std::to_string(fileSize) +
                       " bytes (an incomplete copy or download?)");
    if (d.gridPos != int64_t(gridPos) || (!noBuffers && (d.blockPos < d.gridPos || d.endPos < d.blockPos)) ||
        d.endPos < d.gridPos || uint64_t(d.endPos) > fileSize)
      r.fail("grid \"" + escaped(d.displayName()) + "\" (descriptor at byte " + std::to_string(at) +
             ") has positions grid " + std::to_string(d.gridPos) + ", buffers " + std::to_string(d.blockPos) +
             ", end " + std::to_string(d.endPos) + "; valid: grid = " + std::to_string(gridPos) +
             " <= buffers <= end <= " + std::to_string(fileSize) + " (the file size)");
    c.seek(uint64_t(d.endPos));
    h.grids.push_back(std::move(d));
  }
  return h;
}

std::string gridList(const std::vector<Descriptor>& grids) {
  std::string out;
  for (const auto& g : grids)
    out += (out.empty() ? "" : ", ") + quotedText(g.displayName()) + " (" + escaped(g.type) + (g.half ? ", half" : "") + ")";
  return out.empty() ? "none" : out;
}

std::string typeList(const std::vector<std::string>& types) {
  std::string out;
  for (const auto& t : types) out += (out.empty() ? "" : ", ") + t;
  return out;
}

int componentsOf(const std::string& type) { return type == kFloatTreeType ? 1 : 4; }

// Tree order, as RootNode (std::map by origin) and InternalNode (by child index) iterate: root child key,
// then the 32^3 node's child index, then the 16^3 node's child index.
bool treeOrderLess(const Coord& a, const Coord& b) {
  for (const int shift : {12, 7, 3})
    for (int axis = 0; axis < 3; ++axis) {
      const int32_t ka = a[axis] >> shift, kb = b[axis] >> shift;
      if (ka != kb) return ka < kb;
    }
  return false;
}

// How one leaf's record in the buffer section is laid out (LeafNode::writeBuffers: the value mask, then
// io::writeCompressedValues: metadata byte, inactive values, selection mask, values).
struct Record {
  int8_t metadata = 0;
  uint32_t valueCount = 0;    // values stored: the active count (mask-compressed) or 512
  size_t inactiveAt = 0;      // offset of the stored inactive values (metadata 2, 4, 5)
  size_t selectionAt = 0;     // offset of the selection mask (metadata 3, 4, 5), else 0
  enum class Encoding { Raw, Blosc, Zip } encoding = Encoding::Raw;
  uint64_t payloadAt = 0;     // offset of the value bytes
  uint64_t payloadBytes = 0;  // as stored
  uint64_t decodedBytes = 0;  // valueCount * element size
  uint64_t size() const { return payloadAt + payloadBytes; }
  // Damage that leaves the record's size known (its mask, its blosc header): the leaf is never
  // trusted, but the leaves after it can still be found.
  std::string damage;
};

struct Damaged {
  std::string what;
};

struct Format {
  int components = 1;
  bool half = false;
  uint32_t compression = 0;
};

// Parses io::writeCompressedValues' layout at p + at (`avail` bytes from p are present; fewer than the
// whole record while indexing) for a node of `total` values, `active` of them on, whose selection mask
// takes `maskBytes`: a leaf's buffer after its value mask, and an internal node's tile values in the
// topology. Fills r's layout fields; throws Damaged for anything the format does not allow.
void parseValues(const uint8_t* p, uint64_t avail, uint64_t at, uint32_t total, uint32_t active, size_t maskBytes,
                 const Format& f, Record& r) {
  auto need = [&](uint64_t n, const char* what) {
    if (n > avail) throw Damaged{std::string(what) + " runs past the end of the grid's buffer section"};
  };
  need(at + 1, "the compression metadata");
  r.metadata = int8_t(p[at]);
  if (r.metadata < openvdb::io::NO_MASK_OR_INACTIVE_VALS || r.metadata > openvdb::io::NO_MASK_AND_ALL_VALS)
    throw Damaged{"compression metadata " + std::to_string(int(r.metadata)) + " (valid: 0 to 6)"};
  const size_t valueSize = 4 * size_t(f.components);  // sizeof(ValueType): inactive values are never half
  at += 1;
  using namespace openvdb::io;
  if (r.metadata == NO_MASK_AND_ONE_INACTIVE_VAL || r.metadata == MASK_AND_ONE_INACTIVE_VAL ||
      r.metadata == MASK_AND_TWO_INACTIVE_VALS) {
    r.inactiveAt = at;
    at += valueSize * (r.metadata == MASK_AND_TWO_INACTIVE_VALS ? 2 : 1);
  }
  if (r.metadata == MASK_AND_NO_INACTIVE_VALS || r.metadata == MASK_AND_ONE_INACTIVE_VAL ||
      r.metadata == MASK_AND_TWO_INACTIVE_VALS) {
    r.selectionAt = at;
    at += maskBytes;
  }
  need(at, "the inactive values");
  const bool maskCompressed = f.compression & COMPRESS_ACTIVE_MASK;
  r.valueCount = (maskCompressed && r.metadata != NO_MASK_AND_ALL_VALS) ? active : total;
  r.decodedBytes = uint64_t(r.valueCount) * (f.half ? 2 : 4) * uint64_t(f.components);
  r.payloadAt = at;
  if (f.half && r.valueCount == 0) return;  // HalfReader reads nothing at all, not even a size
  const bool blosc = f.compression & COMPRESS_BLOSC, zip = !blosc && (f.compression & COMPRESS_ZIP);
  if (!blosc && !zip) {
    r.payloadBytes = r.decodedBytes;
    return;
  }
  need(at + 8, "the size of the values");
  int64_t stored;
  std::memcpy(&stored, p + at, 8);
  r.payloadAt = at + 8;
  if (stored <= 0) {  // stored raw: -stored bytes follow
    if (stored != -int64_t(r.decodedBytes))
      // The magnitude in unsigned arithmetic: -stored overflows for the most negative size (found by fuzzing).
      throw Damaged{"raw values of " + std::to_string(uint64_t(0) - uint64_t(stored)) + " bytes where " +
                    std::to_string(r.valueCount) +
                    " values take " + std::to_string(r.decodedBytes)};
    r.payloadBytes = r.decodedBytes;
    return;
  }
  r.payloadBytes = uint64_t(stored);
  if (zip) {
    const uint64_t bound = compressBound(uLong(r.decodedBytes));
    if (r.payloadBytes > bound)
      throw Damaged{"zip data of " + std::to_string(stored) + " bytes for " + std::to_string(r.decodedBytes) +
                    " bytes of values (valid: up to " + std::to_string(bound) + ")"};
    r.encoding = Record::Encoding::Zip;
    return;
  }
  if (r.payloadBytes < kBloscHeader || r.payloadBytes > r.decodedBytes + BLOSC_MAX_OVERHEAD)
    throw Damaged{"blosc data of " + std::to_string(stored) + " bytes for " + std::to_string(r.decodedBytes) +
                  " bytes of values (valid: " + std::to_string(kBloscHeader) + " to " +
                  std::to_string(r.decodedBytes + BLOSC_MAX_OVERHEAD) + ")"};
  need(r.payloadAt + kBloscHeader, "the blosc header");
  size_t nbytes = 0;
  if ((blosc_cbuffer_validate(p + r.payloadAt, size_t(r.payloadBytes), &nbytes) != 0 || nbytes != r.decodedBytes) &&
      r.damage.empty())
    r.damage = "its blosc header does not describe " + std::to_string(r.decodedBytes) + " bytes in " + std::to_string(stored);
  r.encoding = Record::Encoding::Blosc;
}

// Decodes the values of `rec` stored at `src` into `dst` (rec.decodedBytes bytes). Returns what failed, or
// nothing.
std::string decodeValues(const Record& rec, const uint8_t* src, uint8_t* dst) {
  switch (rec.encoding) {
    case Record::Encoding::Raw:
      if (rec.decodedBytes > 0) std::memcpy(dst, src, size_t(rec.decodedBytes));
      return {};
    case Record::Encoding::Blosc: {
      const int n = blosc_decompress_ctx(src, dst, size_t(rec.decodedBytes), /*numinternalthreads=*/1);
      if (n < 0 || uint64_t(n) != rec.decodedBytes)
        return "its blosc data does not decompress to " + std::to_string(rec.decodedBytes) + " bytes (" +
               (n < 0 ? "blosc error " + std::to_string(n) : std::to_string(n) + " bytes") + ")";
      return {};
    }
    case Record::Encoding::Zip: {
      uLongf n = uLongf(rec.decodedBytes);
      const int status = uncompress(dst, &n, src, uLong(rec.payloadBytes));
      if (status != Z_OK || n != rec.decodedBytes)
        return "its zip data does not inflate to " + std::to_string(rec.decodedBytes) + " bytes (" +
               (status != Z_OK ? std::string(zError(status)) : std::to_string(n) + " bytes") + ")";
      return {};
    }
  }
  return "unknown encoding";
}

// Parses a leaf record's head from `p` (`avail` bytes of it are present; fewer than the whole record while
// indexing): its value mask, then its values. Throws Damaged for anything the format does not allow.
Record parseRecord(const uint8_t* p, uint64_t avail, const Mask3& topologyMask, const Format& f) {
  if (kMaskBytes + 1 > avail) throw Damaged{"the value mask runs past the end of the grid's buffer section"};
  Record r;
  for (int w = 0; w < 8; ++w) {
    uint64_t word;
    std::memcpy(&word, p + 8 * w, 8);
    if (word != topologyMask.getWord<uint64_t>(w)) r.damage = "its value mask differs from the topology's";
  }
  parseValues(p, avail, kMaskBytes, kLeafVoxels, topologyMask.countOn(), kMaskBytes, f, r);
  return r;
}

// OpenVDB's Tree/RootNode/InternalNode/LeafNode::readTopology trust every byte they read: a compressed
// size prefix is allocated as it says and a raw one copied into a buffer sized by the node (a heap
// overflow), a second root child at an origin already taken replaces the first (leaked), an unaligned
// root origin or a bit on in both of a node's masks (a child pointer then read as a tile value) breaks
// the tree's invariants, and a tile's active flag is loaded as a bool whatever its byte. So the topology
// is walked here first, byte for byte as OpenVDB will read it (file versions 222 to 224), and OpenVDB
// reads only what passed. Found by fuzz_vdb_leaf_reader (docs/RELIABILITY.md).
class TopologyCheck {
 public:
  TopologyCheck(FieldReader& r, const Format& f) : r_(r), f_(f) {}

  void tree() {
    const int32_t bufferCount = r_.get<int32_t>("the topology");
    if (bufferCount != 1) r_.fail("its tree has " + std::to_string(bufferCount) + " buffers (valid: 1)");
    const size_t valueSize = 4 * size_t(f_.components);
    r_.skip(valueSize, "the background");
    const uint64_t tiles = r_.get<uint32_t>("the root tile count"), children = r_.get<uint32_t>("the root child count");
    const uint64_t tileBytes = 12 + valueSize + 1, childBytes = 12 + 2 * 4096 + 1;
    if (tiles * tileBytes + children * childBytes > r_.cursor().left())
      r_.fail("its root claims " + std::to_string(tiles) + " tiles and " + std::to_string(children) +
              " children, more than fit in its topology");
    std::vector<Coord> keys;
    keys.reserve(size_t(tiles + children));
    for (uint64_t n = 0; n < tiles; ++n) {
      keys.push_back(rootKey("a root tile"));
      r_.skip(valueSize, "a root tile's value");
      const uint8_t active = r_.get<uint8_t>("a root tile's active flag");
      if (active > 1)
        r_.fail("the root tile at " + coordText(keys.back()) + " has active flag " + std::to_string(active) + " (valid: 0, 1)");
    }
    for (uint64_t n = 0; n < children; ++n) {
      keys.push_back(rootKey("a root child"));
      internal(keys.back(), 5);
    }
    std::sort(keys.begin(), keys.end());
    const auto twice = std::adjacent_find(keys.begin(), keys.end());
    if (twice != keys.end()) r_.fail("its root holds two nodes at " + coordText(*twice));
  }

 private:
  // A root tile's or child's origin: a multiple of 4096, the 32^3 node's extent, in each axis.
  Coord rootKey(const char* what) {
    Coord c;
    for (int axis = 0; axis < 3; ++axis) c[axis] = r_.get<int32_t>(what);
    if ((c.x() | c.y() | c.z()) & 4095)
      r_.fail(std::string(what) + " at " + coordText(c) + " is not at a multiple of 4096");
    return c;
  }

  // An internal node of 2^(3 log2) values: child mask, value mask, tile values, then its children in
  // child-mask order (16^3 nodes under a 32^3 node, leaves' value masks under a 16^3 node).
  void internal(const Coord& origin, int log2) {
    const uint32_t total = 1u << (3 * log2);
    const size_t maskBytes = total / 8;
    const std::string node = "the " + std::to_string(1 << log2) + "^3 node at " + coordText(origin);
    const uint8_t* p = r_.cursor().peek(2 * maskBytes);
    if (!p) r_.fail(node + ": its masks run past " + r_.endName());
    std::vector<uint64_t> childMask(maskBytes / 8);
    std::memcpy(childMask.data(), p, maskBytes);
    uint32_t valuesOn = 0;
    for (size_t w = 0; w < childMask.size(); ++w) {
      uint64_t valueWord;
      std::memcpy(&valueWord, p + maskBytes + 8 * w, 8);
      if (valueWord & childMask[w]) r_.fail(node + ": a child is also an active tile (its masks overlap)");
      valuesOn += uint32_t(__builtin_popcountll(valueWord));
    }
    r_.cursor().skip(2 * maskBytes);

    const uint64_t avail = std::min<uint64_t>(1 + 2 * 16 + maskBytes + 8 + kBloscHeader, r_.cursor().left());
    Record values;
    try {
      parseValues(r_.cursor().peek(size_t(avail)), avail, 0, total, valuesOn, maskBytes, f_, values);
    } catch (const Damaged& d) {
      r_.fail(node + ": its tile values: " + d.what);
    }
    if (!values.damage.empty()) r_.fail(node + ": its tile values: " + values.damage);
    // OpenVDB throws for values that do not decompress, after it allocated the node: leaked. Decoded here
    // once more (at most 512 KiB, and only where compressed).
    const uint8_t* stored = r_.cursor().peek(size_t(values.size()));
    if (!stored) r_.fail(node + ": its tile values run past " + r_.endName());
    if (values.encoding != Record::Encoding::Raw) {
      scratch_.resize(size_t(values.decodedBytes));
      if (const std::string failed = decodeValues(values, stored + values.payloadAt, scratch_.data()); !failed.empty())
        r_.fail(node + ": its tile values: " + failed);
    }
    r_.cursor().skip(values.size());

    const int childLog2Extent = log2 == 5 ? 7 : 3;  // a 16^3 node spans 128 voxels, a leaf 8
    for (size_t w = 0; w < childMask.size(); ++w)
      for (uint64_t bits = childMask[w]; bits; bits &= bits - 1) {
        const uint32_t i = uint32_t(64 * w) + uint32_t(__builtin_ctzll(bits));
        const Coord child = origin + (Coord(int32_t(i >> (2 * log2)), int32_t((i >> log2) & ((1u << log2) - 1)),
                                            int32_t(i & ((1u << log2) - 1)))
                                      << size_t(childLog2Extent));
        if (log2 == 5)
          internal(child, 4);
        else
          r_.skip(kMaskBytes, "the value mask of the leaf at " + coordText(child));
      }
  }

  FieldReader& r_;
  const Format f_;
  std::vector<uint8_t> scratch_;
};

template <class TreeT>
const TreeT& treeOf(const openvdb::GridBase& grid) {
  return static_cast<const openvdb::Grid<TreeT>&>(grid).tree();
}

}  // namespace

const std::vector<std::string>& VdbLeafReader::supportedTypes() {
  static const std::vector<std::string> types{kFloatTreeType, kFccTreeTypeName};
  return types;
}

std::vector<VdbGridEntry> VdbLeafReader::listGrids(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(path + ": cannot open: " + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw InputError(path + ": cannot stat: " + std::strerror(errno));
  std::vector<VdbGridEntry> out;
  for (const auto& d : readFileHeader(fd, path, uint64_t(st.st_size)).grids)
    out.push_back({d.displayName(), d.type, d.half});
  return out;
}

VdbLeafReader::VdbLeafReader(const std::string& path, const std::string& gridName,
                             const std::vector<std::string>& requestedTypes, bool indexLeaves)
    : path_(path) {
  std::vector<std::string> types = requestedTypes.empty() ? supportedTypes() : requestedTypes;
  for (const auto& t : types)
    if (std::find(supportedTypes().begin(), supportedTypes().end(), t) == supportedTypes().end())
      throw ValueError("VdbLeafReader reads " + typeList(supportedTypes()) + " grids, not " + t);
  initializeVdb();

  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw InputError(path + ": cannot open: " + std::strerror(errno));
  try {
    struct stat st {};
    if (::fstat(fd_, &st) != 0) throw InputError(path + ": cannot stat: " + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) throw InputError(path + ": not a regular file; valid inputs are .vdb files");
    fileSize_ = uint64_t(st.st_size);

    // --- The grid: by name, or the first of the types.
    const FileHeader header = readFileHeader(fd_, path, fileSize_);
    fileVersion_ = header.fileVersion;
    const Descriptor* chosen = nullptr;
    for (const auto& d : header.grids) {
      const bool typeOk = std::find(types.begin(), types.end(), d.type) != types.end();
      if (gridName.empty() ? typeOk
                           : (d.uniqueName == gridName || d.displayName() == gridName ||
                              openvdb::io::GridDescriptor::stripSuffix(d.uniqueName) == gridName)) {
        chosen = &d;
        break;
      }
    }
    if (!chosen && !gridName.empty())
      throw InputError(path + ": no grid named " + quotedText(gridName) + "; grids: " + gridList(header.grids));
    if (!chosen)
      throw InputError(path + ": holds no grid of type " + typeList(types) + " (grids: " + gridList(header.grids) + ")");
    const Descriptor& d = *chosen;
    gridName_ = d.displayName();
    gridType_ = d.type;
    half_ = d.half;
    const std::string gridText = path + ": grid " + quotedText(gridName_);
    if (std::find(types.begin(), types.end(), d.type) == types.end())
      throw InputError(gridText + " is a " + escaped(d.type) + " grid; valid here: " + typeList(types));
    if (!d.instanceParent.empty())
      throw InputError(gridText + " is an instance of grid " +
                       quotedText(openvdb::io::GridDescriptor::nameAsString(d.instanceParent)) +
                       " (it shares that grid's tree); instanced grids are not supported: write the file without "
                       "instancing, or open the parent grid");
    components_ = componentsOf(d.type);
    gridPos_ = uint64_t(d.gridPos);
    blockPos_ = uint64_t(d.blockPos);
    endPos_ = uint64_t(d.endPos);

    // --- Compression flags and metadata: ours, then each metadata value through OpenVDB from its own bytes.
    Cursor c(fd_, path, uint64_t(d.gridPos), blockPos_, 1 << 16);
    FieldReader r(c, gridText + " is damaged: ");
    r.setEndName("the grid's buffer section");
    compression_ = r.get<uint32_t>("the compression flags");
    if (compression_ & ~kKnownCompression)
      r.fail("compression flags " + std::to_string(compression_) + " (valid: zip 1, active mask 2, blosc 4)");
    const std::vector<MetaEntry> meta = parseMetaMap(r, "the grid metadata");
    const uint64_t transformPos = c.pos();

    openvdb::GridBase::Ptr grid;
    if (components_ == 1)
      grid = openvdb::FloatGrid::create();
    else
      grid = FccGrid::create();
    for (const MetaEntry& e : meta) {
      // Archive drops the delayed-load metadata (it only serves OpenVDB's own reading), and MetaMap::readMeta
      // drops unknown temporary ("__") metadata. Neither is ever parsed here.
      if (e.type == openvdb::io::DelayedLoadMetadata::staticTypeName()) continue;
      const bool known = openvdb::Metadata::isRegisteredType(e.type);
      if (!known && e.type.compare(0, 2, "__") == 0) continue;
      std::string bytes(4 + size_t(e.valueBytes), '\0');
      std::memcpy(bytes.data(), &e.valueBytes, 4);
      if (e.valueBytes > 0 && !preadExact(fd_, path, e.valuePos, bytes.data() + 4, e.valueBytes))
        r.fail("metadata " + quotedText(e.name) + " runs past the end of the file");
      std::istringstream in(bytes);
      openvdb::Metadata::Ptr value;
      try {
        value = known ? openvdb::Metadata::createMetadata(e.type)
                      : openvdb::Metadata::Ptr(new openvdb::UnknownMetadata(e.type));
        value->read(in);
      } catch (const std::exception& ex) {
        r.fail("metadata " + quotedText(e.name) + " (" + escaped(e.type) + ") does not read: " + ex.what());
      }
      if (!in || in.tellg() != std::streampos(bytes.size()))
        r.fail("metadata " + quotedText(e.name) + " (" + escaped(e.type) + ") holds " + std::to_string(e.valueBytes) +
               " bytes, not what its type stores");
      try {
        grid->insertMeta(e.name, *value);
      } catch (const std::exception& ex) {
        // OpenVDB's MetaMap throws its own ValueError for an empty name and TypeError for a name given
        // twice with two types; found by fuzz_vdb_leaf_reader (docs/RELIABILITY.md).
        r.fail("metadata " + quotedText(e.name) + " (" + escaped(e.type) + ") is refused: " + ex.what());
      }
    }
    // After the metadata: OpenVDB keeps the half flag as metadata ("is_saved_as_half_float"), which the file
    // holds too, and a file whose metadata contradicts its descriptor made OpenVDB read the topology's tile
    // values at another size than the walk above checked (a heap overflow; found by fuzz_vdb_leaf_reader).
    // The descriptor decides, as for the leaf buffers.
    grid->setSaveFloatAsHalf(half_);

    // --- Transform and topology through OpenVDB, on a stream tagged as Archive::readGrid tags it.
    {
      Cursor t(fd_, path, transformPos, blockPos_, 1 << 12);
      FieldReader tr(t, gridText + " is damaged: ");
      tr.setEndName("the grid's buffer section");
      const std::string mapType = tr.string("the transform's map type");
      if (!openvdb::math::MapRegistry::isRegistered(mapType))
        tr.fail("the transform's map type " + quotedText(mapType) + " is not one OpenVDB knows");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open: " + std::strerror(errno));
    auto streamMeta = std::make_shared<openvdb::io::StreamMetadata>();
    openvdb::io::setStreamMetadataPtr(in, streamMeta, /*transfer=*/false);  // holds &streamMeta: keep it alive
    openvdb::io::setVersion(in, openvdb::VersionId(header.libraryMajor, header.libraryMinor), header.fileVersion);
    openvdb::io::setDataCompression(in, compression_);
    streamMeta->setSeekable(true);
    streamMeta->setHalfFloat(half_);
    openvdb::io::setGridBackgroundValuePtr(in, nullptr);
    streamMeta->gridMetadata() = static_cast<openvdb::MetaMap&>(*grid);
    openvdb::io::setGridClass(in, grid->getGridClass());
    streamMeta->setLeaf(0);
    in.seekg(std::streamoff(transformPos));
    try {
      grid->readTransform(in);
    } catch (const std::exception& ex) {
      throw InputError(gridText + " is damaged: its transform does not read: " + ex.what());
    }
    const auto topologyPos = std::streamoff(in.tellg());
    if (!in || topologyPos < 0 || uint64_t(topologyPos) > blockPos_)
      throw InputError(gridText + " is damaged: its transform runs past the grid's buffer section");
    {
      Cursor t(fd_, path, uint64_t(topologyPos), blockPos_, 1 << 16);
      FieldReader tr(t, gridText + " is damaged: ");
      tr.setEndName("the grid's buffer section");
      TopologyCheck(tr, Format{components_, half_, compression_}).tree();
      if (t.pos() != blockPos_)
        tr.fail("its topology ends at byte " + std::to_string(t.pos()) + " but its buffers start at byte " +
                std::to_string(blockPos_));
    }
    try {
      grid->readTopology(in);
    } catch (const std::exception& ex) {
      throw InputError(gridText + " is damaged: its topology does not read: " + ex.what());
    }
    if (!in || std::streamoff(in.tellg()) != std::streamoff(blockPos_))
      throw InputError(gridText + " is damaged: its topology " +
                       (in ? "ends at byte " + std::to_string(std::streamoff(in.tellg())) : std::string("runs past its end")) +
                       " but its buffers start at byte " + std::to_string(blockPos_));
    openvdb::io::clearStreamMetadataPtr(in);
    grid_ = grid;

    // --- The index of leaf buffers.
    if (!indexLeaves) return;
    if (components_ == 1)
      buildIndex(treeOf<openvdb::FloatTree>(*grid_));
    else
      buildIndex(treeOf<FccTree>(*grid_));
  } catch (...) {
    ::close(fd_);
    throw;
  }
}

VdbLeafReader::~VdbLeafReader() {
  if (fd_ >= 0) ::close(fd_);
}

namespace {

// Where the record after a leaf whose head is damaged begins: the first offset from `p` (a record
// whose head is unreadable, `avail` bytes of it and what follows present, `left` bytes to the buffer
// section's end) at which the next leaf's value mask `nextMask` stands and its record's head parses
// cleanly, the record within the section; nullopt if none does within the largest record. For the
// last leaf (nextMask null) the section's end, `left` itself, if a record can be that long.
std::optional<uint64_t> recordSizeFromTheNext(const uint8_t* p, uint64_t avail, uint64_t left, const Mask3* nextMask,
                                              const Format& f) {
  const uint64_t least = kMaskBytes + 1;
  if (!nextMask) return left >= least && left <= VdbLeafReader::kMaxLeafBytes ? std::optional<uint64_t>(left) : std::nullopt;
  uint8_t maskBytes[kMaskBytes];
  for (int w = 0; w < 8; ++w) {
    const uint64_t word = nextMask->getWord<uint64_t>(w);
    std::memcpy(maskBytes + 8 * w, &word, 8);
  }
  for (uint64_t at = least; at <= VdbLeafReader::kMaxLeafBytes && at + least <= avail; ++at) {
    if (std::memcmp(p + at, maskBytes, kMaskBytes) != 0) continue;
    try {
      const Record next = parseRecord(p + at, avail - at, *nextMask, f);
      if (next.damage.empty() && next.size() <= left - at) return at;
    } catch (const Damaged&) {
      // not a record: look further
    }
  }
  return std::nullopt;
}

}  // namespace

template <class TreeT>
void VdbLeafReader::buildIndex(const TreeT& tree) {
  for (int k = 0; k < components_; ++k) background_[k] = reinterpret_cast<const float*>(&tree.background())[k];
  const size_t leaves = tree.leafCount();
  // At least a mask and a metadata byte per leaf: a damaged topology cannot make us reserve more than that.
  if (uint64_t(leaves) * (kMaskBytes + 1) > endPos_ - blockPos_)
    throw InputError(path_ + ": grid " + quotedText(gridName_) + " is damaged: its " + std::to_string(leaves) +
                     " leaves do not fit in its buffer section of " + std::to_string(endPos_ - blockPos_) + " bytes");
  index_.reserve(leaves);
  origins_.reserve(leaves);
  const Format format{components_, half_, compression_};
  Cursor c(fd_, path_, blockPos_, endPos_, kIndexChunk);
  std::vector<const typename TreeT::LeafNodeType*> leafNodes;  // for the next leaf's mask
  leafNodes.reserve(leaves);
  for (auto it = tree.cbeginLeaf(); it; ++it) leafNodes.push_back(&*it);
  for (size_t n = 0; n < leafNodes.size(); ++n) {
    const auto* it = leafNodes[n];
    const Coord origin = it->origin();
    const uint64_t at = c.pos();
    auto damaged = [&](const std::string& what) {
      return InputError(path_ + ": leaf at " + coordText(origin) + " is damaged: " + what + " (byte " +
                        std::to_string(at) + " of the file)");
    };
    if (!origins_.empty() && !treeOrderLess(origins_.back(), origin))
      throw damaged("its origin is out of tree order after " + coordText(origins_.back()) + " (damaged topology)");
    const uint64_t avail = std::min<uint64_t>(kMaxRecordHead, c.left());
    Record rec;
    try {
      rec = parseRecord(c.peek(size_t(avail)), avail, it->valueMask(), format);
      if (rec.size() > c.left()) throw Damaged{"its values run past the end of the grid's buffer section"};
      if (rec.size() > kMaxLeafBytes) throw Damaged{"it is larger than any leaf can be"};  // parseRecord bounds it
    } catch (const Damaged& e) {
      // Its head is damaged, so its size is unknown: the next leaf's record, found by its mask, says it.
      const uint64_t window = std::min<uint64_t>(kMaxLeafBytes + kMaxRecordHead, c.left());
      const Mask3* nextMask = n + 1 < leafNodes.size() ? &leafNodes[n + 1]->valueMask() : nullptr;
      const std::optional<uint64_t> size = recordSizeFromTheNext(c.peek(size_t(window)), window, c.left(), nextMask, format);
      if (!size) throw damaged(e.what);
      rec = Record{};
      rec.payloadAt = *size;  // size() is the whole record
      damagedHeads_.emplace(index_.size(), e.what);
    }
    if (!rec.damage.empty() || damagedHeads_.count(index_.size())) ++damagedAtOpen_;  // readLeaf says what
    c.skip(rec.size());
    index_.push_back({at, rec.size()});
    origins_.push_back(origin);
  }
  if (c.pos() != endPos_)
    throw InputError(path_ + ": grid " + quotedText(gridName_) + " is damaged: its buffer section holds " +
                     std::to_string(endPos_ - c.pos()) + " bytes after its last leaf (at byte " +
                     std::to_string(c.pos()) + ")");
}

std::optional<size_t> VdbLeafReader::leafIndexAt(const Coord& origin) const {
  const auto it = std::lower_bound(origins_.begin(), origins_.end(), origin, treeOrderLess);
  if (it == origins_.end() || *it != origin) return std::nullopt;
  return size_t(it - origins_.begin());
}

const openvdb::util::NodeMask<3>* VdbLeafReader::topologyMask(size_t i) const {
  if (components_ == 1) {
    const auto* leaf = treeOf<openvdb::FloatTree>(*grid_).probeConstLeaf(origins_[i]);
    return leaf ? &leaf->valueMask() : nullptr;
  }
  const auto* leaf = treeOf<FccTree>(*grid_).probeConstLeaf(origins_[i]);
  return leaf ? &leaf->valueMask() : nullptr;
}

void VdbLeafReader::readLeaf(size_t i, float* values) const {
  if (i >= index_.size())
    throw ValueError(path_ + ": leaf " + std::to_string(i) + " requested of " + std::to_string(index_.size()));
  const Entry& e = index_[i];
  const Coord origin = origins_[i];
  auto damaged = [&](const std::string& what) {
    return InputError(path_ + ": leaf at " + coordText(origin) + " is damaged: " + what + " (byte " +
                      std::to_string(e.offset) + " of the file)");
  };
  const Mask3* mask = topologyMask(i);
  if (!mask) throw Error(path_ + ": leaf at " + coordText(origin) + " is no longer in the grid's tree (it was modified)");
  if (e.bytes > kMaxLeafBytes || e.offset < blockPos_ || e.offset + e.bytes > endPos_)
    throw damaged("its index entry is out of range");  // cannot happen: checked while indexing

  uint8_t record[kMaxLeafBytes];
  if (!preadExact(fd_, path_, e.offset, record, size_t(e.bytes)))
    throw damaged("the file ends inside it (it was truncated after it was opened)");
  if (const auto head = damagedHeads_.find(i); head != damagedHeads_.end())
    throw damaged(head->second + " (the next leaf's record was found by its value mask)");
  const Format format{components_, half_, compression_};
  Record rec;
  try {
    rec = parseRecord(record, e.bytes, *mask, format);
  } catch (const Damaged& d) {
    throw damaged(d.what + " (the file changed after it was opened?)");
  }
  if (rec.size() != e.bytes) throw damaged("its size differs from when the file was opened");
  if (!rec.damage.empty()) throw damaged(rec.damage);

  // The stored values, decoded to their element size.
  alignas(8) uint8_t decoded[kLeafVoxels * 16];
  if (const std::string failed = decodeValues(rec, record + rec.payloadAt, decoded); !failed.empty())
    throw damaged(failed);

  const int comps = components_;
  const size_t count = size_t(rec.valueCount) * size_t(comps);  // floats stored
  alignas(16) float stored[kLeafVoxels * 4];
  if (half_) {
    for (size_t k = 0; k < count; ++k) {
      uint16_t bits;
      std::memcpy(&bits, decoded + 2 * k, 2);
      openvdb::math::half h;
      h.setBits(bits);
      stored[k] = float(h);
    }
  } else {
    std::memcpy(stored, decoded, count * 4);
  }

  const size_t leafFloats = size_t(kLeafVoxels) * size_t(comps);
  if (rec.valueCount == kLeafVoxels) {  // every value stored (as readCompressedValues: no restoring)
    std::memcpy(values, stored, leafFloats * 4);
    return;
  }
  // Mask-compressed: active values in order, inactive ones from the metadata (readCompressedValues).
  using namespace openvdb::io;
  float inactive0[4], inactive1[4];
  for (int k = 0; k < comps; ++k) {
    inactive1[k] = background_[k];
    inactive0[k] = rec.metadata == NO_MASK_OR_INACTIVE_VALS ? background_[k] : -background_[k];
  }
  if (rec.inactiveAt) {
    std::memcpy(inactive0, record + rec.inactiveAt, 4 * size_t(comps));
    if (rec.metadata == MASK_AND_TWO_INACTIVE_VALS)
      std::memcpy(inactive1, record + rec.inactiveAt + 4 * size_t(comps), 4 * size_t(comps));
  }
  const uint8_t* selection = rec.selectionAt ? record + rec.selectionAt : nullptr;
  size_t next = 0;
  for (uint32_t n = 0; n < kLeafVoxels; ++n) {
    float* out = values + size_t(n) * size_t(comps);
    if (mask->isOn(n)) {
      std::memcpy(out, stored + next, 4 * size_t(comps));
      next += size_t(comps);
    } else {
      const bool one = selection && ((selection[n >> 3] >> (n & 7)) & 1);
      std::memcpy(out, one ? inactive1 : inactive0, 4 * size_t(comps));
    }
  }
}

}  // namespace fcc::io
