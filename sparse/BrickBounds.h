// Per-brick bounds of the FCC spline: the min/max hierarchy the renderer skips empty space with
// (paper 4.3). Stored in the .vdb beside the FCC grid, so neither opening a file nor changing the
// isovalue needs any preprocessing.
//
// Contract of a bounds grid (docs/FORMAT.md):
//   - a Vec2f grid (tree type Tree_vec2s_5_4_3, registered by fcc::initializeVdb) named
//     boundsGridName(fccGridName);
//   - voxel b = (bx, by, bz) is the brick of packed voxels [8b, 8b + 8)^3, i.e. the box
//     [16b, 16b + 16]^3 of the lattice's index space (a VDB leaf of the FCC grid, present or not);
//   - its value (lo, hi) bounds the spline there: lo <= s(xyz) <= hi for every xyz in that closed box,
//     including the parts that depend on neighbouring bricks' coefficients;
//   - active voxels are the bricks where the spline may vary (lo < hi); a brick where it is the
//     constant c holds (c, c), as an inactive voxel or tile or as the background (c0, c0), where c0
//     is the FCC grid's background;
//   - the transform is the FCC grid's, pre-scaled by kBrickSites, so brick b's world box is the
//     world box of its sites.
#pragma once

#include <openvdb/math/Half.h>
#include <openvdb/openvdb.h>

#include <string>

#include "FccGrid.h"

namespace fcc {

using BoundsGrid = openvdb::Grid<openvdb::Vec2STree>;

inline constexpr int kBrickPackedDim = 8;                       // packed voxels per brick side (a leaf)
inline constexpr int kBrickSites = 2 * kBrickPackedDim;         // lattice index units per brick side

namespace meta {
inline constexpr const char* kBoundsOf = "fcc_bounds_of";       // the FCC grid's name
}  // namespace meta

inline std::string boundsGridName(const std::string& fccGridName) { return fccGridName + ".bounds"; }

class BrickKernels;  // sparse/BrickKernels.h; null below means the C++/TBB reference

// The bounds grid of an FCC grid holding coefficients (sparse/FccGrid.h: not storesSamples). Bricks
// computed exactly: the FCC leaves and their 26 neighbour bricks. Elsewhere the spline is a convex
// combination of tile values (or the background), so a brick whose 27-brick neighbourhood holds no
// leaf gets the hull of those constant values. Sets name, transform, fcc_bounds_of and the
// background (c0, c0).
BoundsGrid::Ptr computeBrickBounds(const FccGrid& coefficients, BrickKernels* kernels = nullptr);

// The part of computeBrickBounds that sets the bricks inside `region` (brick coordinates), written
// into `tree` (background boundsBackground of the FCC background; not pruned); bricks outside are
// left as they are. A brick reads only the leaves and tiles of its 27-brick neighbourhood, so
// `coefficients` may hold just those around the region: the streamed build (StreamedBuild.h) passes
// a window of three slabs of leaves for a region of one slab.
void computeBrickBoundsIn(const FccGrid& coefficients, const openvdb::CoordBBox& region, BrickKernels& kernels,
                          openvdb::Vec2STree& tree);

// The bounds grid's background for an FCC grid's background: the hull of its channels.
openvdb::Vec2f boundsBackground(const openvdb::Vec4f& fccBackground);

// The bounds grid of FCC grid `fcc` around `tree`: its name, transform and fcc_bounds_of.
BoundsGrid::Ptr boundsGridOf(const openvdb::Vec2STree::Ptr& tree, const FccGrid& fcc);

// The quasi-interpolation prefilter q_fcc applied to a grid of raw samples (fcc_values = samples):
// the grid the builder would have written without --no-prefilter. Active where a coefficient differs
// from the background; uniform leaves are pruned to tiles; metadata and transform are copied, with
// fcc_values = coefficients. Only the bricks inside `region` are computed (the rest holds the
// background); a brick reads the samples of its 27-brick neighbourhood.
FccGrid::Ptr prefilterGrid(const FccGrid& samples, BrickKernels* kernels = nullptr,
                           const openvdb::CoordBBox& region = openvdb::CoordBBox::inf());

// The grid's values as a reader of its file will see them: rounded through half floats where the
// grid is saved as half (Grid::saveFloatAsHalf; the background, stored exactly, stays), else the grid
// itself. Bounds must be those of the stored values.
FccGrid::ConstPtr valuesAsStored(const FccGrid::ConstPtr& grid);

// A value as a half-stored file holds it; the background is stored exactly.
inline openvdb::Vec4f asStoredHalf(const openvdb::Vec4f& v, const openvdb::Vec4f& background) {
  return v == background ? v : openvdb::Vec4f(openvdb::math::Vec4<openvdb::math::half>(v));
}

// Sets every value that `it` (a value iterator over a grid or a leaf) visits to asStoredHalf: what
// valuesAsStored does to a whole grid.
template <class ValueIter>
void roundAsStoredHalf(ValueIter it, const openvdb::Vec4f& background) {
  for (; it; ++it) {
    const openvdb::Vec4f v = *it;
    if (v != background) it.setValue(asStoredHalf(v, background));
  }
}

// The coefficients to compute bounds of: the grid itself, or its prefiltered copy when it stores
// samples.
FccGrid::ConstPtr coefficientsOf(const FccGrid::ConstPtr& grid, BrickKernels* kernels = nullptr);

}  // namespace fcc
