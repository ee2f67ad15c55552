// `fccvdb bench stream` as a user runs it (llvmpipe, a small file, tiny budgets): the JSON holds every
// key of issue 19's contract with values that agree with each other and with the flags, the plots are
// well-formed SVG, two budgets give two runs, every path runs, and bad flags are one line each.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "RunCommand.h"

namespace fcc::test {
namespace {

using ::testing::HasSubstr;

// One small file for the suite: `synth blobs --dims 64,64,64` (151 varying bricks).
class BenchStream : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir;
    file_ = *dir_ / "blobs.vdb";
    ASSERT_EQ(runFccvdb("synth blobs " + file_ + " --dims 64,64,64 --quiet").status, 0);
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static TempDir* dir_;
  static std::string file_;
};
TempDir* BenchStream::dir_ = nullptr;
std::string BenchStream::file_;

// Python asserts over the bench's JSON file: every contract key, and values consistent with the flags.
const char* const kContractChecks = R"(
import math
d = rows
MiB = 1024 * 1024
assert d['frames'] == FRAMES, d['frames']
assert d['upload_fit'] is True, d['upload_fit']  # the default, as the viewer
assert d['primed'] in (True, False), d['primed']
assert d['res'] == [64, 48], d['res']
assert len(d['runs']) == len(GPU) * len(HOST), len(d['runs'])
pairs = [(r['summary']['gpu_budget_bytes'], r['summary']['host_budget_bytes']) for r in d['runs']]
assert sorted(pairs) == sorted((int(g * MiB), int(h * MiB)) for g in GPU for h in HOST), pairs
for r in d['runs']:
    s = r['summary']
    for k in ['p50_frame_ms', 'p99_frame_ms', 'gpu_hit_rate', 'max_gpu_bytes', 'max_host_bytes',
              'gpu_budget_bytes', 'host_budget_bytes', 'budget_ok', 'max_rss_bytes']:
        assert k in s, k
    f = r['frames']
    assert len(f) == FRAMES, len(f)
    for x in f:
        for k in ['frame_ms', 'bricks_uploaded', 'bricks_missing', 'full_resolution_fraction', 'passes',
                  'bricks_requested', 'bytes_uploaded', 'level_mix', 'gpu_hit_rate', 'gpu_bytes', 'host_bytes', 'rss_bytes',
                  'upload_ms', 'dispatch_ms', 'pass_ms', 'request_ms', 'gpu_pass_ms']:
            assert k in x, k
        assert x['frame_ms'] > 0
        assert x['passes'] in (0, 1)
        assert x['gpu_pass_ms'] >= 0 and (x['passes'] == 1 or x['gpu_pass_ms'] == 0), x
        assert x['bricks_missing'] <= x['bricks_requested'], x
        assert 0 <= x['full_resolution_fraction'] <= 1
        assert x['bytes_uploaded'] == x['bricks_uploaded'] * 16000, x  # an FCC brick's staged block: 10^3 packed voxels
        if x['passes'] == 1:
            assert len(x['level_mix']) >= 1, x
            assert x['gpu_hit_rate'] is None or 0 <= x['gpu_hit_rate'] <= 1, x
        assert x['gpu_bytes'] <= s['max_gpu_bytes'] and x['host_bytes'] <= s['max_host_bytes']
        assert x['rss_bytes'] <= s['max_rss_bytes']
    times = sorted(x['frame_ms'] for x in f)
    assert s['p50_frame_ms'] <= s['p99_frame_ms'] <= max(times), s
    assert min(times) <= s['p50_frame_ms']
    assert s['p50_frame_ms'] in times and s['p99_frame_ms'] in times
    assert 0 <= s['gpu_hit_rate'] <= 1, s
    # Every brick uploaded was requested by an earlier frame's pass (nothing is uploaded unasked).
    requested = 0
    for x in f:
        assert x['bricks_uploaded'] <= requested, (x, requested)
        requested += x['bricks_requested'] - x['bricks_uploaded']
    # The passes asked for bricks (how many arrived within a 1 ms frame depends on the machine's load:
    # a loaded 2-core CI machine uploaded none in 4 frames, so uploads are not counted on here).
    assert sum(x['bricks_requested'] for x in f) > 0, 'nothing requested: the budgets tested nothing'
    assert s['max_gpu_bytes'] == r['slots'] * r['slot_bytes'], s
    ok = s['max_gpu_bytes'] <= 1.02 * s['gpu_budget_bytes'] and s['max_host_bytes'] <= 1.02 * s['host_budget_bytes']
    assert s['budget_ok'] == ok, s
    assert s['budget_ok'], s
    assert s['max_rss_bytes'] > 0
assert len(d['working_set']) >= 1
for w in d['working_set']:
    assert 0 < w['bricks'] <= d['data_bricks'], w
)";

