// A measurement tool outside the build (docs/BENCHMARKS.md, session 34): from a DVR clock image
// (FCCVDB_SHADER_DEFINES="FCC_DVR_CLOCK=1" fccvdb render FILE out.exr --mode dvr ...: R, G, B and Z
// each ray's SM cycles in the finds, the gathers, the chords and the rest, raycast.comp), the frame's
// cycles by phase, their shares, and the cycles a ray and a warp tile of W x H pixels took (the tile's
// largest lane: a warp ends with its last ray). Build:
//   g++ -O2 -std=c++17 tools/device/dvr_clock_phases.cpp -I/usr/include/OpenEXR -I/usr/include/Imath -lOpenEXR-3_1 -lImath-3_1
// Run: ./a.out out.exr 4 8 [MODE]   (MODE: the knob's value, 1 or 2, for the phases' names)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "../../tests/tools/ExrRead.h"  // header-only: the tests' reading of one channel

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s CLOCK.exr [TILE_W TILE_H [MODE]]\n", argv[0]);
    return 2;
  }
  const int tw = argc > 2 ? std::atoi(argv[2]) : 4, th = argc > 3 ? std::atoi(argv[3]) : 8;
  int w = 0, h = 0;
  const char* names[4] = {"R", "G", "B", "Z"};
  std::vector<float> ch[4];
  for (int c = 0; c < 4; ++c) ch[c] = fcc::test::readExrChannel(argv[1], names[c], w, h);
  double sum[4] = {0, 0, 0, 0}, busySum = 0, tileMaxSum = 0, busyTiles = 0;
  long busy = 0;
  for (size_t i = 0; i < size_t(w) * h; ++i) {
    for (int c = 0; c < 4; ++c) sum[c] += ch[c][i];
    const double phases = double(ch[0][i]) + ch[1][i] + ch[2][i];
    if (phases > 0) {
      ++busy;
      busySum += phases + ch[3][i];
    }
  }
  for (int ty = 0; ty < h; ty += th)
    for (int tx = 0; tx < w; tx += tw) {
      double most = 0, rounds = 0;
      for (int y = ty; y < std::min(h, ty + th); ++y)
        for (int x = tx; x < std::min(w, tx + tw); ++x) {
          const size_t i = size_t(y) * w + x;
          rounds += double(ch[0][i]) + ch[1][i] + ch[2][i];
          most = std::max(most, double(ch[0][i]) + ch[1][i] + ch[2][i] + ch[3][i]);
        }
      if (rounds > 0) {
        ++busyTiles;
        tileMaxSum += most;
      }
    }
  const double all = sum[0] + sum[1] + sum[2] + sum[3];
  const bool mode2 = argc > 4 && std::atoi(argv[4]) == 2;
  const char* what1[4] = {"find", "gather+taylor", "chord (rule, sub-steps)", "rest (brick walk, set-up)"};
  const char* what2[4] = {"find+chord set-up", "gather's wait", "piece, rule, sub-steps", "rest (brick walk, set-up)"};
  const char* const* what = mode2 ? what2 : what1;
  std::printf("%dx%d: %ld rays with rounds, %.0f busy %dx%d tiles\n", w, h, busy, busyTiles, tw, th);
  for (int c = 0; c < 4; ++c) std::printf("  %-28s %.4g cycles, %.1f %%\n", what[c], sum[c], 100.0 * sum[c] / all);
  std::printf("  mean cycles a busy ray %.4g; a busy tile's largest lane %.4g\n", busy ? busySum / busy : 0.0,
              busyTiles ? tileMaxSum / busyTiles : 0.0);
  return 0;
}
