// One block of the FCC grid built from a sample field: the VDB leaf of 8^3 packed voxels (16^3 sites)
// at a block coordinate, with the prefilter applied and inactive voxels at the background. The
// in-memory builder (FccBuilder.h) and the streamed one (StreamedBuild.h) both build every leaf here,
// so a block built twice, or by either of them, is bit-identical.
#pragma once

#include <algorithm>
#include <limits>
#include <memory>
#include <vector>

#include "FccGrid.h"
#include "SampleField.h"
#include "SampleStats.h"

namespace fcc {

struct BuildOptions {
  bool prefilter = true;   // store coefficients c = q_fcc * V (what the renderer needs) or raw samples V
  float tolerance = 0.0f;  // a packed voxel whose four values are within this of the background is inactive
};

class FccBlockBuilder {
 public:
  using Leaf = FccTree::LeafNodeType;

  // Working memory of one thread: the block's samples with the prefilter's one-site halo, so the
  // prefilter reads no sample twice.
  struct Scratch {
    glm::ivec3 origin{0};  // site of element (0,0,0)
    int side = 0;
    std::vector<float> values;
    float at(const glm::ivec3& ijk) const {
      const glm::ivec3 l = ijk - origin;
      return values[size_t((l.z * side + l.y) * side + l.x)];
    }
  };

  // Keeps a reference to `field`, which must outlive the builder.
  FccBlockBuilder(const SampleField& field, const BuildOptions& options);

  // The blocks (leaf origins / 8, in packed voxels) that can hold active voxels: the field's bounds
  // and, for coefficients, the one-site halo the prefilter spreads them by. Empty for an empty field.
  const openvdb::CoordBBox& blocks() const { return blocks_; }
  float background() const { return field_.background(); }
  // The field's bounds: the sites whose samples build() and uniform() report (summarizeSamples).
  const SiteBox& siteBounds() const { return bounds_; }
  const BuildOptions& options() const { return options_; }

  // The leaf of `block`, or null when none of its voxels is active. Samples at the block's own sites
  // inside the field's bounds are added to `stats` (if not null). Thread-safe: one Scratch per thread.
  std::unique_ptr<Leaf> build(const openvdb::Coord& block, Scratch& scratch, SampleStats* stats) const;

  // What build() and the prune make of a block whose samples (halo included) are all one value,
  // found without visiting them (SampleField::uniformOver): nothing (`none`: no leaf, the
  // background) or a tile; `known` is false when the field cannot tell, and build() must run.
  struct Uniform {
    bool known = false;
    bool none = false;
    openvdb::Vec4f value;  // the tile, all voxels active
  };
  // Adds the value to `stats` once for each of the block's own sites that build() would have added.
  Uniform uniform(const openvdb::Coord& block, SampleStats* stats) const;

  // The blocks of x-slab `x` (block coordinates) that may hold active voxels, sorted: where the
  // field has data (SampleField::forEachDataBox), else every block of blocks() in the slab.
  // Thread-safe: the streamed build finds several slabs' blocks at once.
  std::vector<openvdb::Coord> blocksInSlab(int x) const;

  // Makes the field's samples for these blocks (with the prefilter's halo) readable (SampleField::prepare).
  void prepare(const std::vector<openvdb::Coord>& blocks) const;

 private:
  SiteBox sampleBox(const openvdb::Coord& block) const;  // the sites build() reads

  const SampleField& field_;
  BuildOptions options_;
  SiteBox bounds_;
  openvdb::CoordBBox blocks_;
};

}  // namespace fcc
