// One grid of a .vdb file opened for reading its leaf buffers one at a time, by us, with pread: nothing
// is mapped, any thread may read any leaf, and every size in the file is checked against what the format
// allows before anything is allocated or decompressed. (Debian's OpenVDB 10.0.1 trusts the sizes it
// reads, maps the whole file for delayed loading, and upstream has removed delayed loading.)
//
// What OpenVDB still parses: the chosen grid's metadata values, transform and topology (root tiles,
// internal node masks and tile values, leaf value masks), through Grid::readMeta/readTransform/
// readTopology on a std::ifstream. Everything else is ours: the file header, the file metadata (skipped),
// the grid descriptors, the structure of the grid's metadata and the whole topology (walked and checked
// before OpenVDB reads them: every size, origin, mask and compressed block), and the whole buffer
// section (the leaf masks again, io::readCompressedValues' layout, blosc/zip/plain values).
#pragma once

#include <openvdb/openvdb.h>

#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace fcc::io {

// A grid as its descriptor in a .vdb file names it.
struct VdbGridEntry {
  std::string name;  // as OpenVDB shows it: "name", or "name[N]" for the N-th of several with one name
  std::string type;  // tree type without the "_HalfFloat" suffix, e.g. "Tree_float_5_4_3"
  bool half = false;
};

// One grid of a .vdb file opened for leaf-by-leaf reading. Value types: float (FloatGrid, 1 component) and
// openvdb::Vec4f (4 components, fcc::FccTree) trees of the standard 5-4-3 configuration, stored as float
// or half.
class VdbLeafReader {
 public:
  // The tree types it reads: "Tree_float_5_4_3" and fcc::kFccTreeTypeName ("Tree_vec4s_5_4_3").
  static const std::vector<std::string>& supportedTypes();

  // Opens `path`, reads the file header and grid descriptors itself, picks grid `gridName` (empty: the
  // first grid whose type is in `types`; an empty `types` means supportedTypes()), then reads that
  // grid's metadata, transform and topology only, through OpenVDB, with the stream metadata Archive would
  // set, and indexes the leaf buffers by walking the buffer section once (sequentially, a few MiB at a
  // time, skipping the value bytes; 28 bytes a leaf).
  // InputError (one line, naming the file) for anything wrong: not a VDB, an unsupported version, no such
  // grid (listing the grids), a grid of another type, an instanced grid, sizes that point outside the
  // file, a buffer section that does not parse. ValueError if `types` names a type it cannot read.
  // `indexLeaves` false stops after the topology (no leaf can be read then): what the guard (fccvdb-guard)
  // needs to check, since the walk of the buffer section is ours and reads the whole file.
  VdbLeafReader(const std::string& path, const std::string& gridName, const std::vector<std::string>& types,
                bool indexLeaves = true);
  ~VdbLeafReader();  // closes the fd
  VdbLeafReader(const VdbLeafReader&) = delete;
  VdbLeafReader& operator=(const VdbLeafReader&) = delete;

  const std::string& path() const { return path_; }
  // Topology only: leaves without value buffers (PartialCreate: reading a leaf's values through OpenVDB
  // crashes), tiles with their values, metadata, transform. Shared: treat it as read-only.
  openvdb::GridBase::Ptr grid() const { return grid_; }
  const std::string& gridName() const { return gridName_; }  // as listGrids shows it
  const std::string& gridType() const { return gridType_; }  // without "_HalfFloat"
  int components() const { return components_; }              // 1 or 4
  bool storedAsHalf() const { return half_; }
  uint32_t compression() const { return compression_; }        // the grid's openvdb::io::COMPRESS_* flags
  uint32_t fileVersion() const { return fileVersion_; }

  size_t leafCount() const { return index_.size(); }
  // i in the tree's cbeginLeaf order (= order in the file).
  openvdb::Coord leafOrigin(size_t i) const { return origins_[i]; }
  // The index of the leaf with this origin (a multiple of 8 in each axis); nullopt if there is none.
  std::optional<size_t> leafIndexAt(const openvdb::Coord& origin) const;
  // Bytes of leaf i's buffer in the file (value mask, compression metadata, values).
  uint64_t leafBytes(size_t i) const { return index_[i].bytes; }
  uint64_t leafOffset(size_t i) const { return index_[i].offset; }
  // Where the grid is in the file: its compression flags, metadata, transform and topology from
  // gridBegin(), its buffer section [bufferBegin(), bufferEnd()).
  uint64_t gridBegin() const { return gridPos_; }
  uint64_t bufferBegin() const { return blockPos_; }
  uint64_t bufferEnd() const { return endPos_; }
  // Leaves found damaged while indexing: those whose size was still known (a value mask that differs
  // from the topology's, a blosc header that does not describe the leaf), and those whose record head
  // is damaged (a compression metadata byte or size prefix out of range) where the next leaf's record
  // was found by its value mask (or the buffer section ends where this one may): the file opens, and
  // readLeaf throws for exactly those. A damaged head with no such next record fails the opening.
  size_t damagedAtOpen() const { return damagedAtOpen_; }

  // Decodes leaf i: 512 * components() floats (component-interleaved, OpenVDB's voxel order: offset
  // n = x<<6 | y<<3 | z) into `values`, inactive voxels restored as OpenVDB restores them. Thread-safe
  // (pread, no shared mutable state). Throws InputError "FILE: leaf at (x, y, z) is damaged: WHAT" on any
  // inconsistency (also if the file shrank or changed since it was opened); never reads out of bounds.
  // The leaf's value mask comes from grid()'s tree (and must equal the one in the buffer): a tree someone
  // changed gives Error; an i out of range, ValueError.
  void readLeaf(size_t i, float* values) const;

  // Names, types and half flags of the grids in a .vdb file, from its descriptors alone (no OpenVDB).
  static std::vector<VdbGridEntry> listGrids(const std::string& path);

  // Everything a buffer record may hold: mask, metadata byte, two inactive Vec4f, selection mask, the
  // Int64 size prefix, 512 Vec4f and blosc's header overhead.
  static constexpr uint64_t kMaxLeafBytes = 64 + 1 + 2 * 16 + 64 + 8 + 512 * 16 + 16;

 private:
  struct Entry {
    uint64_t offset;  // of the leaf's record (its value mask) in the file
    uint64_t bytes;   // of the whole record
  };
  template <class TreeT>
  void buildIndex(const TreeT& tree);
  const openvdb::util::NodeMask<3>* topologyMask(size_t i) const;

  std::string path_;
  int fd_ = -1;
  uint64_t fileSize_ = 0;
  openvdb::GridBase::Ptr grid_;
  std::string gridName_, gridType_;
  int components_ = 1;
  bool half_ = false;
  uint32_t compression_ = 0;
  uint32_t fileVersion_ = 0;
  uint64_t gridPos_ = 0, blockPos_ = 0, endPos_ = 0;
  float background_[4] = {0, 0, 0, 0};
  std::vector<Entry> index_;
  std::vector<openvdb::Coord> origins_;
  size_t damagedAtOpen_ = 0;
  std::unordered_map<size_t, std::string> damagedHeads_;  // leaf index -> what was wrong with its head
};

}  // namespace fcc::io
