#include "StreamedFccTree.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <openvdb/io/io.h>

#include <atomic>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "Error.h"

namespace fcc {
namespace {

using Leaf = FccBlockBuilder::Leaf;

// Leaves rebuilt and encoded at once (2 MiB of values, and their encoded bytes); the next batch is
// built while one is written. (1024 held 4x the memory for no gain that was measured.)
constexpr size_t kBatchLeaves = 256;

openvdb::Coord blockOf(const Leaf& leaf) {
  const openvdb::Coord o = leaf.origin();
  return openvdb::Coord(o.x() / int(Leaf::DIM), o.y() / int(Leaf::DIM), o.z() / int(Leaf::DIM));
}

// Whether `bytes` (LeafNode::writeBuffers's output) begin with `leaf`'s value mask, as that call writes
// it first: a kept leaf that is not the one the topology holds there is never written.
bool startsWithMaskOf(const std::string& bytes, const Leaf& leaf) {
  using Mask = Leaf::NodeMaskType;
  const Mask& mask = leaf.valueMask();
  Mask::Word words[Mask::WORD_COUNT];  // what NodeMask::save writes: its words, in order
  for (openvdb::Index w = 0; w < Mask::WORD_COUNT; ++w) words[w] = mask.getWord<Mask::Word>(w);
  return bytes.size() >= sizeof words && std::memcmp(bytes.data(), words, sizeof words) == 0;
}

}  // namespace

StreamedFccTree::StreamedFccTree(const FccBlockBuilder& builder, openvdb::util::NullInterrupter* progress)
    : FccTree(openvdb::Vec4f(builder.background())), builder_(builder), progress_(progress) {}

openvdb::Index64 StreamedFccTree::memUsage() const { return openvdb::tools::memUsageIfLoaded(static_cast<const FccTree&>(*this)); }

void StreamedFccTree::writeBuffers(std::ostream& os, bool saveFloatAsHalf) const {
  std::vector<const Leaf*> topology;
  topology.reserve(leafCount());
  for (auto it = cbeginLeaf(); it; ++it) topology.push_back(it.getLeaf());

  // What LeafNode::writeBuffers reads of the stream besides the bytes it writes: the compression
  // flags and the grid's background (for the active-mask compression). Each leaf is encoded into a
  // stream of its own carrying the same two, in parallel (compression was most of pass 2, on one
  // thread), and the bytes are written in the tree's order: the file is the same, byte for byte.
  const uint32_t compression = openvdb::io::getDataCompression(os);
  const void* background = openvdb::io::getGridBackgroundValuePtr(os);
  tbb::enumerable_thread_specific<FccBlockBuilder::Scratch> scratch;
  const bool useKept = kept_ && kept_->suits(compression, background, saveFloatAsHalf);
  std::atomic<size_t> copied{0}, rebuilt{0};
  auto build = [&](size_t first, std::vector<std::string>& out) {
    out.clear();
    out.resize(std::min(kBatchLeaves, topology.size() - first));
    // The kept leaves first (a mask that is not the topology's is a leaf to rebuild), then the rest.
    std::vector<char> copiedHere(out.size(), 0);
    if (useKept) {
      tbb::parallel_for(tbb::blocked_range<size_t>(0, out.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i)
          copiedHere[i] = kept_->read(topology[first + i]->origin(), out[i]) && startsWithMaskOf(out[i], *topology[first + i]);
      });
    }
    std::vector<size_t> missing;
    for (size_t i = 0; i < out.size(); ++i)
      if (!copiedHere[i]) missing.push_back(i);
    copied += out.size() - missing.size();
    rebuilt += missing.size();
    if (missing.empty()) return;
    std::vector<openvdb::Coord> blocks(missing.size());
    for (size_t m = 0; m < missing.size(); ++m) blocks[m] = blockOf(*topology[first + missing[m]]);
    builder_.prepare(blocks);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, missing.size(), 8), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t m = r.begin(); m != r.end(); ++m) {
        const size_t i = missing[m];
        const std::unique_ptr<Leaf> leaf = builder_.build(blocks[m], scratch.local(), nullptr);
        const Leaf& expected = *topology[first + i];
        if (!leaf || leaf->valueMask() != expected.valueMask()) {
          std::ostringstream where;
          where << expected.origin();
          throw Error("streamed FCC grid: the leaf at packed voxel " + where.str() +
                      " was rebuilt with another active mask than its topology's");
        }
        out[i] = encodeLeaf(*leaf, compression, background, saveFloatAsHalf);
      }
    });
  };
  auto write = [&](const std::vector<std::string>& leaves) {
    for (const std::string& bytes : leaves) os.write(bytes.data(), std::streamsize(bytes.size()));
  };

  if (progress_) progress_->start("writing FCC grid");
  std::vector<std::string> current, next;
  if (!topology.empty()) build(0, current);
  for (size_t first = 0; first < topology.size(); first += kBatchLeaves) {
    const size_t following = first + kBatchLeaves;
    tbb::task_group group;
    if (following < topology.size()) group.run([&] { build(following, next); });
    try {
      write(current);
      if (progress_ && progress_->wasInterrupted(int(100.0 * double(first + current.size()) / double(topology.size()))))
        throw Error("interrupted");
    } catch (...) {
      group.cancel();
      group.wait();
      throw;
    }
    group.wait();
    std::swap(current, next);
  }
  if (progress_) progress_->end();
  copied_ = copied;
  rebuilt_ = rebuilt;
}

}  // namespace fcc
