// A BCC dataset (sparse/BccGrids.h: the two cosets as float grids `bcc_primary` and `bcc_secondary`)
// as the raycaster's brick source, rendered with one of the BCC lattice's reconstructions (paper 002:
// `render --reconstruction barycentric|sheared-trilinear|bilinear-spatial|bilinear`). Bricks are 16^3
// units of BCC index space, as every lattice's are; a slot holds both cosets' voxels [8b - 2, 8b + 10)^3
// (SlotBlock::BccPacked), read out of core through two io::CartesianBrickStore (validated, nothing
// mapped). The bricks' value ranges come from the cosets' own brick ranges: BCC brick b's voxels lie in
// coset brick b >> 1's block, so no leaf is read for them beyond what the stores read.
#pragma once

#include <memory>
#include <vector>

#include "BrickSource.h"
#include "io/CartesianBrickStore.h"

namespace fcc::render {

// True if `path` is a .vdb holding the two BCC coset grids (from its grid descriptors alone, read by our
// own parser: cheap, and safe on a damaged file, which throws InputError).
bool holdsBccGrids(const std::string& path);

class BccBrickSource : public BrickSource {
 public:
  // Opens both cosets of `path`. `reconstruction`: one of the BCC lattice's (ValueError naming them
  // otherwise). InputError (one line) for a file without both cosets, or whose cosets disagree (their
  // transforms not half a voxel apart, their backgrounds different). `cacheRanges`: the cosets' brick
  // ranges kept in the user cache (io::CartesianBrickStore's).
  BccBrickSource(const std::string& path, const ReconstructionInfo& reconstruction, bool cacheRanges = false);
  ~BccBrickSource() override;

  const std::string& path() const override { return path_; }
  const ReconstructionInfo& reconstruction() const override { return reconstruction_; }
  SlotBlock slotBlock() const override { return SlotBlock::BccPacked; }
  const glm::dmat4& worldFromIndex() const override { return worldFromIndex_; }
  void brickBox(glm::ivec3& lo, glm::ivec3& hi) const override;
  void worldBounds(glm::dvec3& lo, glm::dvec3& hi) const override;
  float background() const override { return primary_->background(); }
  float valueMin() const override { return valueMin_; }
  float valueMax() const override { return valueMax_; }
  void forEachVaryingBrick(const std::function<void(const glm::ivec3&, float, float)>& visit) const override;
  std::size_t varyingBrickCount() const override { return ranges_.size(); }
  void decode(std::vector<LoadedBrick>& chunk) const override;
  io::Damage damage() const override;  // both cosets' damaged leaves (holes)
  bool levelSet() const { return primary_->levelSet(); }

 private:
  std::string path_;
  const ReconstructionInfo& reconstruction_;
  std::unique_ptr<io::CartesianBrickStore> primary_, secondary_;
  glm::dmat4 worldFromIndex_{1.0};
  std::vector<io::CartesianBrickStore::BrickRange> ranges_;  // per BCC brick
  float valueMin_ = 0.0f, valueMax_ = 0.0f;
};

}  // namespace fcc::render
