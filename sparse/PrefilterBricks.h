// The quasi-interpolation prefilter q_fcc (paper 4.2) of whole bricks on the CPU, fast: the brick's
// halo of packed voxels is copied from the 27 leaves (or constant values) around it into four
// channel planes, then each output row of 8 packed voxels is 13 contiguous loads per channel — every
// tap of channel c is one fixed (channel, packed offset) pair — which the compiler vectorises.
//
// Contract: bit for bit spline::prefilterAt at every site (the same 12 neighbour terms summed in
// fcc_neighbour_offset's order from 0, then fcc_prefilter; no fused multiply-add: this file is
// compiled with -ffp-contract=off). tests/sparse/test_prefilter_bricks.cpp checks it against the
// per-site definition.
#pragma once

#include <openvdb/openvdb.h>

#include <functional>
#include <vector>

#include "FccGrid.h"

namespace fcc {

// out[512 i + n] = the prefiltered coefficients of packed voxel n (VDB leaf order, z fastest) of brick
// bricks[i] (the leaf of packed voxels [8b, 8b + 8)^3), from the values `samples` holds there and one
// packed voxel around (leaves, tiles and the background alike). In parallel over the bricks.
void prefilterBricks(const FccGrid& samples, const std::vector<openvdb::Coord>& bricks, openvdb::Vec4f* out);

// The same, handing each brick's 512 results to take(i, values) on the thread that computed them (while
// they are in its cache), instead of into one array. `values` is valid during the call only.
void prefilterBricks(const FccGrid& samples, const std::vector<openvdb::Coord>& bricks,
                     const std::function<void(std::size_t i, const openvdb::Vec4f* values)>& take);

// The coefficient leaf of brick `brick` from its 512 values (leaf order): active where a value differs
// from `background`; a value equal to it is stored as the background itself (as an inactive voxel
// holds it). Null when every value equals the background.
FccTree::LeafNodeType* makeCoefficientLeaf(const openvdb::Coord& brick, const openvdb::Vec4f* values,
                                          const openvdb::Vec4f& background);

}  // namespace fcc
