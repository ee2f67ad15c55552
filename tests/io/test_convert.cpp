// Conversion to FCC grids: exactness of subsampling, the prefilter, half storage, world positions, the
// real input files, and the bad inputs that must leave nothing behind.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <openvdb/math/Half.h>

#include <cmath>
#include <fstream>
#include <random>

#include "io/Convert.h"
#include "io/PatientMetadata.h"
#include "io/VdbFile.h"
#include "sparse/Error.h"
#include "sparse/FccSampler.h"
#include "tests/tools/RunCommand.h"

namespace fcc::io {
namespace {

using test::TempDir;
using ::testing::HasSubstr;

// A random f32 volume written as a raw file.
struct RawFixture {
  DenseVolume volume;
  RawLayout layout;
  std::string path;
  RawFixture(const TempDir& dir, glm::ivec3 dims, glm::dvec3 spacing = glm::dvec3(1.0), uint32_t seed = 1) {
    volume.dims = dims;
    volume.spacing = spacing;
    volume.values.resize(size_t(dims.x) * dims.y * dims.z);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> d(-1.0f, 1.0f);
    for (float& v : volume.values) v = d(rng);
    layout.dims = dims;
    layout.type = ScalarType::F32;
    layout.spacing = spacing;
    path = dir / "volume.raw";
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(volume.values.data()),
                                                std::streamsize(volume.values.size() * sizeof(float)));
  }
};

ConvertOptions rawOptions(const RawLayout& layout) {
  ConvertOptions o;
  o.raw = layout;
  return o;
}

float storedAt(const FccSampler& s, int i, int j, int k) { return s.stored(glm::ivec3(i, j, k)); }

TEST(Convert, SubsampleKeepsEvenParityVoxelsBitForBit) {
  TempDir dir;
  RawFixture raw(dir, {13, 10, 7});
  ConvertOptions o = rawOptions(raw.layout);
  o.prefilter = false;
  convertToFcc(raw.path, dir / "out.vdb", o);
  const FccGrid::Ptr grid = readFccGrid(dir / "out.vdb");
  const FccSampler sampler(*grid, true);
  const DenseVolume& v = raw.volume;
  size_t kept = 0;
  for (int k = 0; k < v.dims.z; ++k)
    for (int j = 0; j < v.dims.y; ++j)
      for (int i = 0; i < v.dims.x; ++i) {
        if ((i + j + k) & 1) continue;
        ++kept;
        ASSERT_EQ(storedAt(sampler, i, j, k), v.at(i, j, k)) << "site " << i << "," << j << "," << k;
      }
  EXPECT_EQ(kept, (v.values.size() + 1) / 2);
  EXPECT_TRUE(storesSamples(*grid));
  // Outside the data: the background (0).
  EXPECT_EQ(storedAt(sampler, -2, 0, 0), 0.0f);
  EXPECT_EQ(storedAt(sampler, 14, 0, 0), 0.0f);
}

TEST(Convert, StoresPrefilteredCoefficientsByDefault) {
  TempDir dir;
  RawFixture raw(dir, {9, 9, 9});
  convertToFcc(raw.path, dir / "out.vdb", rawOptions(raw.layout));
  const FccGrid::Ptr grid = readFccGrid(dir / "out.vdb");
  EXPECT_FALSE(storesSamples(*grid));
  const FccSampler sampler(*grid, false);
  auto sample = [&](const glm::ivec3& s) {
    return raw.volume.contains(s.x, s.y, s.z) ? raw.volume.at(s.x, s.y, s.z) : 0.0f;
  };
  // Every site whose coefficient can differ from the background: the data and one neighbour step out.
  for (int k = -1; k <= 9; ++k)
    for (int j = -1; j <= 9; ++j)
      for (int i = -1; i <= 9; ++i) {
        const glm::ivec3 site(i, j, k);
        if (!spline::isFccSite(site)) continue;
        ASSERT_NEAR(sampler.stored(site), spline::prefilterAt(site, sample), 1e-6f) << i << "," << j << "," << k;
      }
}

TEST(Convert, HalfStorageRoundTrips) {
  TempDir dir;
  RawFixture raw(dir, {8, 8, 8});
  ConvertOptions o = rawOptions(raw.layout);
  o.prefilter = false;
  o.half = true;
  convertToFcc(raw.path, dir / "half.vdb", o);
  o.half = false;
  convertToFcc(raw.path, dir / "full.vdb", o);
  const FccGrid::Ptr grid = readFccGrid(dir / "half.vdb");
  const FccSampler sampler(*grid, true);
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = (j + k) & 1; i < 8; i += 2) {
        const float expected = float(openvdb::math::half(raw.volume.at(i, j, k)));
        ASSERT_EQ(storedAt(sampler, i, j, k), expected) << i << "," << j << "," << k;
      }
  // Half storage is what makes the file smaller.
  EXPECT_LT(std::filesystem::file_size(dir / "half.vdb"), std::filesystem::file_size(dir / "full.vdb"));
}

