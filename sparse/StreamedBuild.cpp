#include "StreamedBuild.h"

#include <openvdb/io/Archive.h>
#include <openvdb/tools/Prune.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <vector>

#include "BrickKernels.h"
#include "EncodedLeafFile.h"
#include "Error.h"
#include "FccSlabWindow.h"
#include "StreamedFccTree.h"

namespace fcc {
namespace {

using openvdb::Coord;
using openvdb::CoordBBox;
using openvdb::Vec4f;
using Leaf = FccBlockBuilder::Leaf;
using LeafTile = FccSlabWindow::LeafTile;

using Clock = std::chrono::steady_clock;

// Seconds since `start`, which moves to now.
double lap(Clock::time_point& start) {
  const Clock::time_point now = Clock::now();
  const double s = std::chrono::duration<double>(now - start).count();
  start = now;
  return s;
}

// Bricks (= blocks) with x in [x0, x1], any y and z.
CoordBBox slabBricks(int x0, int x1) {
  CoordBBox box = CoordBBox::inf();
  box.min().setX(x0);
  box.max().setX(x1);
  return box;
}

// Whether the in-memory builder's prune (tools::prune with its tolerance) makes `leaf` a tile, and
// that tile: the same prune, run on a tree holding only this leaf.
bool prunesToTile(const Leaf& leaf, const Vec4f& background, float tolerance, LeafTile& tile) {
  Vec4f lo, hi;
  bool state;
  if (!leaf.isConstant(lo, hi, state, Vec4f(tolerance))) return false;  // the prune's own test, first
  FccTree alone(background);
  alone.addLeaf(new Leaf(leaf));
  openvdb::tools::prune(alone, Vec4f(tolerance));
  if (alone.leafCount() != 0) return false;
  tile = {leaf.origin(), alone.getValue(leaf.origin()), alone.isValueOn(leaf.origin())};
  return true;
}

// Pass 1 for one slab of blocks at a time: the leaves' masks (and the tiles of uniform leaves) go into
// the topology tree; the leaves themselves, rounded as stored, into the slab for the window.
class SlabBuilder {
 public:
  SlabBuilder(const FccBlockBuilder& builder, bool half, FccTree& topology, EncodedLeafFile* keep)
      : builder_(builder), half_(half), topology_(topology), background_(builder.background()), keep_(keep) {}

