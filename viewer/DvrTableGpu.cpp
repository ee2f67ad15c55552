#include "DvrTableGpu.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace fcc::render {

DvrTableGpu::DvrTableGpu(const TransferTable& table) { upload(table); }

void DvrTableGpu::upload(const TransferTable& table) {
  const std::size_t entryBytes = std::size_t(table.size()) * sizeof(glm::vec4);
  const std::vector<float> maxLevels = extinctionMaxLevels(table);
  if (!entries_ || entryBytes > entries_->size()) {  // all made before any is replaced
    auto entries = std::make_unique<GlBuffer>(entryBytes);
    auto prefix = std::make_unique<GlBuffer>(std::size_t(table.size() + 1) * sizeof(int32_t));
    auto maxLevelBuffer = std::make_unique<GlBuffer>(maxLevels.size() * sizeof(float));
    entries_ = std::move(entries);
    prefix_ = std::move(prefix);
    maxLevels_ = std::move(maxLevelBuffer);
  }
  entries_->write(table.entries().data(), entryBytes);
  const std::vector<int>& prefix = table.nonZeroPrefix();
  const std::vector<int32_t> prefix32(prefix.begin(), prefix.end());
  prefix_->write(prefix32.data(), prefix32.size() * sizeof(int32_t));
  maxLevels_->write(maxLevels.data(), maxLevels.size() * sizeof(float));
  size_ = table.size();
  vmin_ = float(table.vmin());
  scale_ = float((size_ - 1) / (table.vmax() - table.vmin()));
}

void DvrTableGpu::setUniforms(const GlProgram& program, float stopTransmittance) const {
  const GLuint p = program.id();
  glProgramUniform1f(p, program.uniformLocation("uTfMin"), vmin_);
  glProgramUniform1f(p, program.uniformLocation("uTfScale"), scale_);
  glProgramUniform1i(p, program.uniformLocation("uTfSize"), size_);
  glProgramUniform1f(p, program.uniformLocation("uStopTransmittance"), stopTransmittance);
}

void DvrTableGpu::bind() const {
  entries_->bindBase(GL_SHADER_STORAGE_BUFFER, 12);
  prefix_->bindBase(GL_SHADER_STORAGE_BUFFER, 13);
  maxLevels_->bindBase(GL_SHADER_STORAGE_BUFFER, 14);
}

std::vector<float> DvrTableGpu::extinctionMaxLevels(const TransferTable& table) {
  // The table's own sparse table (doubles of the float entries: exact as floats), one row a level.
  const std::size_t size = std::size_t(table.size());
  const std::vector<std::vector<double>>& levels = table.extinctionMaxLevels();
  std::vector<float> flat(levels.size() * size, 0.0f);
  for (std::size_t k = 0; k < levels.size(); ++k)
    std::copy(levels[k].begin(), levels[k].end(), flat.begin() + std::ptrdiff_t(k * size));
  return flat;
}

}  // namespace fcc::render
