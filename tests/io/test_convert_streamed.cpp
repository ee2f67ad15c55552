// The streamed conversion (a .vdb source read leaf by leaf, tiles made without visiting their sites,
// the output built twice and never held) writes the same file as the in-memory reference path, for
// level sets, fog volumes with interior tiles and dense inputs, with --half, --no-prefilter and a
// background override; and it reads each source leaf about twice, never the volume.
#include <gtest/gtest.h>

#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/LevelSetUtil.h>

#include <zlib.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "SameVdbFiles.h"
#include "io/Convert.h"
#include "io/MessageText.h"
#include "sparse/Error.h"
#include "sparse/FccSampler.h"
#include "io/VdbFile.h"
#include "io/VdbLeafReader.h"
#include "io/VdbSourceField.h"
#include "sparse/FccBlockBuilder.h"
#include "sparse/StreamedBuild.h"
#include "tests/tools/RunCommand.h"

namespace fcc::io {
namespace {

using test::TempDir;

struct Variant {
  bool prefilter = true;
  bool half = false;
  std::optional<float> background;
};

std::string describe(const Variant& v) {
  std::string s = v.prefilter ? "coefficients" : "--no-prefilter";
  if (v.half) s += " --half";
  if (v.background) s += " --background " + std::to_string(*v.background);
  return s;
}

void writeGrid(const std::string& path, const openvdb::GridBase::Ptr& grid) {
  initializeVdb();
  openvdb::io::File file(path);
  file.write(openvdb::GridCPtrVec{grid});
  file.close();
}

// A narrow-band level set sphere: interior tiles of -background at every level the radius allows.
std::string writeSphere(const TempDir& dir, const std::string& name, float radius, float voxelSize,
                        bool fog = false) {
  initializeVdb();
  auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
      radius * voxelSize, openvdb::Vec3f(3.3f, -1.7f, 0.6f) * voxelSize, voxelSize, 3.0f);
  if (fog) openvdb::tools::sdfToFogVolume(*grid);  // interior: active tiles of 1
  grid->setName(name);
  const std::string path = dir / (name + ".vdb");
  writeGrid(path, grid);
  return path;
}

const std::vector<Variant> kAllVariants{Variant{}, Variant{true, true, {}}, Variant{false, false, {}}, Variant{true, false, 0.25f}};

void expectStreamedEqualsInMemory(const TempDir& dir, const std::string& input, const ConvertOptions& base,
                                  const std::vector<Variant>& variants = kAllVariants) {
  for (const Variant& v : variants) {
    SCOPED_TRACE(input + " " + describe(v));
    ConvertOptions o = base;
    o.prefilter = v.prefilter;
    o.half = v.half;
    if (v.background) o.background = v.background;
    o.overwrite = true;
    const std::string streamed = dir / "streamed.vdb", inMemory = dir / "memory.vdb";
    const ConvertSummary s = convertToFcc(input, streamed, o);
    o.inMemory = true;
    const ConvertSummary m = convertToFcc(input, inMemory, o);
    EXPECT_EQ(s.activeSamples, m.activeSamples);
    EXPECT_EQ(s.bricks, m.bricks);
    EXPECT_EQ(s.boundsBricks, m.boundsBricks);
    EXPECT_EQ(s.inputVoxels, m.inputVoxels);
    test::expectSameFccFiles(inMemory, streamed);
  }
}

TEST(ConvertStreamed, LevelSetEqualsTheInMemoryPath) {
  TempDir dir;
  // Radius 150 voxels: level-2 tiles (128^3) inside as well as leaf-sized ones.
  expectStreamedEqualsInMemory(dir, writeSphere(dir, "ls", 150.0f, 0.5f), ConvertOptions{});
}

TEST(ConvertStreamed, FogVolumeWithInteriorTilesEqualsTheInMemoryPath) {
  TempDir dir;
  expectStreamedEqualsInMemory(dir, writeSphere(dir, "fog", 70.0f, 1.0f, true), ConvertOptions{});
}

TEST(ConvertStreamed, ResampleEqualsTheInMemoryPath) {
  TempDir dir;
  ConvertOptions resample;
  resample.mode = "resample";
  resample.scale = 1.3;
  expectStreamedEqualsInMemory(dir, writeSphere(dir, "ls", 40.0f, 1.0f), resample);
  expectStreamedEqualsInMemory(dir, writeSphere(dir, "fog", 30.0f, 1.0f, true), resample);
}

// A leaf without an active voxel lies outside the active box the fields' bounds come from, yet blocks
// at the edge of that box read it: the in-memory path prepares everything they reach.
TEST(ConvertStreamed, ResampleReadsLeavesOutsideTheActiveBox) {
  TempDir dir;
  initializeVdb();
  auto grid = openvdb::FloatGrid::create(0.0f);
  for (int i = 64; i <= 71; ++i) grid->tree().setValueOn(openvdb::Coord(i, 66, 67), float(i - 60));
  grid->tree().touchLeaf(openvdb::Coord(16, 64, 64))->setValueOff(openvdb::Coord(17, 65, 66), 5.0f);
  grid->setName("edge");
  const std::string input = dir / "edge.vdb";
  writeGrid(input, grid);
  ConvertOptions resample;
  resample.mode = "resample";
  resample.scale = 1.0;
  expectStreamedEqualsInMemory(dir, input, resample);
}

// Resampling a level set densifies nothing and interpolates it: near the surface, where the source
// holds signed distances, the samples are the distance to the sphere.
TEST(ConvertStreamed, ResampledLevelSetIsTheSignedDistance) {
  TempDir dir;
  constexpr float kRadius = 60.0f;
  const std::string input = writeSphere(dir, "ls", kRadius, 1.0f);
  ConvertOptions o;
  o.mode = "resample";
  o.scale = 0.8;
  o.prefilter = false;
  convertToFcc(input, dir / "out.vdb", o);
  const FccGrid::Ptr grid = readFccGrid(dir / "out.vdb");
  EXPECT_EQ(grid->getGridClass(), openvdb::GRID_LEVEL_SET);
  const FccSampler sampler(*grid, true);
  const glm::dvec3 centre(3.3, -1.7, 0.6);
  int checked = 0;
  double worst = 0.0;
  for (int k = -90; k <= 90; k += 3)
    for (int j = -90; j <= 90; j += 5)
      for (int i = -90; i <= 90; ++i) {
        if ((i + j + k) & 1) continue;
        const openvdb::Vec3d w = grid->transform().indexToWorld(openvdb::Coord(i, j, k));
        const double distance = glm::length(glm::dvec3(w.x(), w.y(), w.z()) - centre) - kRadius;
        if (std::abs(distance) > 1.0) continue;  // well inside the band of half width 3
        worst = std::max(worst, std::abs(double(sampler.stored(glm::ivec3(i, j, k))) - distance));
        ++checked;
      }
  EXPECT_GT(checked, 1000);
  EXPECT_LT(worst, 0.02) << "over " << checked << " sites";
  // The interior is tiles of -background (3 voxels), not leaves.
  EXPECT_EQ(grid->tree().probeConstLeaf(openvdb::Coord(2, -1, 0)), nullptr);
  EXPECT_FLOAT_EQ(grid->tree().getValue(openvdb::Coord(2, -1, 0))[0], -3.0f);
}

TEST(ConvertStreamed, DenseInputEqualsTheInMemoryPath) {
  const std::string data = FCC_SHARED_DATA_DIR;
  if (!std::ifstream(data + "/engine_256x256x128_uint8.raw.gz")) GTEST_SKIP() << "no " << data;
  TempDir dir;
  ConvertOptions o;
  o.raw = RawLayout{{256, 256, 128}, ScalarType::U8, false, glm::dvec3(1.0), 0};
  expectStreamedEqualsInMemory(dir, data + "/engine_256x256x128_uint8.raw.gz", o);
}

// A dense i16 volume: smooth, with a little noise and negative values.
std::vector<int16_t> denseValues(const glm::ivec3& dims) {
  std::vector<int16_t> values;
  values.reserve(size_t(dims.x) * dims.y * dims.z);
  uint32_t noise = 12345;
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) {
        noise = noise * 1664525u + 1013904223u;
        values.push_back(int16_t(900.0 * std::sin(0.31 * i) * std::cos(0.17 * j) + 23.0 * k - 400.0 + double(noise >> 27)));
      }
  return values;
}

