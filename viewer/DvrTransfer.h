// The transfer function as the renderer applies it to a brick source (docs/DVR.md, "Defaults"): a
// preset (defined on [0, 1]) stretched onto the range the reconstruction takes, the default unit
// distance, and the table the GPU reads. Shared by `render` (tools/RenderData.cpp) and the viewer,
// whose panel rebuilds the table when another preset or density scale is chosen.
#pragma once

#include <memory>
#include <string>

#include "BrickSource.h"
#include "sparse/TransferFunction.h"

namespace fcc::render {

// Entries of the GPU's transfer table: dvr.glsl steps about one entry of value change at a time.
constexpr int kTransferTableSize = 256;

// `tf` as applied to `source`: a normalized one (a preset) stretched onto [background, valueMax] when
// the background lies below the data (empty space transparent under every preset's ramp): at or below
// the least of the samples where the source records them (BrickSource::sampleRange), else in the lowest
// tenth of the source's range; otherwise onto [valueMin, valueMax]. A file's function (data values) as
// it is.
TransferFunction fitTransferFunction(const TransferFunction& tf, const BrickSource& source);
// The world length of one index unit: the cube root of worldFromIndex's determinant (--unit-distance's default).
double defaultUnitDistance(const BrickSource& source);
// The table over the function's points (outside them it keeps its end values, as the lookups do).
std::shared_ptr<const TransferTable> transferTable(const TransferFunction& fitted, const OpticalScale& scale);

// A transfer function in use: what --tf named (a preset or a file), the function fitted to the
// source, and the optical scale with its unit distance resolved.
struct DvrTransfer {
  std::string spec;
  TransferFunction function;
  OpticalScale scale;

  std::shared_ptr<const TransferTable> table() const { return transferTable(function, scale); }
};

}  // namespace fcc::render
