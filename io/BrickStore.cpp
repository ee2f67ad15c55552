#include "BrickStore.h"

#include <openvdb/tools/Morphology.h>

#include <cmath>
#include <limits>

#include "VdbFile.h"
#include "WorldFromIndex.h"
#include "VdbLeafReader.h"
#include "sparse/Error.h"

namespace fcc::io {
namespace {

using LeafT = FccTree::LeafNodeType;
static_assert(LeafT::DIM == kBrickPackedDim, "a brick is one leaf of the FCC tree");

openvdb::Coord leafOrigin(const glm::ivec3& brick) {
  return openvdb::Coord(brick.x * kBrickPackedDim, brick.y * kBrickPackedDim, brick.z * kBrickPackedDim);
}

// Bounds for a file written before bounds grids existed: every brick within one brick of a leaf or an
// active tile may vary, over the whole float range (nothing is skipped, nothing is read).
BoundsGrid::Ptr conservativeBounds(const FccGrid& grid) {
  const float bg = grid.background()[0];
  auto bounds = BoundsGrid::create(openvdb::Vec2f(bg, bg));
  const float inf = std::numeric_limits<float>::max();
  auto acc = bounds->getAccessor();
  for (auto it = grid.tree().cbeginLeaf(); it; ++it) {
    const openvdb::Coord b = it->origin() >> 3;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) acc.setValueOn(b.offsetBy(dx, dy, dz), openvdb::Vec2f(-inf, inf));
  }
  return bounds;
}

// The FCC grid to open among the file's grids (from their descriptors alone), and its bounds grid's
// name if the file has one (found by name, confirmed by its fcc_bounds_of metadata once read).
VdbGridEntry chooseFccGrid(const std::string& path, const std::string& gridName, std::string& boundsName) {
  const std::vector<VdbGridEntry> grids = VdbLeafReader::listGrids(path);
  std::string names;
  for (const VdbGridEntry& g : grids) names += (names.empty() ? "" : ", ") + g.name + " (" + g.type + ")";
  const VdbGridEntry* chosen = nullptr;
  for (const VdbGridEntry& g : grids) {
    if (!gridName.empty() && g.name != gridName) continue;
    // Without a name: level 0, never a pyramid level (FccPyramid.h), whatever the grids' order.
    if (gridName.empty() && isLodGridName(g.name)) continue;
    if (g.type == kFccTreeTypeName) {
      chosen = &g;
      break;
    }
    if (!gridName.empty())
      throw InputError(path + ": grid '" + gridName + "' is a " + g.type + " grid, not an FCC grid; run `fccvdb convert " +
                       path + " OUT.vdb` first");
  }
  if (!chosen && !gridName.empty()) throw InputError(path + ": no grid named '" + gridName + "'; grids: " + names);
  if (!chosen)
    throw InputError(path + ": holds no FCC grid (grids: " + (names.empty() ? "none" : names) + "); run `fccvdb convert " +
                     path + " OUT.vdb` first");
  boundsName.clear();
  for (const VdbGridEntry& g : grids)
    if (g.name == boundsGridName(chosen->name) && g.type == openvdb::Vec2STree::treeType()) boundsName = g.name;
  return *chosen;
}

// The bounds grid, read whole by OpenVDB (it is 1/512 of the data); null if it is not the grid's.
BoundsGrid::Ptr readBounds(const std::string& path, const std::string& boundsName, const std::string& fccName) {
  if (boundsName.empty()) return nullptr;
  initializeVdb();
  openvdb::io::File file(path);
  file.setCopyMaxBytes(0);
  file.open(/*delayLoad=*/false);  // nothing mapped
  auto bounds = openvdb::gridPtrCast<BoundsGrid>(file.readGrid(boundsName));
  file.close();
  const auto of = bounds ? bounds->getMetadata<openvdb::StringMetadata>(meta::kBoundsOf) : nullptr;
  return of && of->value() == fccName ? bounds : nullptr;
}

}  // namespace

