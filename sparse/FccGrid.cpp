#include "FccGrid.h"

#include "BrickBounds.h"

#include <mutex>

namespace fcc {

void initializeVdb() {
  static std::once_flag once;
  std::call_once(once, [] {
    openvdb::initialize();
    if (!FccGrid::isRegistered()) FccGrid::registerGrid();
    if (!BoundsGrid::isRegistered()) BoundsGrid::registerGrid();  // OpenVDB registers no Vec2 grids
  });
}

bool isFccGrid(const openvdb::GridBase& grid) {
  if (grid.type() != FccGrid::gridType()) return false;
  const auto lattice = grid.getMetadata<openvdb::StringMetadata>(meta::kLattice);
  return lattice && lattice->value() == "fcc";
}

void setFccMetadata(FccGrid& grid, const FccProvenance& p) {
  grid.insertMeta(meta::kLattice, openvdb::StringMetadata("fcc"));
  grid.insertMeta(meta::kValues, openvdb::StringMetadata(p.coefficients ? kValuesCoefficients : kValuesSamples));
  grid.insertMeta(meta::kSourceFile, openvdb::StringMetadata(p.sourceFile));
  grid.insertMeta(meta::kSourceGrid, openvdb::StringMetadata(p.sourceGrid));
  grid.insertMeta(meta::kMode, openvdb::StringMetadata(p.mode));
  grid.insertMeta(meta::kSampleMin, openvdb::FloatMetadata(p.sampleMin));
  grid.insertMeta(meta::kSampleMax, openvdb::FloatMetadata(p.sampleMax));
  grid.setGridClass(p.levelSet ? openvdb::GRID_LEVEL_SET : openvdb::GRID_FOG_VOLUME);
}

bool storesSamples(const openvdb::GridBase& grid) {
  const auto values = grid.getMetadata<openvdb::StringMetadata>(meta::kValues);
  return values && values->value() == kValuesSamples;
}

}  // namespace fcc
