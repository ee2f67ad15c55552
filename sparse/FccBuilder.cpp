#include "FccBuilder.h"

#include <openvdb/tools/Prune.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <vector>

#include "Error.h"
#include "Lattice.h"
#include "Spline.h"

namespace fcc {
namespace {

using LeafT = FccTree::LeafNodeType;
constexpr int kLeafDim = LeafT::DIM;  // packed voxels per leaf side

// Samples of one block's sites with a one-site halo, so the prefilter reads no field twice.
struct BlockSamples {
  glm::ivec3 origin;  // site of element (0,0,0)
  int side;
  std::vector<float> values;
  float at(const glm::ivec3& ijk) const {
    const glm::ivec3 l = ijk - origin;
    return values[size_t((l.z * side + l.y) * side + l.x)];
  }
};

struct Range {
  float min = std::numeric_limits<float>::infinity();
  float max = -std::numeric_limits<float>::infinity();
};

}  // namespace

BuildResult buildFccGrid(const SampleField& field, const BuildOptions& options,
                         openvdb::util::NullInterrupter* interrupter) {
  const float background = field.background();
  const SiteBox bounds = field.bounds();
  auto grid = FccGrid::create(openvdb::Vec4f(background));
  BuildResult result;
  result.grid = grid;
  if (bounds.empty()) return result;

  // Coefficients differ from the background up to one neighbour step outside the data.
  const int halo = options.prefilter ? 1 : 0;
  const glm::ivec3 packedMin = (bounds.min - halo) >> 1, packedMax = (bounds.max + halo) >> 1;
  const glm::ivec3 blockMin = packedMin >> 3, blockMax = packedMax >> 3;  // leaf blocks, 8 packed voxels each
  static_assert(kLeafDim == 8, "block arithmetic assumes 8^3 leaves");
  const glm::ivec3 blockCount = blockMax - blockMin + 1;
  const size_t totalBlocks = size_t(blockCount.x) * blockCount.y * blockCount.z;

  tbb::enumerable_thread_specific<std::vector<LeafT*>> leavesPerThread;
  tbb::enumerable_thread_specific<Range> rangePerThread;
  std::atomic<size_t> blocksDone{0};
  std::atomic<bool> interrupted{false};
  if (interrupter) interrupter->start("building FCC grid");

  tbb::parallel_for(tbb::blocked_range<size_t>(0, totalBlocks, 16), [&](const tbb::blocked_range<size_t>& r) {
    BlockSamples samples;
    samples.side = 2 * kLeafDim + 2 * halo;
    samples.values.resize(size_t(samples.side) * samples.side * samples.side);
    auto& leaves = leavesPerThread.local();
    auto& range = rangePerThread.local();
    for (size_t b = r.begin(); b != r.end(); ++b) {
      if (interrupted.load(std::memory_order_relaxed)) return;
      const glm::ivec3 block = blockMin + glm::ivec3(int(b % blockCount.x), int((b / blockCount.x) % blockCount.y),
                                                      int(b / (size_t(blockCount.x) * blockCount.y)));
      const glm::ivec3 leafOrigin = block * kLeafDim;  // packed voxel
      SiteBox siteBox{2 * leafOrigin - halo, 2 * leafOrigin + 2 * kLeafDim - 1 + halo};
      if (!field.mayHoldData(siteBox)) continue;

      samples.origin = siteBox.min;
      for (int z = 0; z < samples.side; ++z)
        for (int y = 0; y < samples.side; ++y)
          for (int x = 0; x < samples.side; ++x) {
            const glm::ivec3 ijk = samples.origin + glm::ivec3(x, y, z);
            samples.values[size_t((z * samples.side + y) * samples.side + x)] =
                spline::isFccSite(ijk) ? field.sample(ijk) : background;
          }

      auto leaf = std::make_unique<LeafT>(openvdb::Coord(leafOrigin.x, leafOrigin.y, leafOrigin.z),
                                          openvdb::Vec4f(background), false);
      bool anyActive = false;
      for (openvdb::Index n = 0; n < LeafT::SIZE; ++n) {
        const openvdb::Coord xyz = leaf->offsetToGlobalCoord(n);
        const glm::ivec3 packed(xyz.x(), xyz.y(), xyz.z());
        openvdb::Vec4f value;
        bool active = false;
        for (int c = 0; c < 4; ++c) {
          const glm::ivec3 site = siteOfChannel(packed, c);
          const float v = samples.at(site);
          if (glm::all(glm::greaterThanEqual(site, bounds.min)) && glm::all(glm::lessThanEqual(site, bounds.max))) {
            range.min = std::min(range.min, v);
            range.max = std::max(range.max, v);
          }
          value[c] = options.prefilter ? spline::prefilterAt(site, [&](const glm::ivec3& s) { return samples.at(s); })
                                       : v;
          active = active || !(std::abs(value[c] - background) <= options.tolerance);
        }
        if (active) {
          leaf->setValueOn(n, value);
          anyActive = true;
        }
      }
      if (anyActive) leaves.push_back(leaf.release());
      const size_t done = ++blocksDone;
      if (interrupter && (done & 63) == 0 &&
          interrupter->wasInterrupted(int(100.0 * double(done) / double(totalBlocks))))
        interrupted = true;
    }
  });

  auto& tree = grid->tree();
  for (auto& leaves : leavesPerThread)
    for (LeafT* leaf : leaves) tree.addLeaf(leaf);  // the tree takes ownership
  if (interrupted) throw Error("interrupted");
  // Uniform leaves become tiles: the tile tree is also the coarse level of the bounds hierarchy.
  openvdb::tools::prune(tree, openvdb::Vec4f(options.tolerance));
  if (interrupter) interrupter->end();

  Range total;
  for (const Range& r : rangePerThread) {
    total.min = std::min(total.min, r.min);
    total.max = std::max(total.max, r.max);
  }
  if (total.min <= total.max) {
    result.sampleMin = total.min;
    result.sampleMax = total.max;
  } else {
    result.sampleMin = result.sampleMax = background;
  }
  return result;
}

}  // namespace fcc