TEST(Convert, KeepsWorldPositions) {
  TempDir dir;
  RawFixture raw(dir, {10, 12, 8}, glm::dvec3(0.5, 2.0, 1.25));
  convertToFcc(raw.path, dir / "out.vdb", rawOptions(raw.layout));
  const FccGrid::Ptr grid = readFccGrid(dir / "out.vdb");
  const FccSampler sampler(*grid, false);
  for (const glm::ivec3 site : {glm::ivec3(2, 4, 2), glm::ivec3(5, 3, 4), glm::ivec3(7, 7, 6)}) {
    const openvdb::Vec3d pWorld = grid->transform().indexToWorld(openvdb::Coord(site.x, site.y, site.z));
    EXPECT_NEAR(pWorld.x(), 0.5 * site.x, 1e-12);
    EXPECT_NEAR(pWorld.y(), 2.0 * site.y, 1e-12);
    EXPECT_NEAR(pWorld.z(), 1.25 * site.z, 1e-12);
    const auto atWorld = sampler.evaluateWorld(pWorld);
    const auto atIndex = sampler.evaluateIndex(glm::vec3(site));
    EXPECT_NEAR(atWorld.value, atIndex.value, 1e-6f);
    // d/dworld = d/dindex / spacing.
    EXPECT_NEAR(atWorld.gradient.y, atIndex.gradient.y / 2.0f, 1e-5f);
  }
}

TEST(Convert, ResampleGivesAboutTheRequestedSampleCount) {
  TempDir dir;
  RawFixture raw(dir, {33, 33, 33});
  ConvertOptions o = rawOptions(raw.layout);
  o.mode = "resample";
  o.samples = 4000;
  o.prefilter = false;
  convertToFcc(raw.path, dir / "out.vdb", o);
  const FccGrid::Ptr grid = readFccGrid(dir / "out.vdb");
  // Lattice points over the extent (32 source voxels) at the chosen spacing; half are FCC sites.
  const double h = grid->voxelSize().x();
  const double perAxis = std::floor(32.0 / h) + 1.0;
  const double sites = perAxis * perAxis * perAxis / 2.0;
  EXPECT_NEAR(sites / 4000.0, 1.0, 0.1) << "spacing " << h;
  // Every site of that lattice was sampled (the random data is nowhere the background); packed voxels
  // on the boundary also count their sites just outside.
  const double stored = double(grid->activeVoxelCount() * 4);
  EXPECT_GE(stored, sites);
  EXPECT_LE(stored, 1.5 * sites);
  EXPECT_EQ(grid->metaValue<std::string>(meta::kMode), "resample");
}

TEST(Convert, ResampleReproducesALinearRamp) {
  TempDir dir;
  RawFixture raw(dir, {20, 20, 20});
  for (int k = 0; k < 20; ++k)
    for (int j = 0; j < 20; ++j)
      for (int i = 0; i < 20; ++i) raw.volume.values[raw.volume.index(i, j, k)] = float(i + 2 * j - k);
  std::ofstream(raw.path, std::ios::binary).write(reinterpret_cast<const char*>(raw.volume.values.data()),
                                                  std::streamsize(raw.volume.values.size() * sizeof(float)));
  ConvertOptions o = rawOptions(raw.layout);
  o.mode = "resample";
  o.scale = 0.75;
  o.prefilter = false;
  convertToFcc(raw.path, dir / "out.vdb", o);
  const FccGrid::Ptr grid = readFccGrid(dir / "out.vdb");
  const FccSampler sampler(*grid, true);
  // Away from the mirrored boundary the interpolating B-spline reproduces linear data.
  for (const glm::ivec3 site : {glm::ivec3(10, 10, 10), glm::ivec3(12, 9, 11), glm::ivec3(8, 13, 9)}) {
    const openvdb::Vec3d w = grid->transform().indexToWorld(openvdb::Coord(site.x, site.y, site.z));
    EXPECT_NEAR(sampler.stored(site), float(w.x() + 2 * w.y() - w.z()), 1e-3f) << "site " << site.x;
  }
}