std::string bytesOf(const std::vector<int16_t>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(int16_t));
}

void writeBytes(const std::string& path, const std::string& bytes, bool gzip = false) {
  if (!gzip) {
    std::ofstream(path, std::ios::binary) << bytes;
    return;
  }
  gzFile gz = gzopen(path.c_str(), "wb");
  ASSERT_NE(gz, nullptr);
  ASSERT_EQ(gzwrite(gz, bytes.data(), unsigned(bytes.size())), int(bytes.size()));
  gzclose(gz);
}

// A single-file NIfTI-1 header (little endian, int16, vox_offset 352) with a scale.
std::string niftiHeader(const glm::ivec3& dims, float slope, float intercept) {
  std::string h(352, '\0');
  auto put = [&](size_t at, auto value) { std::memcpy(&h[at], &value, sizeof value); };
  put(0, int32_t(348));
  put(40, int16_t(3));
  put(42, int16_t(dims.x));
  put(44, int16_t(dims.y));
  put(46, int16_t(dims.z));
  put(70, int16_t(4));   // int16
  put(72, int16_t(16));  // bits
  put(76, 1.0f);
  put(80, 0.5f);
  put(84, 1.25f);
  put(88, 2.0f);
  put(108, 352.0f);
  put(112, slope);
  put(116, intercept);
  std::memcpy(&h[344], "n+1\0", 4);
  return h;
}

