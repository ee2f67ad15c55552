// `fccvdb view` under Xvfb (Debian's xvfb-run): the automation screenshot shows the panel and the
// surface, and its 3D area matches `fccvdb render` of the same camera; a missing display and a
// Cartesian input each give one clear line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "ExrRead.h"
#include "PngRead.h"
#include "RunCommand.h"

namespace fcc {
namespace {

using test::CommandResult;
using test::lineCount;
using test::readExrChannel;
using test::readPng;
using test::Rgb8;
using test::runFccvdb;
using test::runShell;
using test::TempDir;

// 8-bit levels the viewer's GPU sRGB encoding may differ from `render`'s CPU one by (float
// rounding before the conversion to 8 bits), and the share of 3D-area pixels allowed beyond it.
constexpr int kLevelTolerance = 1;
constexpr double kOutlierFraction = 0.001;

bool haveXvfb() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

CommandResult runView(const std::string& args) {
  return runShell("xvfb-run -a -s '-screen 0 1280x1024x24' " + std::string(FCC_FCCVDB_EXE) + " view " + args);
}

// The viewer's PNG screenshot `shot` against `render`'s PNG `ref` of the same view: beside the panel
// (the first `panel` columns) the pixels agree within kLevelTolerance (but for kOutlierFraction of
// them), something other than the background shows, and the panel differs from `render`'s image.
void expectViewMatchesRender(const std::string& shot, const std::string& ref, int panel, int width, int height) {
  Rgb8 a, b;
  ASSERT_TRUE(readPng(shot, a));
  ASSERT_TRUE(readPng(ref, b));
  ASSERT_EQ(a.width, width);
  ASSERT_EQ(a.height, height);
  ASSERT_EQ(b.width, a.width);
  ASSERT_EQ(b.height, a.height);
  ASSERT_GT(panel, 100);
  ASSERT_LT(panel, a.width * 2 / 3);

  long compared = 0, outliers = 0, surface = 0, panelDiffers = 0;
  int worst = 0;
  const unsigned char* bg = b.pixels.data();  // render's corner pixel: the background
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const std::size_t i = (std::size_t(y) * a.width + x) * 3;
      int diff = 0;
      for (int c = 0; c < 3; ++c) diff = std::max(diff, std::abs(int(a.pixels[i + c]) - int(b.pixels[i + c])));
      if (x < panel) {
        panelDiffers += diff > 8;
        continue;
      }
      ++compared;
      worst = std::max(worst, diff);
      outliers += diff > kLevelTolerance;
      surface += !std::equal(bg, bg + 3, b.pixels.data() + i);
    }
  std::printf("3D area: %ld pixels, %ld of them not the background, %ld beyond %d levels (worst %d); panel: %ld pixels differ\n",
              compared, surface, outliers, kLevelTolerance, worst, panelDiffers);
  EXPECT_GT(surface, compared / 50) << "the data must show";
  EXPECT_LE(double(outliers), kOutlierFraction * double(compared));
  EXPECT_GT(panelDiffers, long(panel) * a.height / 4) << "the panel must show";
}

// The panel's width in pixels, as `view --screenshot` prints it.
int panelWidthOf(const CommandResult& view) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(view.out, m, std::regex("panel (\\d+) px wide"))) << view.out;
  return m.empty() ? 0 : std::stoi(m[1]);
}

TEST(CliView, ScreenshotShowsThePanelAndMatchesRenderOutsideIt) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed (setup.sh installs it)";
  TempDir dir;
  const std::string vdb = dir / "blobs.vdb", shot = dir / "view.png", ref = dir / "render.png";
  ASSERT_EQ(runFccvdb("synth blobs " + vdb + " --dims 96,96,96 --quiet").status, 0);
  const std::string common = vdb + " --res 800x450 --iso 0.4";
  const CommandResult view = runView(common + " --screenshot " + shot + " --frames 30");
  ASSERT_EQ(view.status, 0) << view.err;
  ASSERT_EQ(runFccvdb("render " + common + " -o " + ref + " --quiet").status, 0);
  expectViewMatchesRender(shot, ref, panelWidthOf(view), 800, 450);
}