std::string checksFor(int frames, const std::string& gpu, const std::string& host) {
  return "FRAMES = " + std::to_string(frames) + "\nGPU = [" + gpu + "]\nHOST = [" + host + "]\n" + kContractChecks;
}

TEST_F(BenchStream, JsonHoldsEveryContractKeyWithConsistentValues) {
  const std::string json = *dir_ / "orbit.json";
  const CommandResult r = runFccvdb("bench stream " + file_ + " --path orbit --res 64x48 --frames 6 --gpu-cache 1 "
                                    "--host-cache 2 --frame-budget-ms 1 --json " + json);
  if (failedForLackOfGl(r)) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(checkJsonWithPython(*dir_, readText(json), checksFor(6, "1", "2")), 0) << readText(json).substr(0, 2000);
  // --prime auto: on for a GPU, off for a CPU renderer (tools/CpuRenderer.h's names).
  EXPECT_EQ(checkJsonWithPython(*dir_, readText(json),
                                "cpu = any(n in rows['device'] for n in ('llvmpipe', 'softpipe', 'lavapipe', 'SwiftShader'))\n"
                                "assert rows['primed'] == (not cpu), (rows['primed'], rows['device'])\n"),
            0);
  EXPECT_THAT(r.out, HasSubstr("p99 ms"));  // the table on stdout
}

// Two GPU budgets give two runs; the plots are written beside the JSON and parse as XML, each with a
// line or points drawn.
TEST_F(BenchStream, TwoBudgetsGiveTwoRunsAndWellFormedPlots) {
  TempDir out;
  const std::string json = out / "sweep.json";
  const CommandResult r = runFccvdb("bench stream " + file_ + " --path orbit --res 64x48 --frames 4 --gpu-cache 1,4 "
                                    "--host-cache 2 --frame-budget-ms 1 --json " + json);
  if (failedForLackOfGl(r)) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(checkJsonWithPython(out, readText(json), checksFor(4, "1, 4", "2")), 0);
  for (const char* name : {"sweep-frame-time.svg", "sweep-fps.svg", "sweep-hit-rate.svg", "sweep-working-set.svg"}) {
    const std::string svg = out / name;
    ASSERT_TRUE(std::filesystem::exists(svg)) << svg;
    EXPECT_EQ(std::system(("python3 -c \"import sys, xml.dom.minidom as m; d = m.parse(sys.argv[1]); "
                           "assert d.documentElement.tagName == 'svg'; "
                           "assert d.getElementsByTagName('polyline') or d.getElementsByTagName('circle')\" " + svg)
                              .c_str()),
              0)
        << svg;
  }
  EXPECT_EQ(checkJsonWithPython(out, readText(json),
                                "import os\nassert len(rows['plots']) == 4, rows['plots']\n"
                                "assert all(os.path.exists(p) for p in rows['plots'])\n"),
            0);
  // Outputs are kept unless --force: a second run refuses before any work.
  const CommandResult again = runFccvdb("bench stream " + file_ + " --res 64x48 --frames 1 --json " + json);
  EXPECT_NE(again.status, 0);
  EXPECT_EQ(lineCount(again.err), 1) << again.err;
  EXPECT_THAT(again.err, HasSubstr("--force"));
  // --plots puts them in another folder.
  TempDir plots;
  const CommandResult p = runFccvdb("bench stream " + file_ + " --res 64x48 --frames 2 --gpu-cache 4 --host-cache 2 "
                                    "--frame-budget-ms 1 --plots " + plots.path.string());
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_TRUE(std::filesystem::exists(plots / "stream-frame-time.svg"));
}

