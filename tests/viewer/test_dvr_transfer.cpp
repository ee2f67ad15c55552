// fitTransferFunction (viewer/DvrTransfer.h): where a preset is stretched to on a brick source. Empty
// space must start the preset (transparent) when it lies below the data, whether the reconstruction's
// undershoot below it is small or large (an MRI's prefilter undershoots 16 % of the range); a
// background inside the data (a signed field's zero) takes the whole range. A fake source gives each
// case its numbers; a converted file checks that an FCC file's recorded range reaches the fit.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <sstream>

#include "io/BrickStore.h"
#include "sparse/SampleField.h"
#include "tests/viewer/RenderTestSupport.h"
#include "viewer/DvrTransfer.h"
#include "viewer/FccBrickSource.h"

namespace fcc {
namespace {

using test::TempDir;

// Only the range queries matter to the fit; the rest is a source with no bricks.
class RangeOnlySource final : public render::BrickSource {
 public:
  RangeOnlySource(float background, float lo, float hi, std::optional<std::pair<float, float>> samples)
      : background_(background), lo_(lo), hi_(hi), samples_(samples) {}
  const std::string& path() const override { return path_; }
  const ReconstructionInfo& reconstruction() const override { return reconstructionInfos().front(); }
  render::SlotBlock slotBlock() const override { return render::SlotBlock::Sites; }
  const glm::dmat4& worldFromIndex() const override { return worldFromIndex_; }
  void brickBox(glm::ivec3& lo, glm::ivec3& hi) const override { lo = glm::ivec3(1), hi = glm::ivec3(0); }
  void worldBounds(glm::dvec3& lo, glm::dvec3& hi) const override { lo = glm::dvec3(0.0), hi = glm::dvec3(1.0); }
  float background() const override { return background_; }
  float valueMin() const override { return lo_; }
  float valueMax() const override { return hi_; }
  std::optional<std::pair<float, float>> sampleRange() const override { return samples_; }
  void forEachVaryingBrick(const std::function<void(const glm::ivec3&, float, float)>&) const override {}
  std::size_t varyingBrickCount() const override { return 0; }
  void decode(std::vector<render::LoadedBrick>&) const override {}
  io::Damage damage() const override { return {}; }

 private:
  std::string path_ = "range-only";
  glm::dmat4 worldFromIndex_{1.0};
  float background_, lo_, hi_;
  std::optional<std::pair<float, float>> samples_;
};

struct FitCase {
  const char* what;
  float background, lo, hi;
  std::optional<std::pair<float, float>> samples;
  double expectedMin;  // the fitted domain's least value (its greatest is always hi)
};

std::string describe(const FitCase& c) {
  std::ostringstream s;
  s << c.what << ": background " << c.background << ", reconstruction [" << c.lo << ", " << c.hi << "], samples ";
  if (c.samples) s << "[" << c.samples->first << ", " << c.samples->second << "]";
  else s << "not recorded";
  return s.str();
}

TEST(DvrFit, PresetsStartAtEmptySpaceWhenItLiesBelowTheData) {
  const std::vector<FitCase> cases = {
      {"recorded, undershoot 30 % of the range", 0.f, -30.f, 100.f, std::pair(0.f, 100.f), 0.0},
      {"recorded, undershoot 2 %", 0.f, -2.f, 100.f, std::pair(0.f, 100.f), 0.0},
      {"recorded, background below every sample", -5.f, -8.f, 100.f, std::pair(10.f, 100.f), -5.0},
      {"recorded, background inside the samples (a signed field)", 0.f, -50.f, 50.f, std::pair(-50.f, 50.f), -50.0},
      {"recorded, background above the data", 200.f, 0.f, 100.f, std::pair(0.f, 100.f), 0.0},
      {"not recorded, background in the lowest tenth", 0.f, -5.f, 100.f, std::nullopt, 0.0},
      {"not recorded, undershoot beyond a tenth", 0.f, -30.f, 100.f, std::nullopt, -30.0},
      {"not recorded, background at the least value", 0.f, 0.f, 100.f, std::nullopt, 0.0},
  };
  for (const FitCase& c : cases) {
    const RangeOnlySource source(c.background, c.lo, c.hi, c.samples);
    const TransferFunction fitted = render::fitTransferFunction(transferFunctionPreset("inferno"), source);
    EXPECT_DOUBLE_EQ(fitted.domainMin(), c.expectedMin) << describe(c);
    EXPECT_DOUBLE_EQ(fitted.domainMax(), c.hi) << describe(c);
  }
}

TEST(DvrFit, AFilesOwnFunctionIsKeptAsItIs) {
  const TransferFunction own = transferFunctionPreset("viridis").stretchedTo(3.0, 7.0);
  const RangeOnlySource source(0.f, -30.f, 100.f, std::pair(0.f, 100.f));
  const TransferFunction fitted = render::fitTransferFunction(own, source);
  EXPECT_DOUBLE_EQ(fitted.domainMin(), 3.0);
  EXPECT_DOUBLE_EQ(fitted.domainMax(), 7.0);
}

// A bright cube in zeros: the file records its samples as [0, 100], the source reads that record, and
// the preset starts at the background 0 (the fake source above gives the cases with an undershoot).
class BrightCubeField final : public SampleField {
 public:
  float sample(const glm::ivec3& ijk) const override {
    const SiteBox cube{glm::ivec3(12), glm::ivec3(27)};
    return cube.contains(ijk) ? 100.f : 0.f;
  }
  SiteBox bounds() const override { return {glm::ivec3(0), glm::ivec3(39)}; }
  float background() const override { return 0.f; }
};

TEST(DvrFit, AConvertedFilesRecordedSamplesPutThePresetAtItsBackground) {
  TempDir dir;
  const std::string path = dir / "cube.vdb";
  test::writeFccFile(path, BrightCubeField{});
  const io::BrickStore store(path);
  const render::FccBrickSource source(store, std::size_t(16) << 20);
  ASSERT_TRUE(source.sampleRange().has_value()) << "the file's fcc_sample_min/max did not reach the source";
  EXPECT_FLOAT_EQ(source.sampleRange()->first, 0.f);
  EXPECT_FLOAT_EQ(source.sampleRange()->second, 100.f);
  const TransferFunction fitted = render::fitTransferFunction(transferFunctionPreset("grayscale"), source);
  EXPECT_DOUBLE_EQ(fitted.domainMin(), 0.0);
  EXPECT_DOUBLE_EQ(fitted.domainMax(), source.valueMax());
}

}  // namespace
}  // namespace fcc