// The volume in every dense format we read ourselves, each input converted streamed and in memory:
// the same file (the slab scratch keeps the stored i16 samples and their NIfTI scale, converted as
// the reader converts them). Dims: three slabs and a part along x, two level-1 nodes along y (pass 2's batches
// then span nodes), an odd z.
TEST(ConvertStreamed, EveryDenseFormatEqualsTheInMemoryPath) {
  TempDir dir;
  const glm::ivec3 dims(37, 290, 21);
  const std::string data = bytesOf(denseValues(dims));
  const std::string nrrd = "NRRD0004\ntype: short\ndimension: 3\nsizes: 37 290 21\nendian: little\n"
                           "spacings: 0.5 1 2\nspace origin: (1,-2,3)\n";
  writeBytes(dir / "v.raw", data);
  writeBytes(dir / "v.raw.gz", data, true);
  writeBytes(dir / "v.nrrd", nrrd + "encoding: raw\n\n" + data);
  writeBytes(dir / "v.nhdr", nrrd + "encoding: gzip\nbyte skip: 6\ndata file: v.data.gz\n\n");
  writeBytes(dir / "v.data.gz", "header" + data, true);
  std::string swapped = data;  // big endian: the slab scratch keeps samples in this machine's order
  for (size_t i = 0; i + 1 < swapped.size(); i += 2) std::swap(swapped[i], swapped[i + 1]);
  std::string bigEndian = nrrd;
  bigEndian.replace(bigEndian.find("endian: little"), 14, "endian: big");
  writeBytes(dir / "be.nrrd", bigEndian + "encoding: raw\n\n" + swapped);
  writeBytes(dir / "v.nii", niftiHeader(dims, 0.5f, -3.0f) + data);
  writeBytes(dir / "v.nii.gz", niftiHeader(dims, 0.0f, 0.0f) + data, true);

  ConvertOptions subsample;
  subsample.raw = RawLayout{dims, ScalarType::I16, false, glm::dvec3(1.0), 0};
  ConvertOptions resample = subsample;
  resample.mode = "resample";
  resample.scale = 1.3;
  // Every variant on raw; the other formats differ only in how their voxels are read.
  expectStreamedEqualsInMemory(dir, dir / "v.raw", subsample);
  expectStreamedEqualsInMemory(dir, dir / "v.raw", resample);
  for (const char* name : {"v.raw.gz", "v.nrrd", "be.nrrd", "v.nhdr", "v.nii", "v.nii.gz"}) {
    expectStreamedEqualsInMemory(dir, dir / name, subsample, {Variant{}});
    expectStreamedEqualsInMemory(dir, dir / name, resample, {Variant{}});
  }
  // Finer than the voxels (more samples than voxels) and by a sample count.
  resample.scale = 0.7;
  expectStreamedEqualsInMemory(dir, dir / "v.nii.gz", resample, {Variant{false, false, {}}});
  resample.scale = 0.0;
  resample.samples = 40000;
  expectStreamedEqualsInMemory(dir, dir / "v.nrrd", resample, {Variant{}});
}

// Volumes thinner than a slab, a B-spline's support or two voxels: the mirrored boundary reads
// voxels the region of the block must hold, and a one-voxel axis has a constant spline.
TEST(ConvertStreamed, ThinDenseVolumesEqualTheInMemoryPath) {
  TempDir dir;
  for (const glm::ivec3 dims : {glm::ivec3(5, 2, 19), glm::ivec3(1, 17, 3), glm::ivec3(18, 1, 1)}) {
    SCOPED_TRACE(commaList(dims));
    writeBytes(dir / "thin.raw", bytesOf(denseValues(dims)));
    ConvertOptions o;
    o.raw = RawLayout{dims, ScalarType::I16, false, glm::dvec3(1.0), 0};
    expectStreamedEqualsInMemory(dir, dir / "thin.raw", o, {Variant{}});
    o.mode = "resample";
    for (const double scale : {0.45, 1.0, 1.7}) {
      o.scale = scale;
      expectStreamedEqualsInMemory(dir, dir / "thin.raw", o, {Variant{}});
    }
  }
}

