#include "FccBuilder.h"

#include <openvdb/tools/Prune.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <vector>

#include "Error.h"

namespace fcc {

BuildResult buildFccGrid(const SampleField& field, const BuildOptions& options,
                         openvdb::util::NullInterrupter* interrupter) {
  using Leaf = FccBlockBuilder::Leaf;
  const FccBlockBuilder builder(field, options);
  auto grid = FccGrid::create(openvdb::Vec4f(field.background()));
  BuildResult result;
  result.grid = grid;
  const openvdb::CoordBBox blocks = builder.blocks();
  if (blocks.empty()) return result;
  const openvdb::Coord blockCount = blocks.dim();
  const size_t totalBlocks = blocks.volume();

  tbb::enumerable_thread_specific<std::vector<Leaf*>> leavesPerThread;
  tbb::enumerable_thread_specific<SampleStats> statsPerThread;
  tbb::enumerable_thread_specific<FccBlockBuilder::Scratch> scratchPerThread;
  std::atomic<size_t> blocksDone{0};
  std::atomic<bool> interrupted{false};
  if (interrupter) interrupter->start("building FCC grid");

  tbb::parallel_for(tbb::blocked_range<size_t>(0, totalBlocks, 16), [&](const tbb::blocked_range<size_t>& r) {
    auto& leaves = leavesPerThread.local();
    auto& stats = statsPerThread.local();
    auto& scratch = scratchPerThread.local();
    for (size_t b = r.begin(); b != r.end(); ++b) {
      if (interrupted.load(std::memory_order_relaxed)) return;
      const openvdb::Coord block = blocks.min().offsetBy(int(b % blockCount.x()), int((b / blockCount.x()) % blockCount.y()),
                                                         int(b / (size_t(blockCount.x()) * blockCount.y())));
      if (std::unique_ptr<Leaf> leaf = builder.build(block, scratch, &stats)) leaves.push_back(leaf.release());
      const size_t done = ++blocksDone;
      if (interrupter && (done & 63) == 0 &&
          interrupter->wasInterrupted(int(100.0 * double(done) / double(totalBlocks))))
        interrupted = true;
    }
  });

  auto& tree = grid->tree();
  for (auto& leaves : leavesPerThread)
    for (Leaf* leaf : leaves) tree.addLeaf(leaf);  // the tree takes ownership
  if (interrupted) throw Error("interrupted");
  // Uniform leaves become tiles: the tile tree is also the coarse level of the bounds hierarchy.
  openvdb::tools::prune(tree, openvdb::Vec4f(options.tolerance));
  if (interrupter) interrupter->end();

  SampleStats total;
  for (const SampleStats& s : statsPerThread) total.add(s);
  result.samples = summarizeSamples(total, builder.siteBounds(), field.background());
  return result;
}

}  // namespace fcc
