#include "DvrTableGpu.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace fcc::render {

DvrTableGpu::DvrTableGpu(const TransferTable& table) { upload(table); }

void DvrTableGpu::upload(const TransferTable& table) {
  const std::size_t entryBytes = std::size_t(table.size()) * sizeof(glm::vec4);
  if (!entries_ || entryBytes > entries_->size()) {  // both made before either is replaced
    auto entries = std::make_unique<GlBuffer>(entryBytes);
    auto prefix = std::make_unique<GlBuffer>(std::size_t(table.size() + 1) * sizeof(int32_t));
    entries_ = std::move(entries);
    prefix_ = std::move(prefix);
  }
  entries_->write(table.entries().data(), entryBytes);
  const std::vector<int>& prefix = table.nonZeroPrefix();
  const std::vector<int32_t> prefix32(prefix.begin(), prefix.end());
  prefix_->write(prefix32.data(), prefix32.size() * sizeof(int32_t));
  // dvr.glsl's bins: the largest extinction of each run of entries, ends shared.
  size_ = table.size();
  binEntries_ = std::max(1, (size_ - 1 + kBins - 1) / kBins);
  std::fill(std::begin(binMax_), std::end(binMax_), 0.0f);
  for (int k = 0; k < kBins; ++k)
    for (int i = k * binEntries_; i <= std::min((k + 1) * binEntries_, size_ - 1); ++i)
      binMax_[k] = std::max(binMax_[k], table.entries()[std::size_t(i)].a);
  vmin_ = float(table.vmin());
  scale_ = float((size_ - 1) / (table.vmax() - table.vmin()));
}

void DvrTableGpu::setUniforms(const GlProgram& program, float stopTransmittance) const {
  const GLuint p = program.id();
  glProgramUniform1f(p, program.uniformLocation("uTfMin"), vmin_);
  glProgramUniform1f(p, program.uniformLocation("uTfScale"), scale_);
  glProgramUniform1i(p, program.uniformLocation("uTfSize"), size_);
  glProgramUniform1fv(p, program.uniformLocation("uTfBinMax"), kBins, binMax_);
  glProgramUniform1i(p, program.uniformLocation("uTfBinEntries"), binEntries_);
  glProgramUniform1f(p, program.uniformLocation("uStopTransmittance"), stopTransmittance);
}

void DvrTableGpu::bind() const {
  entries_->bindBase(GL_SHADER_STORAGE_BUFFER, 12);
  prefix_->bindBase(GL_SHADER_STORAGE_BUFFER, 13);
}

}  // namespace fcc::render
