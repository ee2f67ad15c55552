// `fccvdb convert` of a narrow-band level set streams: its peak memory follows the band (the data),
// not the interior (constant tiles, many times larger as voxels) nor the bounding box; and the surface
// it renders lies on the analytic sphere.
#include <Imath/ImathBox.h>
#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfInputFile.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

#include "MeasuredRun.h"
#include "RunCommand.h"
#include "io/VdbFile.h"
#include "viewer/Camera.h"

namespace fcc::test {
namespace {

TEST(CliMemory, ConvertOfALevelSetFollowsTheBandAndRendersTheSphere) {
  TempDir dir;
  constexpr double kRadius = 400.0;  // voxels; half width 3
  const std::string input = dir / "ls.vdb", output = dir / "ls_fcc.vdb", exr = dir / "ls.exr";
  // Made by another process: a child starts with its parent's peak RSS (exec keeps it), so this
  // process must stay small.
  const CommandResult made = runFccvdb("bench convert --stage make --radius 400 --keep " + input);
  ASSERT_EQ(made.status, 0) << made.err;
  const double interiorMiB = 4.0 / 3.0 * M_PI * std::pow(kRadius, 3.0) * sizeof(float) / double(1 << 20);

  const MeasuredRun run = runMeasured({"convert", input, output, "--cl-device", "reference"}, dir);
  ASSERT_EQ(run.status, 0) << run.err;
  unsigned long long bandVoxels = 0;
  const size_t at = run.err.find(", from ");
  ASSERT_NE(at, std::string::npos) << run.err;
  ASSERT_EQ(std::sscanf(run.err.c_str() + at, ", from %llu input voxels", &bandVoxels), 1) << run.err;
  const double bandMiB = double(bandVoxels) * sizeof(float) / double(1 << 20);
  const double peakMiB = double(run.peakRssKiB) / 1024.0;
  std::printf("convert level-set sphere r=%g: peak RSS %.0f MiB; band %.0f MiB as floats, interior %.0f MiB as voxels\n",
              kRadius, peakMiB, bandMiB, interiorMiB);
  // The in-memory conversion built every interior block and held source and output whole: several
  // times the interior's voxels. Streamed: the process, the topologies and a window of slabs.
  EXPECT_LT(peakMiB, 200.0) << "band " << bandMiB << " MiB, interior " << interiorMiB << " MiB";
  EXPECT_LT(peakMiB, interiorMiB / 3.0);

  // The surface: every hit pixel's depth puts it on the sphere, within 0.01 voxel.
  render::Camera camera;
  camera.eye = glm::dvec3(300.0, 200.0, 1300.0);
  camera.lookat = glm::dvec3(0.0);
  camera.fovYDegrees = 40.0;
  const int width = 48, height = 40;
  const CommandResult r = runFccvdb("render " + output + " -o " + exr + " --res 48x40 --eye 300,200,1300 --lookat 0,0,0 " +
                                    "--fov 40 --gpu-cache 64 --host-cache 64 --quiet");
  if (failedForLackOfGl(r)) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.status, 0) << r.err;
  Imf::InputFile file(exr.c_str());
  const Imath::Box2i dw = file.header().dataWindow();
  ASSERT_EQ(dw.max.x - dw.min.x + 1, width);
  Imf::Array2D<float> depth(height, width);
  Imf::FrameBuffer fb;
  fb.insert("Z", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(&depth[0][0]), sizeof(float), sizeof(float) * width));
  file.setFrameBuffer(fb);
  file.readPixels(dw.min.y, dw.max.y);
  const render::CameraFrame frame = render::cameraFrame(camera, double(width) / height);
  int hits = 0;
  double worst = 0.0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (!std::isfinite(depth[y][x])) continue;
      const glm::dvec3 p = frame.eye + pixelRay(frame, x, y, width, height) * double(depth[y][x]);
      worst = std::max(worst, std::abs(glm::length(p) - kRadius));
      ++hits;
    }
  EXPECT_GT(hits, width * height / 4);
  EXPECT_LT(worst, 0.01) << "worst distance from the analytic sphere, in voxels, over " << hits << " hits";
}

// A dense raw input three times the memory bound converts within it: the voxels are read once into
// the slab scratch (TMPDIR) and the conversion holds about a slab of them, never the volume.
TEST(CliMemory, ConvertOfADenseRawFileLargerThanItsMemoryBound) {
  TempDir dir;
  // 384 MiB of f32, long along x so that a slab (its y-z cross-section) is small; a ball of data in
  // the middle (1 at the centre, 0 at radius 80), zeros elsewhere: every voxel is read all the same.
  const glm::ivec3 dims(2048, 256, 192);
  constexpr double kBoundMiB = 128.0;
  const std::string input = dir / "dense.raw", output = dir / "dense.vdb";
  {
    std::ofstream out(input, std::ios::binary);
    std::vector<float> row(size_t(dims.x));
    for (int z = 0; z < dims.z; ++z)
      for (int y = 0; y < dims.y; ++y) {
        for (int x = 0; x < dims.x; ++x) {
          const double r = glm::length(glm::dvec3(x, y, z) - glm::dvec3(dims) / 2.0);
          row[size_t(x)] = r < 80.0 ? float(1.0 - r / 80.0) : 0.0f;
        }
        out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size() * sizeof(float)));
      }
  }
  const double inputMiB = double(std::filesystem::file_size(input)) / double(1 << 20);
  ASSERT_GE(inputMiB, 3.0 * kBoundMiB);

  const MeasuredRun run = runMeasured({"convert", input, output, "--dims", "2048,256,192", "--type", "f32",
                                       "--cl-device", "reference", "--timings", "--quiet"}, dir);
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.err.find("read into slabs"), std::string::npos) << "--timings names the slab reading: " << run.err;
  const double peakMiB = double(run.peakRssKiB) / 1024.0;
  std::printf("convert dense raw %dx%dx%d f32 (%.0f MiB): peak RSS %.0f MiB\n", dims.x, dims.y, dims.z, inputMiB, peakMiB);
  // In memory the volume alone, as floats, was the input's size.
  EXPECT_LT(peakMiB, kBoundMiB) << run.err;

  // The ball is there: the samples run from 0 to the centre's 1.
  const FccGrid::Ptr grid = io::readFccGrid(output);
  EXPECT_FLOAT_EQ(grid->metaValue<float>(meta::kSampleMax), 1.0f);
  EXPECT_FLOAT_EQ(grid->metaValue<float>(meta::kSampleMin), 0.0f);
  EXPECT_GT(grid->tree().leafCount(), 500u);
}

}  // namespace
}  // namespace fcc::test