// The zoom and jumps paths run to the end; jumps with one seed hold their camera for --jump-every
// frames: a frame that keeps the camera of a complete view runs no pass.
TEST_F(BenchStream, ZoomAndJumpsPathsRun) {
  for (const std::string path : {"zoom", "jumps"}) {
    TempDir out;
    const std::string json = out / "p.json";
    // --prime on: the runs follow a throwaway renderer's steps (the JSON says so); they start with
    // fresh caches all the same (nothing resident at the first frame, which requests bricks).
    const CommandResult r = runFccvdb("bench stream " + file_ + " --path " + path + " --res 64x48 --frames 5 "
                                      "--gpu-cache 4 --host-cache 4 --frame-budget-ms 1 --jump-every 5 --prime on --json " + json);
    if (failedForLackOfGl(r)) GTEST_SKIP() << r.err;
    ASSERT_EQ(r.status, 0) << path << ": " << r.err;
    EXPECT_EQ(checkJsonWithPython(out, readText(json), checksFor(5, "4", "4")), 0) << path;
    EXPECT_EQ(checkJsonWithPython(out, readText(json),
                                  "assert rows['primed'] is True\n"
                                  "f = rows['runs'][0]['frames']\n"
                                  "assert f[0]['gpu_resident_bytes'] == 0 and f[0]['bricks_requested'] > 0, f[0]\n"),
              0)
        << path;
    // Jumps hold each camera for 5 frames: only the first frame restarts the rays.
    if (path == "jumps")
      EXPECT_EQ(checkJsonWithPython(out, readText(json),
                                    "f = rows['runs'][0]['frames']\n"
                                    "assert [x['restarted'] for x in f] == [True] + [False] * 4, f\n"),
                0);
    else  // the zoom moves every frame
      EXPECT_EQ(checkJsonWithPython(out, readText(json),
                                    "assert all(x['restarted'] for x in rows['runs'][0]['frames'])\n"),
                0);
  }
}

TEST_F(BenchStream, BadFlagsAreOneLineNamingTheFlag) {
  TempDir out;
  const std::string notJson = out / "cameras.txt", broken = out / "broken.json";
  {
    std::ofstream(notJson) << "x";
    std::ofstream(broken) << "{\"fccvdb_camera_path\": 1, \"frames\": []}";
  }
  const struct {
    std::string args, flag;
  } cases[] = {
      {"--path spiral", "--path"},
      {"--path " + notJson, "--path"},
      {"--path " + (out / "missing.json"), "--path"},
      {"--path " + broken, "--path"},
      {"--gpu-cache 1,x", "--gpu-cache"},
      {"--gpu-cache 0", "--gpu-cache"},
      {"--host-cache 4,,8", "--host-cache"},
      {"--frames 0", "--frames"},
      {"--res 64", "--res"},
      {"--plots " + (out / "no-such-folder"), "--plots"},
      {"--upload-ms 20 --frame-budget-ms 10", "--upload-ms"},
      {"--upload-fit maybe", "--upload-fit"},
      {"--prime maybe", "--prime"},
  };
  for (const auto& c : cases) {
    const CommandResult r = runFccvdb("bench stream " + file_ + " --frames 2 --res 64x48 " + c.args);
    EXPECT_NE(r.status, 0) << c.args;
    EXPECT_EQ(lineCount(r.err), 1) << c.args << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.flag)) << c.args;
  }
}

}  // namespace
}  // namespace fcc::test