TEST(Convert, RealFiles) {
  const std::string data = FCC_SHARED_DATA_DIR;
  if (!std::ifstream(data + "/engine_256x256x128_uint8.raw.gz")) GTEST_SKIP() << "no " << data;
  TempDir dir;
  ConvertOptions engine;
  engine.raw = RawLayout{{256, 256, 128}, ScalarType::U8, false, glm::dvec3(1.0), 0};
  auto s = convertToFcc(data + "/engine_256x256x128_uint8.raw.gz", dir / "engine.vdb", engine);
  EXPECT_EQ(s.inputVoxels, 256u * 256u * 128u);
  EXPECT_GT(s.bricks, 100u);
  // 83% of engine's voxels are air below 16, but not 0: the grid is sparse only where values are 0.
  ConvertOptions den;
  den.raw = RawLayout{{128, 128, 84}, ScalarType::U8, false, glm::dvec3(1.0), 62};
  den.prefilter = false;
  convertToFcc(data + "/brainsmall.den", dir / "brain.vdb", den);
  const DenseVolume brain = readRaw(data + "/brainsmall.den", *den.raw);
  const FccGrid::Ptr brainGrid = readFccGrid(dir / "brain.vdb");
  const FccSampler brainSampler(*brainGrid, true);
  EXPECT_EQ(storedAt(brainSampler, 64, 64, 40), brain.at(64, 64, 40));

  s = convertToFcc(data + "/ch2better.nii.gz", dir / "colin.vdb", ConvertOptions{});
  EXPECT_EQ(s.inputVoxels, 301u * 370u * 316u);
  const FccGrid::Ptr colin = readFccGrid(dir / "colin.vdb");
  EXPECT_NEAR(colin->voxelSize().x(), 0.5, 1e-9);
  // A NIfTI's patient axes ride along for the default camera; the raw files and the level set have none.
  const std::optional<PatientAxes> colinAxes = patientAxesOf(*colin, "colin.vdb");
  ASSERT_TRUE(colinAxes.has_value());
  EXPECT_EQ(colinAxes->superior, glm::dvec3(0, 0, 1));
  EXPECT_EQ(colinAxes->anterior, glm::dvec3(0, 1, 0));
  EXPECT_FALSE(patientAxesOf(*readFccGrid(dir / "engine.vdb"), "engine.vdb").has_value());
  EXPECT_FALSE(patientAxesOf(*brainGrid, "brain.vdb").has_value());

  // The OpenVDB level set keeps its name, class and the values at its even-parity voxels.
  ConvertOptions ls;
  ls.prefilter = false;
  s = convertToFcc(data + "/sphere.vdb", dir / "sphere_fcc.vdb", ls);
  EXPECT_EQ(s.gridName, "ls_sphere");
  const FccGrid::Ptr sphere = readFccGrid(dir / "sphere_fcc.vdb", "ls_sphere");
  EXPECT_EQ(sphere->getGridClass(), openvdb::GRID_LEVEL_SET);
  EXPECT_FALSE(patientAxesOf(*sphere, "sphere_fcc.vdb").has_value());
  const openvdb::FloatGrid::Ptr source = readFloatGrid(data + "/sphere.vdb");
  const FccSampler sphereSampler(*sphere, true);
  int compared = 0;
  for (auto it = source->cbeginValueOn(); it && compared < 5000; ++it) {
    const openvdb::Coord c = it.getCoord();
    if ((c.x() + c.y() + c.z()) & 1) continue;
    ASSERT_EQ(sphereSampler.stored(glm::ivec3(c.x(), c.y(), c.z())), *it);
    ++compared;
  }
  EXPECT_EQ(compared, 5000);
}

