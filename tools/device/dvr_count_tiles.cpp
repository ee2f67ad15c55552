// A measurement tool outside the build (docs/BENCHMARKS.md, sessions 33 and 35): from a DVR count image
// (FCCVDB_SHADER_DEFINES="FCC_DVR_COUNT=2" or "=3" fccvdb render FILE out.exr --mode dvr ...; 2: R the
// rounds a ray took, G its integrated cells, B its chain starts; 3: R its rounds, G its brick steps, B
// its walk's iterations), each channel's total, its mean over the rays with rounds (theirs alone), the mean over warp
// tiles of W x H pixels of the tile's largest lane (a warp runs as long as its longest ray) and the
// channel's SIMT efficiency there (sum over the tile's lanes / (lanes x the tile's largest)). Build:
//   g++ -O2 -std=c++17 tools/device/dvr_count_tiles.cpp -I/usr/include/OpenEXR -I/usr/include/Imath -lOpenEXR-3_1 -lImath-3_1
// Run: ./a.out out.exr 4 8 [MODE]   (MODE: the knob's value, 2 or 3, for the channels' names)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "../../tests/tools/ExrRead.h"  // header-only: the tests' reading of one channel

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s COUNT.exr [TILE_W TILE_H [MODE]]\n", argv[0]);
    return 2;
  }
  const int tw = argc > 2 ? std::atoi(argv[2]) : 4, th = argc > 3 ? std::atoi(argv[3]) : 8;
  const bool mode3 = argc > 4 && std::atoi(argv[4]) == 3;
  const char* names[3] = {"R", "G", "B"};
  const char* what2[3] = {"rounds that take a cell", "cells integrated", "chain starts"};
  const char* what3[3] = {"rounds", "brick steps", "walk iterations"};
  int w = 0, h = 0;
  std::vector<float> ch[3];
  for (int c = 0; c < 3; ++c) ch[c] = fcc::test::readExrChannel(argv[1], names[c], w, h);
  // Over the tiles with rounds: their sums (the efficiency's numerator), largest lanes and lanes x largest.
  double sum[3] = {0, 0, 0}, busySum[3] = {0, 0, 0}, tileSum[3] = {0, 0, 0}, tileMost[3] = {0, 0, 0}, lanesTimesMost[3] = {0, 0, 0};
  long busy = 0, tiles = 0;
  for (int ty = 0; ty < h; ty += th)
    for (int tx = 0; tx < w; tx += tw) {
      double most[3] = {0, 0, 0}, inTile[3] = {0, 0, 0};
      int lanes = 0;
      for (int y = ty; y < std::min(h, ty + th); ++y)
        for (int x = tx; x < std::min(w, tx + tw); ++x) {
          const size_t i = size_t(y) * w + x;
          for (int c = 0; c < 3; ++c) {
            sum[c] += ch[c][i];
            inTile[c] += ch[c][i];
            if (ch[0][i] > 0) busySum[c] += ch[c][i];
            most[c] = std::max(most[c], double(ch[c][i]));
          }
          busy += ch[0][i] > 0;
          ++lanes;
        }
      if (most[0] <= 0) continue;  // no ray of the tile took a round
      ++tiles;
      for (int c = 0; c < 3; ++c) {
        tileSum[c] += inTile[c];
        tileMost[c] += most[c];
        lanesTimesMost[c] += most[c] * lanes;
      }
    }
  std::printf("%dx%d: %ld rays with rounds, %ld tiles of %dx%d with some\n", w, h, busy, tiles, tw, th);
  for (int c = 0; c < 3; ++c)
    std::printf("  %-24s total %.4g, %.1f a ray; a tile's largest lane %.1f on average; SIMT efficiency %.3f\n",
                (mode3 ? what3 : what2)[c], sum[c], busy ? busySum[c] / busy : 0.0, tiles ? tileMost[c] / tiles : 0.0,
                lanesTimesMost[c] > 0 ? tileSum[c] / lanesTimesMost[c] : 0.0);
  return 0;
}
