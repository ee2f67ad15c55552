// A transfer table (sparse/TransferFunction.h) as shaders/dvr.glsl reads it: its entries and their
// non-zero prefix in SSBOs 12 and 13, its range, size and the largest extinction of each of 16 runs of
// entries as uniforms. Shared by every program that integrates emission and absorption (the
// raycaster's DVR, projected tetrahedra), so they read one table the same way.
#pragma once

#include <memory>

#include "GlProgram.h"
#include "sparse/TransferFunction.h"

namespace fcc::render {

class DvrTableGpu {
 public:
  static constexpr int kBins = 16;  // dvr.glsl's kTfBins

  explicit DvrTableGpu(const TransferTable& table);
  // The table again (a new transfer function); the buffers grow when it has more entries.
  void upload(const TransferTable& table);
  // dvr.glsl's uniforms on `program`, and the transmittance at which a ray stops.
  void setUniforms(const GlProgram& program, float stopTransmittance) const;
  void bind() const;  // the SSBOs at bindings 12 and 13

 private:
  std::unique_ptr<GlBuffer> entries_, prefix_;
  float vmin_ = 0.0f, scale_ = 1.0f;
  int size_ = 0, binEntries_ = 1;
  float binMax_[kBins] = {};
};

}  // namespace fcc::render