// `view --mode dvr` shows the volume as `render --mode dvr` does (premultiplied colour over the
// background, sRGB), with the transfer function's panel.
TEST(CliView, DvrScreenshotMatchesRenderOutsideThePanel) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed (setup.sh installs it)";
  TempDir dir;
  const std::string vdb = dir / "blobs.vdb", shot = dir / "view.png", ref = dir / "render.png";
  ASSERT_EQ(runFccvdb("synth blobs " + vdb + " --dims 48,48,48 --quiet").status, 0);
  const std::string common = vdb + " --res 640x360 --mode dvr --tf viridis --density-scale 2";
  const CommandResult view = runView(common + " --screenshot " + shot + " --frames 5");
  ASSERT_EQ(view.status, 0) << view.err;
  ASSERT_EQ(runFccvdb("render " + common + " -o " + ref + " --quiet").status, 0);
  expectViewMatchesRender(shot, ref, panelWidthOf(view), 640, 360);
}

// `view --reconstruction trilinear` renders a Cartesian .vdb as it is (no conversion), as `render` does.
TEST(CliView, CartesianReconstructionRendersTheGridAsItIs) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed (setup.sh installs it)";
  TempDir dir;
  const std::string shot = dir / "view.png", ref = dir / "render.png";
  const std::string common = std::string(FCC_SHARED_DATA_DIR) + "/sphere.vdb --res 640x360 --reconstruction trilinear";
  const CommandResult view = runView(common + " --screenshot " + shot + " --frames 5");
  ASSERT_EQ(view.status, 0) << view.err;
  EXPECT_EQ(view.err.find("converting"), std::string::npos) << view.err;
  ASSERT_EQ(runFccvdb("render " + common + " -o " + ref + " --quiet").status, 0);
  expectViewMatchesRender(shot, ref, panelWidthOf(view), 640, 360);
}

// A BCC dataset opens in the viewer as in `render`: its default reconstruction, the same image.
TEST(CliView, BccDatasetRendersAsRenderDrawsIt) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed (setup.sh installs it)";
  TempDir dir;
  const std::string vdb = dir / "blobs_bcc.vdb", shot = dir / "view.png", ref = dir / "render.png";
  ASSERT_EQ(runFccvdb("synth blobs " + vdb + " --dims 48,48,48 --lattice bcc --quiet").status, 0);
  const std::string common = vdb + " --res 640x360 --iso 0.4";
  const CommandResult view = runView(common + " --screenshot " + shot + " --frames 5");
  ASSERT_EQ(view.status, 0) << view.err;
  ASSERT_EQ(runFccvdb("render " + common + " -o " + ref + " --quiet").status, 0);
  expectViewMatchesRender(shot, ref, panelWidthOf(view), 640, 360);
}

// The EXR screenshot holds the whole view, the columns under the panel (where the viewer casts no
// rays) included: the same coverage and depth as `fccvdb render`.
TEST(CliView, ExrScreenshotHoldsTheWholeView) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed (setup.sh installs it)";
  TempDir dir;
  const std::string vdb = dir / "blobs.vdb", shot = dir / "view.exr", ref = dir / "render.exr";
  ASSERT_EQ(runFccvdb("synth blobs " + vdb + " --dims 64,64,64 --quiet").status, 0);
  const std::string common = vdb + " --res 640x400 --iso 0.4";  // the panel is 330 px wide
  const CommandResult view = runView(common + " --screenshot " + shot + " --frames 10");
  ASSERT_EQ(view.status, 0) << view.err;
  ASSERT_EQ(runFccvdb("render " + common + " -o " + ref + " --quiet").status, 0);
  int w = 0, h = 0, rw = 0, rh = 0;
  const std::vector<float> alpha = readExrChannel(shot, "A", w, h), depth = readExrChannel(shot, "Z", w, h);
  const std::vector<float> refAlpha = readExrChannel(ref, "A", rw, rh), refDepth = readExrChannel(ref, "Z", rw, rh);
  ASSERT_EQ(w, rw);
  ASSERT_EQ(h, rh);
  constexpr float kDepthTolerance = 1e-4f;  // relative: the same renderer, the same rays
  int hitsLeft = 0, mismatches = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      const bool same = alpha[i] == refAlpha[i] &&
                        (std::isinf(refDepth[i]) ? std::isinf(depth[i])
                                                 : std::abs(depth[i] - refDepth[i]) <= kDepthTolerance * refDepth[i]);
      mismatches += !same;
      hitsLeft += x < w / 2 && refAlpha[i] > 0.5f;  // under the panel
    }
  EXPECT_GT(hitsLeft, 0) << "the surface must reach the panel's columns for this test to mean anything";
  EXPECT_EQ(mismatches, 0);
}