  FccSlabWindow::Slab build(int x, StreamedBuild::Times& times) {
    auto start = Clock::now();
    const std::vector<Coord> blocks = blocksInSlab(x);
    times.blocks += lap(start);
    builder_.prepare(blocks);
    times.prepare += lap(start);
    struct Built {
      std::unique_ptr<Leaf> leaf;
      bool isTile = false;
      LeafTile tile;
    };
    std::vector<Built> built(blocks.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks.size(), 4), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i) {
        const Coord& block = blocks[i];
        Built& b = built[i];
        const FccBlockBuilder::Uniform uniform = builder_.uniform(block, &stats_.local());
        if (uniform.known) {  // a tile without visiting the block's sites
          b.isTile = !uniform.none;
          b.tile = {block << Leaf::LOG2DIM, uniform.value, true};
          continue;
        }
        b.leaf = builder_.build(block, scratch_.local(), &stats_.local());
        if (!b.leaf) continue;
        b.isTile = prunesToTile(*b.leaf, background_, builder_.options().tolerance, b.tile);
        if (b.isTile) continue;
        if (keep_) keep_->add(*b.leaf);  // before rounding: pass 2 would encode the leaf as built
        if (half_) roundAsStoredHalf(b.leaf->beginValueAll(), background_);
      }
    });
    times.build += lap(start);
    FccSlabWindow::Slab slab;
    for (Built& b : built) {
      if (b.isTile) {
        topology_.addTile(1, b.tile.origin, b.tile.value, b.tile.active);
        LeafTile stored = b.tile;
        if (half_) stored.value = asStoredHalf(stored.value, background_);
        slab.tiles.push_back(stored);
      } else if (b.leaf) {
        auto mask = std::make_unique<Leaf>(openvdb::PartialCreate(), b.leaf->origin(), background_);
        mask->setValueMask(b.leaf->valueMask());
        topology_.addLeaf(mask.release());
        slab.leaves.push_back(std::move(b.leaf));
      }
    }
    return slab;
  }

  // The blocks of slab x. Finding them walks the source's topology over the slab's whole area
  // (serial and a sixth of pass 1 on 16 cores), so the next slabs are found at once, in parallel,
  // and kept until asked for (slabs are asked for in increasing x): up to 32 slabs, fewer where a
  // slab's list is long (a dense source lists its slab's whole area), about 1 M blocks in all.
  std::vector<Coord> blocksInSlab(int x) {
    auto found = ahead_.find(x);
    if (found == ahead_.end()) {
      ahead_.clear();
      const size_t perSlab = std::max<size_t>(lastListSize_, 1);
      const int lookAhead = int(std::clamp<size_t>(kAheadBlocks / perSlab, 1, 32));
      const int last = std::min(x + lookAhead - 1, builder_.blocks().max().x());
      std::vector<std::vector<Coord>> lists(size_t(std::max(1, last - x + 1)));
      tbb::parallel_for(0, int(lists.size()), [&](int i) { lists[size_t(i)] = builder_.blocksInSlab(x + i); });
      for (size_t i = 0; i < lists.size(); ++i) ahead_.emplace(x + int(i), std::move(lists[i]));
      found = ahead_.find(x);
    }
    std::vector<Coord> blocks = std::move(found->second);
    ahead_.erase(found);
    lastListSize_ = blocks.size();
    return blocks;
  }

  SampleStats stats() const {
    SampleStats total;
    for (const SampleStats& s : stats_) total.add(s);
    return total;
  }

 private:
  const FccBlockBuilder& builder_;
  bool half_;
  FccTree& topology_;
  Vec4f background_;
  EncodedLeafFile* keep_;
  tbb::enumerable_thread_specific<FccBlockBuilder::Scratch> scratch_;
  tbb::enumerable_thread_specific<SampleStats> stats_;
  static constexpr size_t kAheadBlocks = size_t(1) << 20;
  std::map<int, std::vector<Coord>> ahead_;
  size_t lastListSize_ = 1 << 16;  // before any list is known: 16 slabs at first
};

// Where pass 1 keeps its encoded leaves, with the compression io::File writes with; null without one
// (a temp folder where no file can be made costs pass 2's rebuild, never the conversion).
std::shared_ptr<EncodedLeafFile> keepLeavesFor(const Vec4f& background, const StreamedBuildOptions& options) {
  if (!options.keepLeaves) return nullptr;
  try {
    return std::make_shared<EncodedLeafFile>(openvdb::io::Archive::DEFAULT_COMPRESSION_FLAGS, background, options.half,
                                             options.keepLeavesMaxBytes);
  } catch (const Error&) {
    return nullptr;
  }
}

}  // namespace

