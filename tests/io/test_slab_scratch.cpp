// The slab scratch file (io/SlabScratch.h): the source is read once, front to back, every voxel once;
// any box read back is the volume's; the file is never visible in the temp dir; the resampling
// field's spline from the slabs is CubicBSplineVolume's, bit for bit.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <random>

#include "io/DenseSlabField.h"
#include "io/DenseSource.h"
#include "io/SlabScratch.h"
#include "sparse/CubicBSpline.h"
#include "sparse/Error.h"
#include "tests/tools/RunCommand.h"

namespace fcc::io {
namespace {

using test::TempDir;

// A volume in memory as a source that records what it was asked for.
class RecordingSource final : public DenseSource {
 public:
  explicit RecordingSource(const glm::ivec3& dims) {
    geometry_.dims = dims;
    std::mt19937 random(5);
    std::uniform_real_distribution<float> value(-100.0f, 100.0f);
    values.resize(voxelCount());
    for (float& v : values) v = value(random);
  }
  void read(uint64_t first, uint64_t count, float* out) override {
    runs.emplace_back(first, count);
    std::copy_n(values.begin() + ptrdiff_t(first), count, out);
  }
  void finish() override { ++finished; }
  float at(const glm::ivec3& v) const {
    return values[(size_t(v.z) * geometry_.dims.y + size_t(v.y)) * geometry_.dims.x + size_t(v.x)];
  }

