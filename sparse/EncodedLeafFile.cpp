#include "EncodedLeafFile.h"

#include <openvdb/io/io.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <sstream>

namespace fcc {

std::string encodeLeaf(const FccTree::LeafNodeType& leaf, uint32_t compression, const void* background, bool half) {
  std::ostringstream bytes(std::ios_base::binary);
  openvdb::io::setDataCompression(bytes, compression);
  openvdb::io::setGridBackgroundValuePtr(bytes, background);
  leaf.writeBuffers(bytes, half);
  return bytes.str();
}

EncodedLeafFile::EncodedLeafFile(uint32_t compression, const openvdb::Vec4f& background, bool half, uint64_t maxBytes)
    : compression_(compression),
      background_(background),
      half_(half),
      file_("the encoded-leaf scratch file", "about the output's size"),
      maxBytes_(maxBytes ? maxBytes : file_.freeBytes() / 2) {}

void EncodedLeafFile::add(const Leaf& leaf) {
  if (stopped_.load(std::memory_order_relaxed)) return;
  const std::string bytes = encodeLeaf(leaf, compression_, &background_, half_);
  const uint64_t offset = next_.fetch_add(bytes.size());
  int error = 0;
  if (offset + bytes.size() > maxBytes_ || !file_.tryWrite(bytes.data(), bytes.size(), offset, error)) {
    stopped_ = true;  // the leaves kept so far stay usable; the rest are rebuilt in pass 2
    return;
  }
  added_.local().push_back({leaf.origin(), uint32_t(bytes.size()), offset});
}

void EncodedLeafFile::finish() {
  index_.clear();
  for (std::vector<Entry>& part : added_) {
    index_.insert(index_.end(), part.begin(), part.end());
    std::vector<Entry>().swap(part);
  }
  tbb::parallel_sort(index_.begin(), index_.end(), [](const Entry& a, const Entry& b) { return a.origin < b.origin; });
}

bool EncodedLeafFile::suits(uint32_t compression, const void* background, bool half) const {
  return compression == compression_ && half == half_ && background &&
         *static_cast<const openvdb::Vec4f*>(background) == background_;
}

bool EncodedLeafFile::read(const openvdb::Coord& origin, std::string& bytes) const {
  const auto found = std::lower_bound(index_.begin(), index_.end(), origin,
                                      [](const Entry& e, const openvdb::Coord& o) { return e.origin < o; });
  if (found == index_.end() || found->origin != origin) return false;
  bytes.resize(found->size);
  file_.read(bytes.data(), bytes.size(), found->offset);
  return true;
}

}  // namespace fcc