BrickStore::BrickStore(const std::string& path, const std::string& gridName, bool forRendering) : path_(path) {
  std::string boundsName;
  const VdbGridEntry entry = chooseFccGrid(path, gridName, boundsName);
  const std::vector<std::string> fccTypes{kFccTreeTypeName};
  // OpenVDB parses the FCC grid's topology and the bounds grid: first in the guard's process, which a
  // damaged file may crash. Leaf buffers are ours (VdbLeafReader validates them before decoding).
  guardLeafRead(path, entry.name, fccTypes, boundsName);
  try {
    reader_ = std::make_shared<VdbLeafReader>(path, entry.name, fccTypes);
    bounds_ = readBounds(path, boundsName, entry.name);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path + ": OpenVDB cannot read it: " + e.what());
  }
  grid_ = openvdb::gridPtrCast<FccGrid>(reader_->grid());
  if (!grid_ || !isFccGrid(*grid_))
    throw InputError(path + ": grid '" + entry.name + "' is a Vec4 grid without the FCC metadata (lattice = fcc), not an FCC grid; "
                     "run `fccvdb convert` on its Cartesian source");
  if (forRendering && storesSamples(*grid_))
    throw InputError(path + ": grid '" + grid_->getName() +
                     "' stores raw samples (converted with --no-prefilter); the renderer needs spline "
                     "coefficients: convert again without --no-prefilter");
  background_ = grid_->background()[0];
  worldFromIndex_ = affineWorldFromIndex(grid_->transform(), path);

  boundsFromFile_ = bounds_ != nullptr;
  if (!bounds_) bounds_ = conservativeBounds(*grid_);

  activeBrickBox_ = bounds_->evalActiveVoxelBoundingBox();
  valueMin_ = valueMax_ = background_;
  for (auto it = bounds_->cbeginValueOn(); it; ++it) {
    valueMin_ = std::min(valueMin_, (*it)[0]);
    valueMax_ = std::max(valueMax_, (*it)[1]);
  }
  if (!boundsFromFile_) {  // the recorded sample range is the best guess there is
    const auto lo = grid_->getMetadata<openvdb::FloatMetadata>(meta::kSampleMin);
    const auto hi = grid_->getMetadata<openvdb::FloatMetadata>(meta::kSampleMax);
    valueMin_ = lo ? lo->value() : background_;
    valueMax_ = hi ? hi->value() : background_;
  }
}

void BrickStore::worldBounds(glm::dvec3& lo, glm::dvec3& hi) const {
  // Topology only (value masks), so no leaf buffer is read.
  openvdb::CoordBBox packed = grid_->evalActiveVoxelBoundingBox();
  if (packed.empty()) packed = openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(0));
  const glm::dvec3 indexLo = glm::dvec3(packed.min().x(), packed.min().y(), packed.min().z()) * 2.0;
  const glm::dvec3 indexHi = glm::dvec3(packed.max().x(), packed.max().y(), packed.max().z()) * 2.0 + 1.0;
  worldBoxOfIndexBox(worldFromIndex_, indexLo, indexHi, lo, hi);
}

bool BrickStore::storedAsHalf() const { return reader_->storedAsHalf(); }

bool BrickStore::hasLeaf(const glm::ivec3& brick) const {
  return grid_->tree().probeConstLeaf(leafOrigin(brick)) != nullptr;
}

openvdb::Vec4f BrickStore::constantValue(const glm::ivec3& brick) const {
  // Only called where no leaf exists, so getValue reads a tile or the background and loads nothing.
  return grid_->tree().getValue(leafOrigin(brick));
}

bool BrickStore::readBrick(const glm::ivec3& brick, BrickValues& out) const {
  const std::optional<size_t> leaf = reader_->leafIndexAt(leafOrigin(brick));
  if (!leaf) {
    out.fill(constantValue(brick));
    return false;
  }
  static_assert(sizeof(BrickValues) == LeafT::SIZE * 4 * sizeof(float), "Vec4f packs four floats");
  try {
    reader_->readLeaf(*leaf, reinterpret_cast<float*>(out.data()));
    return true;
  } catch (const InputError& e) {
    damageLog_.record(*leaf, e.what());
    out.fill(grid_->background());
    return false;
  }
}

}  // namespace fcc::io