// A damaged input fails the streamed conversion with the reader's own line, and leaves no output.
TEST(ConvertStreamed, DamagedDenseInputsFailWithTheReadersLine) {
  TempDir dir;
  const glm::ivec3 dims(20, 20, 20);
  const std::string data = bytesOf(denseValues(dims));
  writeBytes(dir / "short.raw.gz", data.substr(0, data.size() - 100), true);
  writeBytes(dir / "long.raw.gz", data + "xx", true);
  std::string gz;
  {
    writeBytes(dir / "whole.raw.gz", data, true);
    std::ifstream in(dir / "whole.raw.gz", std::ios::binary);
    gz.assign(std::istreambuf_iterator<char>(in), {});
  }
  writeBytes(dir / "cut.raw.gz", gz.substr(0, gz.size() / 2));
  ConvertOptions o;
  o.raw = RawLayout{dims, ScalarType::I16, false, glm::dvec3(1.0), 0};
  const std::vector<std::pair<std::string, std::string>> cases{
      {"short.raw.gz", "short.raw.gz: file holds 15900 bytes once decompressed but --dims 20,20,20 --type i16 needs 16000"},
      {"long.raw.gz", "long.raw.gz: file holds 16002 bytes once decompressed"},
      {"cut.raw.gz", "cut.raw.gz: truncated gzip data"},
  };
  for (const auto& [name, message] : cases) {
    SCOPED_TRACE(name);
    for (const bool inMemory : {false, true}) {
      o.inMemory = inMemory;
      try {
        convertToFcc(dir / name, dir / "out.vdb", o);
        ADD_FAILURE() << "no error";
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line";
      }
      EXPECT_FALSE(std::filesystem::exists(dir / "out.vdb"));
    }
  }
}

TEST(ConvertStreamed, RealLevelSetFileEqualsTheInMemoryPath) {
  const std::string data = FCC_SHARED_DATA_DIR;
  if (!std::ifstream(data + "/sphere.vdb")) GTEST_SKIP() << "no " << data;
  TempDir dir;
  expectStreamedEqualsInMemory(dir, data + "/sphere.vdb", ConvertOptions{});
}

// The interior of a level set becomes tiles without a voxel of it visited: source leaves are decoded
// a bounded number of times (pass 1's slab window, pass 2's batches), the output keeps the level-set
// class, and its leaves lie along the surface only.
TEST(ConvertStreamed, LevelSetInteriorStaysTiles) {
  TempDir dir;
  const std::string input = writeSphere(dir, "ls", 150.0f, 1.0f);
  const auto reader = std::make_shared<VdbLeafReader>(input, "", std::vector<std::string>{openvdb::FloatTree::treeType()});
  VdbSourceField field(reader, static_cast<const openvdb::FloatGrid&>(*reader->grid()).background());
  const FccBlockBuilder builder(field, BuildOptions{});
  const StreamedBuild built = buildFccGridStreamed(builder, StreamedBuildOptions{});
  const size_t pass1 = field.leavesDecoded();
  // Every source leaf is decoded in pass 1, once per slab window that needs it (at most 2: a leaf
  // is 8 voxels wide, a slab 16).
  EXPECT_GE(pass1, reader->leafCount());
  EXPECT_LE(pass1, 2 * reader->leafCount());
  // Leaves only where the band is: far fewer than the blocks of the sphere's box.
  const double blocksInBox = std::pow(2.0 * 150.0 / 16.0, 3.0);
  EXPECT_LT(double(built.grid->tree().leafCount()), 0.5 * blocksInBox) << built.grid->tree().leafCount();
  // The centre (packed voxel of site (3, -2, 1)) is inside: a tile of the interior value, the
  // prefilter of -background.
  const openvdb::Coord centre(1, -1, 0);
  EXPECT_LT(built.grid->tree().getValue(centre)[0], 0.0f);
  EXPECT_LT(built.grid->tree().getValueDepth(centre), int(FccTree::DEPTH) - 1) << "the centre is a tile";

  ConvertOptions o;
  convertToFcc(input, dir / "out.vdb", o);
  const FccGrid::Ptr out = readFccGrid(dir / "out.vdb");
  EXPECT_EQ(out->getGridClass(), openvdb::GRID_LEVEL_SET);
}

}  // namespace
}  // namespace fcc::io