// An NRRD in LPS space: streamed and in memory, subsampled and resampled, the file records the patient's
// axes in its world frame; damaged axes are one line naming the file.
TEST(Convert, RecordsThePatientAxesOfAnAnatomicalSpace) {
  TempDir dir;
  const std::string nrrd = dir / "lps.nrrd";
  {
    std::ofstream out(nrrd, std::ios::binary);
    out << "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 9 9 9\nencoding: raw\nspace: left-posterior-superior\n"
           "space directions: (-1,0,0) (0,1,0) (0,0,2)\nspace origin: (4,0,0)\n\n";
    for (int i = 0; i < 9 * 9 * 9; ++i) out.put(char(i % 7 == 0 ? 100 : 0));
  }
  for (const bool inMemory : {false, true})
    for (const char* mode : {"subsample", "resample"}) {
      ConvertOptions o;
      o.inMemory = inMemory;
      o.mode = mode;
      o.scale = 1.5;
      const std::string out = dir / (std::string(mode) + (inMemory ? "_mem.vdb" : ".vdb"));
      convertToFcc(nrrd, out, o);
      const std::optional<PatientAxes> axes = patientAxesOf(*readFccGrid(out), out);
      ASSERT_TRUE(axes.has_value()) << out;
      EXPECT_EQ(axes->superior, glm::dvec3(0, 0, 1)) << out;
      EXPECT_EQ(axes->anterior, glm::dvec3(0, -1, 0)) << out << ": LPS's anterior is -y (the x flip leaves y)";
    }

  FccGrid grid;
  recordPatientAxes(grid, PatientAxes{{0, 0, 2}, {0, -3, 0}});
  const std::optional<PatientAxes> scaled = patientAxesOf(grid, "g.vdb");
  ASSERT_TRUE(scaled.has_value());
  EXPECT_EQ(scaled->superior, glm::dvec3(0, 0, 1)) << "normalised when read";
  EXPECT_EQ(scaled->anterior, glm::dvec3(0, -1, 0));
  recordPatientAxes(grid, PatientAxes{{0, 0, 1}, {0, 0, -1}});
  try {
    patientAxesOf(grid, "g.vdb");
    ADD_FAILURE() << "parallel axes were accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("g.vdb: metadata fcc_patient_superior (0,0,1) and fcc_patient_anterior (0,0,-1)"));
  }
  grid.removeMeta(meta::kPatientAnterior);
  EXPECT_THROW(patientAxesOf(grid, "g.vdb"), InputError);
}

TEST(Convert, BadInputsLeaveNothingBehind) {
  TempDir dir;
  RawFixture raw(dir, {8, 8, 8});
  const std::string out = dir / "out.vdb";
  ConvertOptions o = rawOptions(raw.layout);
  o.raw->dims = {8, 8, 9};  // the file is shorter than these dims
  EXPECT_THROW(convertToFcc(raw.path, out, o), InputError);
  o.raw->dims = {8, 8, 8};
  o.mode = "sideways";
  EXPECT_THROW(convertToFcc(raw.path, out, o), ValueError);
  o.mode = "resample";
  EXPECT_THROW(convertToFcc(raw.path, out, o), ValueError);  // neither --samples nor --scale
  o.mode = "subsample";
  EXPECT_THROW(convertToFcc(raw.path, raw.path, o), OutputError);  // output == input
  EXPECT_EQ(dir.fileCount(), 1) << "only the input remains";
  convertToFcc(raw.path, out, o);
  try {
    convertToFcc(raw.path, out, o);
    ADD_FAILURE() << "overwrote without --force";
  } catch (const OutputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("--force"));
  }
  o.overwrite = true;
  convertToFcc(raw.path, out, o);
  EXPECT_EQ(dir.fileCount(), 2) << "input and output, no temporary file";
  // A .vdb with no float grid.
  try {
    convertToFcc(out, dir / "again.vdb", ConvertOptions{});
    ADD_FAILURE() << "converted an FCC grid as if it were Cartesian";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("out.vdb"));
  }
  EXPECT_EQ(dir.fileCount(), 2);
}

}  // namespace
}  // namespace fcc::io