// One camera file for both: `view --camera F --screenshot OUT.exr` holds what `render --camera F` renders.
TEST(CliView, CameraFileGivesViewAndRenderTheSameView) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed (setup.sh installs it)";
  TempDir dir;
  const std::string vdb = dir / "blobs.vdb", camera = dir / "camera.json", shot = dir / "view.exr",
                    ref = dir / "render.exr";
  ASSERT_EQ(runFccvdb("synth blobs " + vdb + " --dims 64,64,64 --quiet").status, 0);
  std::ofstream(camera) << "{\"eye\": [90, 20, 110], \"lookat\": [30, 34, 28], \"up\": [0.2, 0, 1], \"fov\": 35}\n";
  const std::string common = vdb + " --res 480x320 --iso 0.4 --camera " + camera;
  const CommandResult view = runView(common + " --screenshot " + shot + " --frames 3");
  ASSERT_EQ(view.status, 0) << view.err;
  ASSERT_EQ(runFccvdb("render " + common + " -o " + ref + " --quiet").status, 0);
  int w = 0, h = 0, rw = 0, rh = 0;
  const std::vector<float> depth = readExrChannel(shot, "Z", w, h), refDepth = readExrChannel(ref, "Z", rw, rh);
  ASSERT_EQ(w, rw);
  ASSERT_EQ(h, rh);
  int hits = 0, mismatches = 0;
  for (std::size_t i = 0; i < depth.size(); ++i) {
    hits += std::isfinite(refDepth[i]);
    mismatches += !(depth[i] == refDepth[i] || (std::isinf(depth[i]) && std::isinf(refDepth[i])));
  }
  EXPECT_GT(hits, int(depth.size()) / 50) << "the surface must show";
  EXPECT_EQ(mismatches, 0);
}

TEST(CliView, BadCameraFileIsOneLineAndStatus1) {
  TempDir dir;
  const std::string vdb = dir / "s.vdb", camera = dir / "camera.json";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 16,16,16 --quiet").status, 0);
  std::ofstream(camera) << "{\"eye\": [1, 2, 3], \"lookat\": [0, 0, 0], \"fov\": \"wide\"}";
  for (const std::string& command : {"render " + vdb + " -o " + (dir / "x.png"), "view " + vdb}) {
    const CommandResult r = runFccvdb(command + " --camera " + camera);
    EXPECT_EQ(r.status, 1) << command;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("camera file " + camera + ": \"fov\" expects numbers; valid is"), std::string::npos) << r.err;
  }
}

TEST(CliView, NoDisplayGivesOneLineAndStatus1) {
  TempDir dir;
  const std::string vdb = dir / "s.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 16,16,16 --quiet").status, 0);
  const CommandResult r =
      runShell("env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(FCC_FCCVDB_EXE) + " view " + vdb);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("no display: use `fccvdb render` for headless images"), std::string::npos) << r.err;
  // A Cartesian input: the same line before any conversion (none is cached, nothing is said of one).
  const std::string raw = dir / "cube.raw";
  std::ofstream(raw, std::ios::binary) << std::string(8 * 8 * 8, '\x40');
  const CommandResult cartesian = runShell("FCCVDB_CACHE_DIR=" + (dir / "cache") + " env -u DISPLAY -u WAYLAND_DISPLAY " +
                                           std::string(FCC_FCCVDB_EXE) + " view " + raw + " --dims 8,8,8 --type u8");
  EXPECT_EQ(cartesian.status, 1);
  EXPECT_EQ(lineCount(cartesian.err), 1) << cartesian.err;
  EXPECT_NE(cartesian.err.find("no display"), std::string::npos) << cartesian.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "cache")) << "converted before saying there is no display";
}

