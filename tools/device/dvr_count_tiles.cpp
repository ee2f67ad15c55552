// A measurement tool outside the build (docs/BENCHMARKS.md, session 33): from a DVR count image
// (FCCVDB_SHADER_DEFINES="FCC_DVR_COUNT=2" fccvdb render FILE out.exr --mode dvr ...: R the rounds a ray
// took, G its integrated cells, B its chain starts), the totals and the SIMT efficiency of the rounds
// over warp tiles of W x H pixels (sum over the tile's lanes / (lanes x the tile's largest)). Build:
//   g++ -O2 -std=c++17 tools/device/dvr_count_tiles.cpp -I/usr/include/OpenEXR -I/usr/include/Imath -lOpenEXR-3_1 -lImath-3_1
// Run: ./a.out out.exr 4 8
#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/ImfArray.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfChannelList.h>
#include <Imath/ImathBox.h>
#include <cstdio>
#include <vector>
#include <algorithm>
int main(int argc, char** argv) {
  Imf::InputFile f(argv[1]);
  int tw = argc > 2 ? atoi(argv[2]) : 4, th = argc > 3 ? atoi(argv[3]) : 8;
  Imath::Box2i dw = f.header().dataWindow();
  int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
  std::vector<float> r(size_t(w) * h), g(size_t(w) * h), b(size_t(w) * h);
  Imf::FrameBuffer fb;
  fb.insert("R", Imf::Slice(Imf::FLOAT, (char*)(r.data() - dw.min.x - dw.min.y * w), 4, 4 * w));
  fb.insert("G", Imf::Slice(Imf::FLOAT, (char*)(g.data() - dw.min.x - dw.min.y * w), 4, 4 * w));
  fb.insert("B", Imf::Slice(Imf::FLOAT, (char*)(b.data() - dw.min.x - dw.min.y * w), 4, 4 * w));
  f.setFrameBuffer(fb);
  f.readPixels(dw.min.y, dw.max.y);
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
