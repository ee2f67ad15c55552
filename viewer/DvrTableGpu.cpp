#include "DvrTableGpu.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace fcc::render {

DvrTableGpu::DvrTableGpu(const TransferTable& table) { upload(table); }

void DvrTableGpu::upload(const TransferTable& table) {
  const std::size_t entryBytes = std::size_t(table.size()) * sizeof(glm::vec4);
  const std::vector<glm::vec2> maxLevels = extinctionLevels(table);
  if (!entries_ || entryBytes > entries_->size()) {  // all made before any is replaced
    auto entries = std::make_unique<GlBuffer>(entryBytes);
    auto prefix = std::make_unique<GlBuffer>(std::size_t(table.size() + 1) * sizeof(glm::uvec4));
    auto maxLevelBuffer = std::make_unique<GlBuffer>(maxLevels.size() * sizeof(glm::vec2));
    entries_ = std::move(entries);
    prefix_ = std::move(prefix);
    maxLevels_ = std::move(maxLevelBuffer);
  }
  entries_->write(table.entries().data(), entryBytes);
  const Prefixes sums = prefixes(table);
  prefix_->write(sums.sums.data(), sums.sums.size() * sizeof(glm::uvec4));
  kinkQuantum_ = sums.kinkQuantum;
  colourQuantum_ = sums.colourQuantum;
  maxLevels_->write(maxLevels.data(), maxLevels.size() * sizeof(glm::vec2));
  nonZero_ = nonZeroSpan(table);
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
  // tfZeroOn's (not every program calls it: -1 is ignored).
  glProgramUniform1i(p, glGetUniformLocation(p, "uTfNonZeroFirst"), nonZero_.first);
  glProgramUniform1i(p, glGetUniformLocation(p, "uTfNonZeroEnd"), nonZero_.end);
  glProgramUniform1i(p, glGetUniformLocation(p, "uTfInteriorZeros"), nonZero_.interiorZeros ? 1 : 0);
  // Only the sub-step rule reads these: a shader built with a fixed count (FCC_DVR_FIXED_STEPS, a
  // measurement knob) has them inactive, and GL ignores location -1.
  glProgramUniform1f(p, glGetUniformLocation(p, "uTfKinkQuantum"), kinkQuantum_);
  glProgramUniform1f(p, glGetUniformLocation(p, "uTfColourQuantum"), colourQuantum_);
}

void DvrTableGpu::bind() const {
  entries_->bindBase(GL_SHADER_STORAGE_BUFFER, 12);
  prefix_->bindBase(GL_SHADER_STORAGE_BUFFER, 13);
  maxLevels_->bindBase(GL_SHADER_STORAGE_BUFFER, 14);
}

DvrTableGpu::NonZeroSpan DvrTableGpu::nonZeroSpan(const TransferTable& table) {
  const std::vector<int>& count = table.nonZeroPrefix();  // among entries [0, i)
  const int size = table.size(), total = count[std::size_t(size)];
  NonZeroSpan span{size, 0, false};
  if (total == 0) return span;
  span.first = 0;
  while (count[std::size_t(span.first) + 1] == count[std::size_t(span.first)]) ++span.first;
  span.end = size;
  while (count[std::size_t(span.end) - 1] == count[std::size_t(span.end)]) --span.end;
  span.interiorZeros = span.end - span.first != total;
  return span;
}

std::vector<glm::vec2> DvrTableGpu::extinctionLevels(const TransferTable& table) {
  // The table's own sparse tables (doubles of the float entries: exact as floats), one row a level.
  const std::size_t size = std::size_t(table.size());
  const std::vector<std::vector<double>>& maxima = table.extinctionMaxLevels();
  const std::vector<std::vector<double>>& negatedMinima = table.negatedExtinctionMaxLevels();
  std::vector<glm::vec2> flat(maxima.size() * size, glm::vec2(0.0f));
  for (std::size_t k = 0; k < maxima.size(); ++k)
    for (std::size_t i = 0; i < maxima[k].size(); ++i) flat[k * size + i] = glm::vec2(float(maxima[k][i]), float(-negatedMinima[k][i]));
  return flat;
}

namespace {

// Whole quanta of 2^-30 of the terms' sum, each rounded up (their sum stays below 2^31); the quantum.
float quantize(const std::vector<double>& terms, std::vector<uint32_t>& quanta) {
  double total = 0.0;
  for (double t : terms) total += t;
  const double quantum = total > 0.0 ? total / double(1u << 30) : 1.0;
  quanta.resize(terms.size());
  for (std::size_t i = 0; i < terms.size(); ++i) quanta[i] = uint32_t(std::ceil(terms[i] / quantum));
  // The float the shader multiplies by, rounded up (a sum times it is then not below the terms' but
  // for the float rounding of the product).
  return std::nextafter(float(quantum), std::numeric_limits<float>::infinity());
}

}  // namespace

DvrTableGpu::Prefixes DvrTableGpu::prefixes(const TransferTable& table) {
  Prefixes p;
  std::vector<uint32_t> kinks, colours;
  p.kinkQuantum = quantize(table.kinks(), kinks);
  p.colourQuantum = quantize(table.colourSteps(), colours);
  const std::vector<int>& nonZero = table.nonZeroPrefix();
  p.sums.assign(nonZero.size(), glm::uvec4(0u));
  for (std::size_t i = 0; i < nonZero.size(); ++i) {
    p.sums[i].x = uint32_t(nonZero[i]);
    if (i > 0) {
      p.sums[i].y = p.sums[i - 1].y + kinks[i - 1];
      p.sums[i].z = p.sums[i - 1].z + colours[i - 1];
    }
  }
  // The next entry's kink sum beside each, so that dvrSteps reads both kink sums it needs from the two
  // entries its colour sum reads (the last entry's: its own, never read).
  for (std::size_t i = 0; i < p.sums.size(); ++i) p.sums[i].w = p.sums[i + 1 < p.sums.size() ? i + 1 : i].y;
  return p;
}

}  // namespace fcc::render
