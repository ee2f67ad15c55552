// A measurement tool outside the build (docs/BENCHMARKS.md, session 33): from a DVR count image
// (FCCVDB_SHADER_DEFINES="FCC_DVR_COUNT=2" fccvdb render FILE out.exr --mode dvr ...: R the rounds a ray
// took, G its integrated cells, B its chain starts), the totals and the SIMT efficiency of the rounds
// over warp tiles of W x H pixels (sum over the tile's lanes / (lanes x the tile's largest)). Build:
//   g++ -O2 -std=c++17 tools/device/dvr_count_tiles.cpp -I/usr/include/OpenEXR -I/usr/include/Imath -lOpenEXR-3_1 -lImath-3_1
// Run: ./a.out out.exr 4 8
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "../../tests/tools/ExrRead.h"  // header-only: the tests' reading of one channel

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s COUNT.exr [TILE_W TILE_H]\n", argv[0]);
    return 2;
  }
  int tw = argc > 2 ? std::atoi(argv[2]) : 4, th = argc > 3 ? std::atoi(argv[3]) : 8;
  int w = 0, h = 0;
  const std::vector<float> r = fcc::test::readExrChannel(argv[1], "R", w, h), g = fcc::test::readExrChannel(argv[1], "G", w, h),
                           b = fcc::test::readExrChannel(argv[1], "B", w, h);
  double sumR = 0, sumG = 0, sumB = 0, warpR = 0, warpG = 0; long pixR = 0, tiles = 0;
  for (int ty = 0; ty < h; ty += th)
    for (int tx = 0; tx < w; tx += tw) {
      double s = 0, mx = 0, sg = 0, mg = 0; int n = 0;
      for (int y = ty; y < std::min(h, ty + th); ++y)
        for (int x = tx; x < std::min(w, tx + tw); ++x) {
          size_t i = size_t(y) * w + x;
          s += r[i]; mx = std::max(mx, double(r[i])); sg += g[i]; mg = std::max(mg, double(g[i])); ++n;
          sumR += r[i]; sumG += g[i]; sumB += b[i]; pixR += r[i] > 0;
        }
      if (mx > 0) { ++tiles; warpR += mx * n; warpG += mg * n; }
    }
  std::printf("%dx%d: pixels with rounds %ld; rounds %.4g cells %.4g chain starts %.4g; mean rounds/ray %.1f cells/ray %.1f\n",
              w, h, pixR, sumR, sumG, sumB, sumR / pixR, sumG / pixR);
  std::printf("tile %dx%d: %ld tiles; SIMT efficiency of rounds %.3f, of cells %.3f\n", tw, th, tiles, sumR / warpR, sumG / warpG);
}