TEST(CliView, CartesianInputIsConvertedIntoTheCache) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed (setup.sh installs it)";
  TempDir dir;
  const std::string source = dir / "sphere.vdb", cache = dir / "cache";
  std::filesystem::copy_file(std::string(FCC_SOURCE_DIR) + "/../shared/data/sphere.vdb", source);
  const std::string shot = dir / "shot.png";
  const CommandResult converted = runShell("FCCVDB_CACHE_DIR=" + cache + " xvfb-run -a -s '-screen 0 1280x1024x24' " +
                                           FCC_FCCVDB_EXE + " view " + source + " --res 320x240 --screenshot " + shot +
                                           " --frames 3");
  ASSERT_EQ(converted.status, 0) << converted.err;
  EXPECT_NE(converted.err.find("converting " + source + " to FCC once"), std::string::npos) << converted.err;
  Rgb8 image;
  EXPECT_TRUE(readPng(shot, image));
  EXPECT_EQ(dir.fileCount(), 2) << "nothing but the input and the screenshot beside the input";
  EXPECT_FALSE(std::filesystem::is_empty(cache));
}

// `view` takes a raw file's layout as `convert` does (--dims, --type), and keeps an existing screenshot
// unless --force, as every output of fccvdb, saying so in one line before a window opens.
TEST(CliView, RawInputTakesDimsAndTypeAndScreenshotNeedsForce) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed (setup.sh installs it)";
  TempDir dir;
  const std::string raw = dir / "ball.raw", shot = dir / "shot.png";
  {
    std::ofstream out(raw, std::ios::binary);
    for (int k = 0; k < 16; ++k)
      for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i) out.put(char((i - 8) * (i - 8) + (j - 8) * (j - 8) + (k - 8) * (k - 8) < 30 ? 200 : 0));
  }
  const std::string env = "FCCVDB_CACHE_DIR=" + (dir / "cache") + " ";
  const std::string args = raw + " --dims 16,16,16 --type u8 --res 320x240 --frames 2 --screenshot " + shot;
  const CommandResult r = runShell(env + "xvfb-run -a -s '-screen 0 1280x1024x24' " + FCC_FCCVDB_EXE + " view " + args);
  ASSERT_EQ(r.status, 0) << r.err;
  Rgb8 image;
  ASSERT_TRUE(readPng(shot, image));
  EXPECT_EQ(image.width, 320);
  const auto written = std::filesystem::last_write_time(shot);
  const CommandResult again = runShell(env + "xvfb-run -a -s '-screen 0 1280x1024x24' " + FCC_FCCVDB_EXE + " view " + args);
  EXPECT_EQ(again.status, 1);
  EXPECT_EQ(lineCount(again.err), 1) << again.err;
  EXPECT_NE(again.err.find("exists; pass --force to overwrite it"), std::string::npos) << again.err;
  EXPECT_EQ(std::filesystem::last_write_time(shot), written) << "overwritten without --force";
}


// `view --record-path` writes the camera of every frame on exit (here after --screenshot's frames, at
// least --frames of them), in the format `bench stream --path` reads; an existing file needs --force,
// refused in one line before the window opens.
TEST(CliView, RecordPathWritesEveryFrameOnExit) {
  if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed (setup.sh installs it)";
  TempDir dir;
  const std::string vdb = dir / "blobs.vdb", shot = dir / "view.png", path = dir / "path.json";
  ASSERT_EQ(runFccvdb("synth blobs " + vdb + " --dims 48,48,48 --quiet").status, 0);
  const CommandResult view = runView(vdb + " --res 480x270 --screenshot " + shot + " --frames 4 --record-path " + path);
  ASSERT_EQ(view.status, 0) << view.err;
  EXPECT_NE(view.out.find("camera path of"), std::string::npos) << view.out;
  EXPECT_EQ(test::checkJsonWithPython(dir, test::readText(path),
                                      "f = rows['frames']\nassert rows['fccvdb_camera_path'] == 1\n"
                                      "assert len(f) >= 4, len(f)\n"
                                      "assert all(a['t'] <= b['t'] for a, b in zip(f, f[1:]))\n"
                                      "assert all(x['eye'] == f[0]['eye'] for x in f)  # no input: the camera stayed\n"),
            0);
  const CommandResult again = runView(vdb + " --res 480x270 --screenshot " + (dir / "b.png") + " --frames 1 --record-path " + path);
  EXPECT_NE(again.status, 0);
  EXPECT_EQ(lineCount(again.err), 1) << again.err;
  EXPECT_NE(again.err.find("--force"), std::string::npos) << again.err;
}

}  // namespace
}  // namespace fcc
