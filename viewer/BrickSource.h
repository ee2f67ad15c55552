// What the brick-paged raycaster renders, whatever the lattice: the reconstruction layer's storage
// side (docs/RECONSTRUCTION.md). Every lattice is cut into bricks of 16^3 index units, so the page
// table, residency, requests and node skipping are the same for all; a source says which bricks may
// vary and over which values, fills a pool slot's block for a brick, and names the reconstruction the
// shader evaluates (FCC_RECON_* of sparse/ReconDispatch.h). Two sources exist: an FCC .vdb through the
// host cache (FccBrickSource.h) and a Cartesian float grid read directly (CartesianBrickSource.h).
#pragma once

#include <glm/glm.hpp>

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/Damage.h"
#include "sparse/Reconstruction.h"

namespace fcc::render {

// What one pool slot is filled from (viewer/BrickPool.h spreads or copies it into the slot's layout).
enum class SlotBlock {
  FccPacked,  // io::kHaloBlockVoxels packed FCC voxels [8b - 1, 8b + 9)^3, four floats each, x fastest
  Sites,      // the 20^3 lattice points [16b - 2, 16b + 18)^3, one float each, x fastest (scalar layouts only)
  // BCC (viewer/BccBrickSource.h): the two cosets' voxels m in [8b - 2, 8b + 10)^3 (sites 2m and 2m + 1,
  // every stencil of the brick's cells and of their bounds, which reach 3 index units), the primary's
  // 12^3 then the secondary's, x fastest; held in a scalar slot of 20^3 floats (the rest unused).
  BccPacked,
};
inline constexpr int kBccSlotDim = 12;  // coset voxels per side of a BCC slot block
inline constexpr int kBccSlotLo = 2;    // the block starts this many coset voxels before the brick's 8b
inline std::size_t slotBlockFloats(SlotBlock block) {
  return block == SlotBlock::FccPacked ? std::size_t(10 * 10 * 10 * 4) : std::size_t(20 * 20 * 20);
}

struct LoadedBrick {
  glm::ivec3 brick;
  std::vector<float> halo;  // slotBlockFloats(source.slotBlock()) floats: one pool slot
  int level = 0;            // the pyramid level the brick is of (BrickLoader's sources[level] decodes it)
};

// A brick of one level of a level-of-detail pyramid (level 0: the data itself).
struct LevelBrick {
  glm::ivec3 brick{0};
  int level = 0;
  bool operator==(const LevelBrick& o) const { return brick == o.brick && level == o.level; }
};

// Memory a source keeps decoded on the host (the viewer's panel shows it).
struct HostCacheUse {
  std::size_t bytesUsed = 0, budgetBytes = 0;
};

class BrickSource {
 public:
  virtual ~BrickSource() = default;

  virtual const std::string& path() const = 0;
  virtual const ReconstructionInfo& reconstruction() const = 0;
  virtual SlotBlock slotBlock() const = 0;
  // worldFromIndex of the lattice's index space (an affine map), column-vector convention.
  virtual const glm::dmat4& worldFromIndex() const = 0;
  // The bricks that may vary, as an inclusive box of brick coordinates (lo > hi: none).
  virtual void brickBox(glm::ivec3& lo, glm::ivec3& hi) const = 0;
  // World-space bounding box of the data (for framing a camera).
  virtual void worldBounds(glm::dvec3& lo, glm::dvec3& hi) const = 0;
  // The value of empty space (bricks not listed by forEachVaryingBrick hold it or another constant).
  virtual float background() const = 0;
  // The range the reconstruction can take (the hull of the bricks' ranges).
  virtual float valueMin() const = 0;
  virtual float valueMax() const = 0;
  // The range of the data's own samples before any prefilter, where the file records it (FCC files
  // that convert or synth wrote): valueMin may lie below it (the prefilter's undershoot), which is
  // not data. nullopt elsewhere.
  virtual std::optional<std::pair<float, float>> sampleRange() const { return std::nullopt; }
  // Each brick whose reconstruction may vary, with a conservative range of its values on the brick's
  // cells; bricks not visited hold one value and are skipped by rays.
  virtual void forEachVaryingBrick(const std::function<void(const glm::ivec3&, float lo, float hi)>& visit) const = 0;
  virtual std::size_t varyingBrickCount() const = 0;
  // Fills each brick's block (LoadedBrick::halo, resized here). The bricks of one call are mostly
  // neighbours. Called on several loader threads at once. A damaged leaf is no failure: it reads as the
  // background (a hole) and is recorded in damage(); anything else throws (io::InputError: one line).
  virtual void decode(std::vector<LoadedBrick>& chunk) const = 0;
  virtual HostCacheUse hostCacheUse() const { return {}; }
  // The damage met so far, reading ranges or decoding (io/Damage.h): what `render` and the panel report.
  virtual io::Damage damage() const = 0;
};

}  // namespace fcc::render
