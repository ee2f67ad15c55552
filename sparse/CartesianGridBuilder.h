// A Cartesian float grid (openvdb::FloatGrid) from values at the integer points of a box, built in
// memory one leaf at a time in parallel (4 bytes a point, plus the tree's overhead): what `synth
// --lattice cc` writes and what `compare` times the renderer on for its CC rows. Every point of the box
// is active; beyond it lies the background. The transform is left as identity (the caller sets it).
#pragma once

#include <openvdb/openvdb.h>

#include <functional>

#include "SampleField.h"

namespace fcc {

// `value(ijk)` for every point of `box` (called from several threads at once). A leaf's part of the box
// for which `mayHoldData` (if given) answers false holds the background and gets no leaf.
openvdb::FloatGrid::Ptr buildCartesianGrid(const SiteBox& box, float background,
                                           const std::function<float(const glm::ivec3&)>& value,
                                           const std::function<bool(const SiteBox&)>& mayHoldData = {});

}  // namespace fcc