StreamedBuild buildFccGridStreamed(const FccBlockBuilder& builder, const StreamedBuildOptions& options,
                                   openvdb::util::NullInterrupter* progress) {
  const Vec4f background(builder.background());
  auto topology = std::make_shared<StreamedFccTree>(builder, progress);
  StreamedBuild result;
  result.grid = FccGrid::create(topology);
  result.grid->setSaveFloatAsHalf(options.half);
  result.bounds = std::make_shared<openvdb::Vec2STree>(boundsBackground(background));
  const CoordBBox& blocks = builder.blocks();
  if (blocks.empty()) return result;
  std::unique_ptr<BrickKernels> own;
  BrickKernels& kernels = options.kernels ? *options.kernels : *(own = makeReferenceBrickKernels());

  // A brick's bounds read the coefficients one slab either side. Raw samples become coefficients
  // (prefilterGrid) from one slab further: a coefficient leaf exists where a sample leaf is within one
  // brick, and that decides which bricks get exact bounds. So the slabs of bricks whose bounds are
  // computed (the coefficient leaves' and their neighbours) reach as far beyond the blocks.
  const bool rawSamples = !builder.options().prefilter;
  const int reach = rawSamples ? 2 : 1;
  std::shared_ptr<EncodedLeafFile> kept = keepLeavesFor(background, options);
  SlabBuilder slabs(builder, options.half, *topology, kept.get());
  FccSlabWindow window(background);
  const int first = blocks.min().x() - reach, last = blocks.max().x() + reach;
  int nextSlab = blocks.min().x();
  // Bounds are computed for a run of slabs at once: each call reads the whole window (its leaves,
  // its tiles, their borders), so one slab a call read every slab 2 reach + 1 times. Runs of up to
  // 8 slabs, fewer where slabs are full (the window holds run + 2 reach slabs; about kWindowLeaves
  // leaves, 256 MiB, unless one slab is more) and no more than a sixteenth of the slabs, so that the
  // window stays a small part of any dataset.
  constexpr std::size_t kWindowLeaves = 32768;
  const int mostRun = std::clamp((blocks.max().x() - blocks.min().x() + 1) / 16, 1, 8);
  std::size_t mostSlabLeaves = 0;
  auto addSlabsThrough = [&](int x, StreamedBuild::Times& times) {
    for (; nextSlab <= std::min(x, blocks.max().x()); ++nextSlab) {
      FccSlabWindow::Slab slab = slabs.build(nextSlab, times);
      mostSlabLeaves = std::max(mostSlabLeaves, slab.leaves.size());
      const auto start = Clock::now();
      window.add(nextSlab, std::move(slab));
      times.window += std::chrono::duration<double>(Clock::now() - start).count();
    }
  };
  if (progress) progress->start("building FCC topology and bounds");
  StreamedBuild::Times& times = result.times;
  for (int x = first; x <= last;) {
    auto start = Clock::now();
    window.dropBelow(x - reach);  // first: never more than the run and 2 reach slabs at once
    times.window += lap(start);
    addSlabsThrough(x + reach, times);  // what a run of one slab needs; then as many as fit
    const std::size_t fit = kWindowLeaves / std::max<std::size_t>(mostSlabLeaves, 1);
    const int run = int(std::clamp<std::size_t>(fit > std::size_t(2 * reach) ? fit - 2 * reach : 1, 1, std::size_t(mostRun)));
    const int xEnd = std::min(x + run - 1, last);
    addSlabsThrough(xEnd + reach, times);
    start = Clock::now();
    const double kernelSecondsBefore = kernels.computeSeconds;
    if (rawSamples) {
      const FccGrid::Ptr coefficients = prefilterGrid(window.grid(), &kernels, slabBricks(x - 1, xEnd + 1));
      computeBrickBoundsIn(*coefficients, slabBricks(x, xEnd), kernels, *result.bounds);
    } else {
      computeBrickBoundsIn(window.grid(), slabBricks(x, xEnd), kernels, *result.bounds);
    }
    times.bounds += lap(start);
    times.boundsKernels += kernels.computeSeconds - kernelSecondsBefore;
    x = xEnd + 1;
    if (progress && progress->wasInterrupted(int(100.0 * double(x - first) / double(last - first + 1))))
      throw Error("interrupted");
  }
  if (progress) progress->end();

  // Uniform leaves became tiles one by one; merging those upwards is the rest of the builder's
  // prune, and reads no leaf (the topology's have no values).
  auto start = Clock::now();
  openvdb::tools::pruneTiles(static_cast<FccTree&>(*topology), Vec4f(builder.options().tolerance));
  openvdb::tools::prune(*result.bounds);
  times.prune += lap(start);
  result.samples = summarizeSamples(slabs.stats(), builder.siteBounds(), builder.background());
  if (kept) {
    kept->finish();
    topology->useEncodedLeaves(kept);
  }
  return result;
}

}  // namespace fcc
