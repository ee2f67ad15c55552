// The BCC lattice stored in a .vdb (docs/FORMAT.md, "BCC datasets"): its two cosets as two ordinary
// Cartesian float grids, one voxel per 2 x 2 x 2 block of BCC index space each. BCC site x (all
// coordinates even: the primary coset, or all odd: the secondary, the cube centres) lives in voxel
// x >> 1 of grid `bcc_primary` or `bcc_secondary`. Each grid's transform maps its voxels to their sites'
// world positions (the secondary's is the primary's moved by half a voxel), so any OpenVDB tool shows
// either coset where it lies. Two float grids rather than one Vec2 grid: every reader of Cartesian
// grids (io::CartesianBrickStore: validated, out of core) reads them as they are.
#pragma once

#include <openvdb/openvdb.h>

#include <functional>

#include "SampleField.h"

namespace fcc {

inline constexpr const char* kBccPrimaryGridName = "bcc_primary";
inline constexpr const char* kBccSecondaryGridName = "bcc_secondary";

struct BccGrids {
  openvdb::FloatGrid::Ptr primary, secondary;
};

// The BCC sites of `box` (BCC index space; points of it that are not sites are never asked for), from
// `value(x)` (called from several threads at once), beyond it the background. `worldFromIndex` maps BCC
// index space to world space (an affine map). Both grids carry the metadata `lattice` = `bcc` and
// `bcc_coset` = `primary` / `secondary`, and the grid class `gridClass`. A part of the box for which
// `mayHoldData` (if given; BCC index space) answers false holds the background and gets no leaf.
BccGrids buildBccGrids(const SiteBox& box, float background, const std::function<float(const glm::ivec3&)>& value,
                       const openvdb::math::Transform& worldFromIndex,
                       openvdb::GridClass gridClass = openvdb::GRID_FOG_VOLUME,
                       const std::function<bool(const SiteBox&)>& mayHoldData = {});

// The coset grid's voxel transform from the BCC index space's: voxel m of coset c (0 primary, 1
// secondary) is BCC site 2m + c (1, 1, 1).
openvdb::math::Transform::Ptr bccCosetTransform(const openvdb::math::Transform& worldFromIndex, int coset);

}  // namespace fcc
