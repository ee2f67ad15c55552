#include "CopiedFccTree.h"

#include <openvdb/tools/Count.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>

#include <vector>

#include "VdbLeafReader.h"
#include "sparse/Error.h"

namespace fcc::io {
namespace {

using Leaf = FccTree::LeafNodeType;

// Leaves read at once (2 MiB of values); the next batch is read while one is written.
constexpr size_t kBatchLeaves = 256;

}  // namespace

CopiedFccTree::CopiedFccTree(const BrickStore& source, openvdb::util::NullInterrupter* progress)
    : FccTree(source.index().tree().background()), source_(source), progress_(progress) {}

openvdb::Index64 CopiedFccTree::memUsage() const { return openvdb::tools::memUsageIfLoaded(source_.index().tree()); }
void CopiedFccTree::writeTopology(std::ostream& os, bool half) const { source_.index().tree().writeTopology(os, half); }
bool CopiedFccTree::evalActiveVoxelBoundingBox(openvdb::CoordBBox& b) const {
  return source_.index().tree().evalActiveVoxelBoundingBox(b);
}
bool CopiedFccTree::evalActiveVoxelDim(openvdb::Coord& d) const { return source_.index().tree().evalActiveVoxelDim(d); }
bool CopiedFccTree::evalLeafBoundingBox(openvdb::CoordBBox& b) const { return source_.index().tree().evalLeafBoundingBox(b); }
bool CopiedFccTree::evalLeafDim(openvdb::Coord& d) const { return source_.index().tree().evalLeafDim(d); }
openvdb::Index32 CopiedFccTree::leafCount() const { return source_.index().tree().leafCount(); }
openvdb::Index32 CopiedFccTree::nonLeafCount() const { return source_.index().tree().nonLeafCount(); }
openvdb::Index64 CopiedFccTree::activeVoxelCount() const { return source_.index().tree().activeVoxelCount(); }
openvdb::Index64 CopiedFccTree::inactiveVoxelCount() const { return source_.index().tree().inactiveVoxelCount(); }
openvdb::Index64 CopiedFccTree::activeLeafVoxelCount() const { return source_.index().tree().activeLeafVoxelCount(); }
openvdb::Index64 CopiedFccTree::inactiveLeafVoxelCount() const { return source_.index().tree().inactiveLeafVoxelCount(); }
openvdb::Index64 CopiedFccTree::activeTileCount() const { return source_.index().tree().activeTileCount(); }

void CopiedFccTree::writeBuffers(std::ostream& os, bool saveFloatAsHalf) const {
  // The source's leaves in its own order, the order its writeTopology wrote their masks in.
  std::vector<const Leaf*> topology;
  topology.reserve(leafCount());
  for (auto it = source_.index().tree().cbeginLeaf(); it; ++it) topology.push_back(it.getLeaf());

  auto read = [&](size_t first, std::vector<std::unique_ptr<Leaf>>& out) {
    out.clear();
    out.resize(std::min(kBatchLeaves, topology.size() - first));
    tbb::parallel_for(tbb::blocked_range<size_t>(0, out.size(), 8), [&](const tbb::blocked_range<size_t>& r) {
      BrickValues values;
      for (size_t i = r.begin(); i != r.end(); ++i) {
        const Leaf& shape = *topology[first + i];
        const openvdb::Coord b = shape.origin() >> 3;
        // false for a leaf of the topology: damaged (recorded in the store's damage()); stop below.
        if (!source_.readBrick(glm::ivec3(b.x(), b.y(), b.z()), values)) continue;
        auto leaf = std::make_unique<Leaf>(shape.origin(), source_.index().tree().background(), false);
        for (openvdb::Index n = 0; n < Leaf::SIZE; ++n) leaf->setValueOnly(n, values[n]);
        leaf->setValueMask(shape.valueMask());
        out[i] = std::move(leaf);
      }
    });
  };
  auto write = [&](const std::vector<std::unique_ptr<Leaf>>& leaves) {
    for (const auto& leaf : leaves) {
      if (!leaf) throw InputError(source_.damage().first);
      leaf->writeBuffers(os, saveFloatAsHalf);
    }
  };

  if (progress_) progress_->start(("copying " + source_.index().getName()).c_str());
  std::vector<std::unique_ptr<Leaf>> current, next;
  if (!topology.empty()) read(0, current);
  for (size_t first = 0; first < topology.size(); first += kBatchLeaves) {
    const size_t following = first + kBatchLeaves;
    tbb::task_group group;
    if (following < topology.size()) group.run([&] { read(following, next); });
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
}

FccGrid::Ptr copiedFccGrid(const BrickStore& source, openvdb::util::NullInterrupter* progress) {
  auto tree = std::make_shared<CopiedFccTree>(source, progress);
  FccGrid::Ptr grid = FccGrid::create(tree);
  const FccGrid& from = source.index();
  for (auto it = from.beginMeta(); it != from.endMeta(); ++it) grid->insertMeta(it->first, *it->second);  // name, class too
  grid->setTransform(from.transform().copy());
  grid->setSaveFloatAsHalf(source.storedAsHalf());
  return grid;
}

}  // namespace fcc::io
