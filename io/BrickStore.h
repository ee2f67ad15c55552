// An FCC grid opened out of core: its topology (which bricks exist, tile values, the transform) and
// bounds grid in memory, each brick's values read from the file on demand by our own reader
// (VdbLeafReader: pread, validated, nothing mapped) into the caller's memory.
#pragma once

#include <glm/glm.hpp>
#include <openvdb/openvdb.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "Damage.h"
#include "sparse/BrickBounds.h"
#include "sparse/FccGrid.h"

namespace fcc::io {

class VdbLeafReader;

// The 8^3 packed voxels of one brick in OpenVDB's leaf order: z fastest, index (x * 8 + y) * 8 + z.
using BrickValues = std::array<openvdb::Vec4f, kBrickPackedDim * kBrickPackedDim * kBrickPackedDim>;

class BrickStore {
 public:
  // Opens `gridName` (empty: the first FCC grid) of `path`, after a guarded read of its topology
  // (io/VdbFile.h). Its bounds grid is read fully (it is 1/512 of the data); a file
  // without one gets conservative bounds (every brick near data, the whole value range).
  // Throws InputError for a file without an FCC grid (saying to run convert), one that stores raw
  // samples, or a transform that is not affine.
  // `forRendering` false (fccvdb info): a grid of raw samples opens too.
  BrickStore(const std::string& path, const std::string& gridName = {}, bool forRendering = true);

  const std::string& path() const { return path_; }
  const FccGrid& index() const { return *grid_; }  // leaf buffers stay out of core: do not read values
  const BoundsGrid& bounds() const { return *bounds_; }
  BoundsGrid::ConstPtr boundsGrid() const { return bounds_; }  // the same, shared (for writing it again)
  bool boundsFromFile() const { return boundsFromFile_; }
  bool storedAsHalf() const;  // the file stores the grid's values as half floats
  float background() const { return background_; }
  // worldFromIndex of the lattice's index space (an affine map), column-vector convention.
  const glm::dmat4& worldFromIndex() const { return worldFromIndex_; }
  // Bricks of the bounds grid whose spline may vary, as an inclusive box of brick coordinates.
  const openvdb::CoordBBox& activeBrickBox() const { return activeBrickBox_; }
  // World-space bounding box of the active data (for framing a camera).
  void worldBounds(glm::dvec3& lo, glm::dvec3& hi) const;
  float valueMin() const { return valueMin_; }  // range of the spline (the bounds' hull)
  float valueMax() const { return valueMax_; }

  // The brick's packed voxels: the leaf's values if it has one (decoded from the file), else the
  // tile value or the background everywhere. Thread-safe. Returns true if it was a leaf. A leaf whose
  // bytes are damaged is never trusted: it reads as the background (a hole in the surface), returns
  // false, and is recorded once (damage()).
  bool readBrick(const glm::ivec3& brick, BrickValues& out) const;

  // The damaged bricks met so far (io/Damage.h; unit "brick"), and the first one's message ("FILE: leaf
  // at (x, y, z) is damaged: WHAT"). Thread-safe.
  using Damage = io::Damage;
  Damage damage() const { return damageLog_.damage(); }
  // True if brick has a leaf in the file (its values need decoding).
  bool hasLeaf(const glm::ivec3& brick) const;
  // The constant value of a brick without a leaf.
  openvdb::Vec4f constantValue(const glm::ivec3& brick) const;

 private:
  std::string path_;
  std::shared_ptr<const VdbLeafReader> reader_;
  FccGrid::Ptr grid_;
  BoundsGrid::Ptr bounds_;
  bool boundsFromFile_ = false;
  float background_ = 0.0f;
  glm::dmat4 worldFromIndex_{1.0};
  openvdb::CoordBBox activeBrickBox_;
  float valueMin_ = 0.0f, valueMax_ = 0.0f;
  mutable DamageLog damageLog_{"brick"};  // by leaf index
};

}  // namespace fcc::io
