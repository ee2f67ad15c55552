#include "FccPyramid.h"

#include <unistd.h>

#include <filesystem>
#include <memory>

#include "AtomicOutput.h"
#include "BrickStore.h"
#include "CopiedFccTree.h"
#include "FinerSplineField.h"
#include "VdbFile.h"
#include "VdbLeafReader.h"
#include "sparse/BrickBounds.h"
#include "sparse/Error.h"
#include "sparse/SampleHistogram.h"
#include "sparse/StreamedBuild.h"

namespace fcc::io {
namespace {

// Temporary level files beside the output (the same file system, which has room for the output),
// removed whatever happens.
class TemporaryFiles {
 public:
  explicit TemporaryFiles(std::string stem) : stem_(std::move(stem)) {}
  ~TemporaryFiles() {
    std::error_code ignored;
    for (const std::string& p : paths_) std::filesystem::remove(p, ignored);
  }
  const std::string& add(int level) {
    paths_.push_back(stem_ + ".lod" + std::to_string(level) + "." + std::to_string(::getpid()) + ".tmp");
    return paths_.back();
  }

 private:
  std::string stem_;
  std::vector<std::string> paths_;
};

void throwIfDamaged(const BrickStore& store) {
  const BrickStore::Damage damage = store.damage();
  if (damage.count > 0) throw InputError(damage.first + " (the pyramid needs every brick; nothing was written)");
}

// The grids `input` may hold: level 0 (`base`), its bounds, its levels and theirs. Anything else would
// be lost by the rewrite, so it is refused.
void checkOnlyPyramidGrids(const std::string& input, const std::string& base) {
  std::string others;
  for (const VdbGridEntry& g : VdbLeafReader::listGrids(input)) {
    std::string name = g.name;
    if (name.size() > 7 && name.compare(name.size() - 7, 7, ".bounds") == 0) name.resize(name.size() - 7);
    const bool ours = name == base || (isLodGridName(name) && name.compare(0, base.size() + 4, base + ".lod") == 0);
    if (!ours) others += (others.empty() ? "" : ", ") + g.name;
  }
  if (!others.empty())
    throw InputError(input + ": holds grids other than FCC grid '" + base + "', its bounds and its levels (" + others +
                     "); `pyramid` rewrites the file with those only, so it refuses to drop the others");
}

// Level `level` (from `finer`, level - 1) into `path` with its bounds; returns its summary.
PyramidLevel buildLevel(const BrickStore& finer, const FccGrid& level0, int level, const std::string& path,
                        const PyramidOptions& options, openvdb::util::NullInterrupter* progress) {
  const FinerSplineField field(finer);
  BuildOptions build;  // coefficients, nothing dropped: tolerance 0
  const FccBlockBuilder builder(field, build);
  StreamedBuildOptions streamed;
  streamed.half = finer.storedAsHalf();
  streamed.kernels = options.kernels;
  const StreamedBuild built = buildFccGridStreamed(builder, streamed, progress);
  throwIfDamaged(finer);

  FccGrid& grid = *built.grid;
  grid.setName(lodGridName(level0.getName(), level));
  openvdb::math::Transform::Ptr xform = finer.index().transform().copy();
  xform->preScale(2.0);  // level k's index J is level k-1's 2J
  grid.setTransform(xform);
  FccProvenance p;
  p.coefficients = true;
  if (const auto file = level0.getMetadata<openvdb::StringMetadata>(meta::kSourceFile)) p.sourceFile = file->value();
  p.sourceGrid = level0.getName();
  p.mode = "pyramid";
  p.sampleMin = built.samples.min;
  p.sampleMax = built.samples.max;
  p.levelSet = level0.getGridClass() == openvdb::GRID_LEVEL_SET;
  setFccMetadata(grid, p);
  recordSampleHistogram(grid, built.samples);
  grid.insertMeta(meta::kLodLevel, openvdb::Int32Metadata(level));
  grid.insertMeta(meta::kLodOf, openvdb::StringMetadata(level0.getName()));
  grid.insertMeta(meta::kLodSpacing, openvdb::DoubleMetadata(double(uint64_t(1) << level)));
  const BoundsGrid::Ptr bounds = boundsGridOf(built.bounds, grid);
  // The tree rebuilds its leaves while written, reading `finer` again through `field`.
  writeVdbAtomically(path, openvdb::GridCPtrVec{built.grid, bounds}, /*overwrite=*/true);
  throwIfDamaged(finer);

  PyramidLevel summary;
  summary.level = level;
  summary.spacing = double(uint64_t(1) << level);
  summary.grid = grid.getName();
  summary.bricks = grid.tree().leafCount();
  summary.boundsBricks = bounds->activeVoxelCount();
  summary.brickBox = dataBrickBoxVolume(grid.tree());
  return summary;
}

uint64_t fileBytes(const std::string& path) {
  std::error_code ec;
  const auto n = std::filesystem::file_size(path, ec);
  return ec ? 0 : uint64_t(n);
}

}  // namespace

uint64_t dataBrickBoxVolume(const FccTree& tree) {
  openvdb::CoordBBox data;
  for (auto it = tree.cbeginLeaf(); it; ++it) data.expand(it->getNodeBoundingBox());
  auto tiles = tree.cbeginValueAll();
  tiles.setMaxDepth(FccTree::ValueAllCIter::LEAF_DEPTH - 1);
  for (; tiles; ++tiles) {
    if (*tiles == tree.background()) continue;
    openvdb::CoordBBox box;
    tiles.getBoundingBox(box);
    data.expand(box);
  }
  if (data.empty()) return 0;
  const openvdb::Coord lo = data.min() >> 3, hi = data.max() >> 3;
  return uint64_t(hi.x() - lo.x() + 1) * uint64_t(hi.y() - lo.y() + 1) * uint64_t(hi.z() - lo.z() + 1);
}

PyramidSummary addPyramid(const std::string& input, const PyramidOptions& options,
                          openvdb::util::NullInterrupter* progress) {
  initializeVdb();
  std::error_code notThere;  // an output that does not exist yet is not the input
  const bool inPlace = options.output.empty() || std::filesystem::equivalent(input, options.output, notThere);
  const std::string output = inPlace ? input : options.output;
  if (!inPlace) checkOutputPath(output, options.overwrite);  // before any work

  const BrickStore level0(input, {}, /*forRendering=*/false);  // guarded; level 0, never a level
  const FccGrid& base = level0.index();
  if (storesSamples(base))
    throw InputError(input + ": grid '" + base.getName() +
                     "' stores raw samples (converted with --no-prefilter); the pyramid is built from spline "
                     "coefficients: convert again without --no-prefilter");
  checkOnlyPyramidGrids(input, base.getName());

  PyramidSummary summary;
  summary.inputBytes = fileBytes(input);
  PyramidLevel first;
  first.grid = base.getName();
  first.bricks = base.tree().leafCount();
  first.boundsBricks = level0.boundsFromFile() ? level0.bounds().activeVoxelCount() : 0;
  first.brickBox = dataBrickBoxVolume(base.tree());
  summary.levels.push_back(first);

  TemporaryFiles temporary(output);
  std::vector<std::unique_ptr<BrickStore>> levels;  // 1, 2, ...: each read from its temporary file
  while (summary.levels.back().brickBox > kMaxCoarsestBricks && int(summary.levels.size()) < kMaxPyramidLevels) {
    const int k = int(summary.levels.size());
    const BrickStore& finer = levels.empty() ? level0 : *levels.back();
    const std::string& path = temporary.add(k);
    summary.levels.push_back(buildLevel(finer, base, k, path, options, progress));
    levels.push_back(std::make_unique<BrickStore>(path, summary.levels.back().grid, /*forRendering=*/false));
  }

  // Level 0 and its bounds as they are (the level count added), then each level and its bounds.
  openvdb::GridCPtrVec grids;
  const FccGrid::Ptr copy0 = copiedFccGrid(level0, progress);
  copy0->insertMeta(meta::kLodLevels, openvdb::Int32Metadata(int(summary.levels.size())));
  grids.push_back(copy0);
  if (level0.boundsFromFile()) grids.push_back(level0.boundsGrid());
  for (const auto& level : levels) {
    grids.push_back(copiedFccGrid(*level, progress));
    grids.push_back(level->boundsGrid());
  }
  try {
    writeVdbAtomically(output, grids, inPlace || options.overwrite, inPlace ? std::string() : input);
  } catch (const OutputError&) {
    throwIfDamaged(level0);  // a damaged brick first met while copying: the input's fault
    throw;
  }
  summary.outputBytes = fileBytes(output);
  return summary;
}

}  // namespace fcc::io
