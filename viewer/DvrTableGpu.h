// A transfer table (sparse/TransferFunction.h) as shaders/dvr.glsl reads it: its entries, their
// prefix sums (non-zero count, kinks, colour steps) and a sparse table of their extinction's maxima and
// minima in SSBOs 12, 13 and 14 (the GPU's TransferTable::zeroOn, maxExtinctionOn and minExtinctionOn,
// exact, kinkSumOn and colourVariationOn, bounds: all O(1)), its range and size as uniforms. Shared
// by every program that integrates emission and absorption (the raycaster's DVR, projected
// tetrahedra), so they read one table the same way.
#pragma once

#include <memory>
#include <vector>

#include "GlProgram.h"
#include "sparse/TransferFunction.h"

namespace fcc::render {

class DvrTableGpu {
 public:
  explicit DvrTableGpu(const TransferTable& table);
  // The table again (a new transfer function); the buffers grow when it has more entries.
  void upload(const TransferTable& table);
  // dvr.glsl's uniforms on `program`, and the transmittance at which a ray stops.
  void setUniforms(const GlProgram& program, float stopTransmittance) const;
  void bind() const;  // the SSBOs at bindings 12, 13 and 14

  // TransferTable's extinction sparse tables flattened as dvr.glsl's tfExtinctionOn reads them:
  // levels[k * size + i] = (the largest, the smallest extinction of entries [i, i + 2^k)), for k while
  // 2^k <= size (the i past size - 2^k, which no query reads, are 0).
  static std::vector<glm::vec2> extinctionLevels(const TransferTable& table);

  // The prefix sums dvr.glsl's tfPrefix holds, size + 1 of them: (non-zero entries, kinks, colour
  // steps) among entries [0, i), and in w the kinks among [0, i + 1). The sums are in whole quanta
  // (returned), each term rounded up, so a difference of two is exact in unsigned arithmetic and times
  // its quantum at least the table's own sum (within float rounding where the shader multiplies) and
  // at most a quantum a term more; a quantum is 2^-30 of the table's whole sum.
  struct Prefixes {
    std::vector<glm::uvec4> sums;
    float kinkQuantum = 0.0f, colourQuantum = 0.0f;
  };
  static Prefixes prefixes(const TransferTable& table);

  // Where the table's non-zero entries lie: [first, end) holds them all (first = size, end = 0 where
  // there are none), and whether a zero entry lies between two of them. dvr.glsl's tfZeroOn answers
  // from these alone where it can (uniforms: no reads), from the prefix counts where a zero run lies
  // inside (docs/DVR.md, "Skipping").
  struct NonZeroSpan {
    int first = 0, end = 0;
    bool interiorZeros = false;
  };
  static NonZeroSpan nonZeroSpan(const TransferTable& table);

 private:
  std::unique_ptr<GlBuffer> entries_, prefix_, maxLevels_;
  float vmin_ = 0.0f, scale_ = 1.0f, kinkQuantum_ = 0.0f, colourQuantum_ = 0.0f;
  NonZeroSpan nonZero_;
  int size_ = 0;
};

}  // namespace fcc::render