  std::vector<float> values;
  std::vector<std::pair<uint64_t, uint64_t>> runs;
  int finished = 0;
};

// Sets TMPDIR for the scope.
struct TempDirVariable {
  explicit TempDirVariable(const std::string& dir) { ::setenv("TMPDIR", dir.c_str(), 1); }
  ~TempDirVariable() { ::unsetenv("TMPDIR"); }
};

TEST(SlabScratch, ReadsTheSourceOnceInOrderAndGivesBackAnyBox) {
  TempDir dir;
  const TempDirVariable tmp(dir / "tmp");
  std::filesystem::create_directories(dir / "tmp");
  // 700 x 1000 floats a slice: a group of 5 slices (16 MiB), so 13 slices take three reads.
  RecordingSource source(glm::ivec3(700, 1000, 13));
  const SlabScratch scratch(source);
  uint64_t next = 0;
  for (const auto& [first, count] : source.runs) {
    EXPECT_EQ(first, next) << "front to back, each voxel once";
    next = first + count;
  }
  EXPECT_EQ(next, source.voxelCount());
  EXPECT_GT(source.runs.size(), 1u);
  EXPECT_EQ(source.finished, 1);
  EXPECT_TRUE(std::filesystem::is_empty(dir / "tmp")) << "the scratch file is unlinked at once";
  // The file holds 18 of every 16 columns (the halo), as float.
  EXPECT_EQ(scratch.bytes(), uint64_t(700 + 2 * 43) * 1000 * 13 * sizeof(float));

  std::mt19937 random(9);
  const glm::ivec3 dims = scratch.dims();
  for (int trial = 0; trial < 200; ++trial) {
    SiteBox box;
    for (int a = 0; a < 3; ++a) {
      std::uniform_int_distribution<int> at(0, dims[a] - 1);
      const int p = at(random), q = at(random);
      box.min[a] = std::min(p, q);
      box.max[a] = std::min(std::max(p, q), box.min[a] + (a == 0 ? 60 : 9));
    }
    if (trial == 0) box = {glm::ivec3(0), dims - 1};  // all of it
    if (trial == 1) box = {glm::ivec3(15, 0, 0), glm::ivec3(32, 3, 2)};  // a block's box: one slab
    const glm::ivec3 d = box.dim();
    std::vector<float> got(size_t(d.x) * d.y * d.z);
    scratch.read(box, got.data());
    size_t n = 0;
    for (int z = box.min.z; z <= box.max.z; ++z)
      for (int y = box.min.y; y <= box.max.y; ++y)
        for (int x = box.min.x; x <= box.max.x; ++x, ++n)
          ASSERT_EQ(got[n], source.at({x, y, z})) << "voxel " << x << "," << y << "," << z << " of trial " << trial;
  }
}

// Stored u16 samples with a scale, as a NIfTI file's: converted only when read back.
class StoredSource final : public DenseSource {
 public:
  explicit StoredSource(const glm::ivec3& dims) {
    geometry_.dims = dims;
    for (uint64_t i = 0; i < voxelCount(); ++i) samples.push_back(uint16_t(i * 7919 % 65521));
  }
  std::optional<Stored> stored() const override { return Stored{ScalarType::U16, std::make_pair(0.37f, -11.0f)}; }
  void readStored(uint64_t first, uint64_t count, void* out) override {
    ++storedReads;
    std::copy_n(samples.begin() + ptrdiff_t(first), count, static_cast<uint16_t*>(out));
  }
  void read(uint64_t first, uint64_t count, float* out) override {
    for (uint64_t i = 0; i < count; ++i) out[i] = float(samples[first + i]) * 0.37f + -11.0f;
  }
  std::vector<uint16_t> samples;
  int storedReads = 0;
};

TEST(SlabScratch, KeepsStoredSamplesAsStoredAndConvertsThemAsTheSourceDoes) {
  StoredSource source(glm::ivec3(50, 21, 9));
  const SlabScratch scratch(source);
  EXPECT_GT(source.storedReads, 0);
  EXPECT_EQ(scratch.bytes(), uint64_t(50 + 2 * 3) * 21 * 9 * sizeof(uint16_t)) << "2 bytes a voxel, not float's 4";
  const SiteBox all{glm::ivec3(0), scratch.dims() - 1};
  std::vector<float> got(source.voxelCount()), expected(source.voxelCount());
  scratch.read(all, got.data());
  source.read(0, source.voxelCount(), expected.data());
  EXPECT_EQ(got, expected);
}

TEST(SlabScratch, AnUnusableTempDirIsOneLine) {
  TempDir dir;
  const TempDirVariable tmp(dir / "missing");
  RecordingSource source(glm::ivec3(4, 4, 4));
  try {
    SlabScratch scratch(source);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("TMPDIR"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// Progress runs from the slices read; an interruption stops the reading with fcc::Error.
TEST(SlabScratch, ReportsProgressAndStopsWhenInterrupted) {
  struct Stopper : openvdb::util::NullInterrupter {
    std::vector<int> percents;
    int stopAt = 101;
    bool wasInterrupted(int percent) override {
      percents.push_back(percent);
      return percent >= stopAt;
    }
  };
  RecordingSource source(glm::ivec3(700, 1000, 13));
  Stopper all;
  SlabScratch scratch(source, {}, &all);
  EXPECT_EQ(all.percents, (std::vector<int>{38, 76, 100}));  // groups of 5 slices
  RecordingSource again(glm::ivec3(700, 1000, 13));
  Stopper stop;
  stop.stopAt = 50;
  EXPECT_THROW(SlabScratch(again, {}, &stop), Error);
  EXPECT_EQ(again.finished, 0) << "stopped before the end";
}

// The coefficients, filtered along x and y per group of slices and along z per slab, evaluate to
// CubicBSplineVolume's values bit for bit, at sites across slab borders and the mirrored faces.
TEST(SlabScratch, ResampleFieldIsTheInMemorySpline) {
  RecordingSource source(glm::ivec3(41, 23, 12));
  const CubicBSplineVolume spline(source.geometry().dims, source.values);
  constexpr double kSpacing = 0.85;
  const DenseSlabResampleField field(slabsOfCoefficients(source), 0.0f, kSpacing);
  const SiteBox sites = field.bounds();
  ASSERT_EQ(sites.max, glm::ivec3(47, 25, 12));
  field.prepare({sites.expandedBy(1)});
  int checked = 0;
  for (int z = sites.min.z; z <= sites.max.z; ++z)
    for (int y = sites.min.y; y <= sites.max.y; ++y)
      for (int x = sites.min.x; x <= sites.max.x; ++x) {
        const glm::ivec3 ijk(x, y, z);
        ASSERT_EQ(field.sample(ijk), spline.evaluate(glm::dvec3(ijk) * kSpacing)) << x << "," << y << "," << z;
        ++checked;
      }
  EXPECT_EQ(checked, 48 * 26 * 13);
  EXPECT_EQ(field.sample(glm::ivec3(-1, 0, 0)), 0.0f) << "the background outside the lattice";
}

}  // namespace
}  // namespace fcc::io
