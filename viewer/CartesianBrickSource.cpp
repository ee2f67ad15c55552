#include "CartesianBrickSource.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "sparse/CubicBSpline.h"
#include "sparse/Error.h"

namespace fcc::render {
namespace {

constexpr int kBlockDim = io::CartesianBrickStore::kBlockDim;
constexpr int kPad = kBSplinePrefilterReach;
constexpr int kPaddedDim = kBlockDim + 2 * kPad;

uint64_t brickKey(const glm::ivec3& b) {
  return (uint64_t(uint32_t(b.x) & 0x1FFFFF) << 42) | (uint64_t(uint32_t(b.y) & 0x1FFFFF) << 21) | (uint32_t(b.z) & 0x1FFFFF);
}

}  // namespace

double CartesianBrickSource::prefilterGain() {
  // The 1D response from a unit impulse in a line long enough that its tails are below float
  // precision (the filter's pole is |z| = 0.27), then cubed for the separable 3D filter.
  static const double gain = [] {
    std::vector<float> line(8 * kPad + 1, 0.0f);
    line[4 * kPad] = 1.0f;
    bsplinePrefilterLine(line.data(), int(line.size()), 1);
    double sum = 0.0;
    for (float h : line) sum += std::abs(double(h));
    return sum * sum * sum * (1.0 + 1e-5);  // and a margin for float rounding in the filter
  }();
  return gain;
}

CartesianBrickSource::CartesianBrickSource(const io::CartesianBrickStore& store, const ReconstructionInfo& reconstruction)
    : store_(store), reconstruction_(reconstruction) {
  if (reconstruction.lattice != Lattice::Cc) {
    const Lattice cc = Lattice::Cc;
    throw ValueError("reconstruction '" + std::string(reconstruction.name) + "' is not one of a Cartesian grid's (valid: " +
                     reconstructionNames(&cc) + ")");
  }
  prefiltered_ = reconstruction.prefilter == Prefilter::CubicBSpline;
  ranges_ = store.brickRanges();  // the raw samples' (from the user cache when the store keeps them there)
  if (prefiltered_) {
    // A coefficient is sum h_k s_k over the samples within kPad of it, with sum h_k = 1, so it lies
    // within gain * r of m for the samples' range [m - r, m + r] there; the padded block of brick b lies
    // in the blocks of b - 1 .. b + 1 (16 > kPad), a brick not listed holds the background only.
    std::unordered_map<uint64_t, glm::vec2> sampleRange;
    for (const auto& r : ranges_) sampleRange[brickKey(r.brick)] = glm::vec2(r.lo, r.hi);
    const float background = store.background();
    std::vector<io::CartesianBrickStore::BrickRange> widened;
    std::unordered_map<uint64_t, bool> seen;
    const double gain = prefilterGain();
    for (const auto& r : ranges_)
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const glm::ivec3 b = r.brick + glm::ivec3(dx, dy, dz);
            if (!seen.emplace(brickKey(b), true).second) continue;
            float lo = std::numeric_limits<float>::infinity(), hi = -lo;
            for (int ez = -1; ez <= 1; ++ez)
              for (int ey = -1; ey <= 1; ++ey)
                for (int ex = -1; ex <= 1; ++ex) {
                  const auto it = sampleRange.find(brickKey(b + glm::ivec3(ex, ey, ez)));
                  const glm::vec2 s = it == sampleRange.end() ? glm::vec2(background) : it->second;
                  lo = std::min(lo, s.x);
                  hi = std::max(hi, s.y);
                }
            const double mid = 0.5 * (double(lo) + hi), half = 0.5 * (double(hi) - lo) * gain;
            widened.push_back({b, float(mid - half), float(mid + half)});
          }
    ranges_ = std::move(widened);
  }
  if (ranges_.empty()) {
    valueMin_ = valueMax_ = store.background();
  } else {
    valueMin_ = std::numeric_limits<float>::infinity();
    valueMax_ = -valueMin_;
    for (const auto& r : ranges_) {
      valueMin_ = std::min(valueMin_, r.lo);
      valueMax_ = std::max(valueMax_, r.hi);
    }
  }
}

void CartesianBrickSource::brickBox(glm::ivec3& lo, glm::ivec3& hi) const {
  lo = glm::ivec3(std::numeric_limits<int>::max());
  hi = glm::ivec3(std::numeric_limits<int>::min());
  for (const auto& r : ranges_) {
    lo = glm::min(lo, r.brick);
    hi = glm::max(hi, r.brick);
  }
}

void CartesianBrickSource::forEachVaryingBrick(const std::function<void(const glm::ivec3&, float, float)>& visit) const {
  for (const auto& r : ranges_) visit(r.brick, r.lo, r.hi);
}

void CartesianBrickSource::decode(std::vector<LoadedBrick>& chunk) const {
  std::vector<float> padded;
  for (LoadedBrick& b : chunk) {
    b.halo.resize(slotBlockFloats(SlotBlock::Sites));
    const glm::ivec3 blockMin = b.brick * io::CartesianBrickStore::kBrickSites - io::CartesianBrickStore::kBlockLo;
    if (!prefiltered_) {
      store_.readBlock(b.brick, b.halo.data());
      continue;
    }
    padded.resize(std::size_t(kPaddedDim) * kPaddedDim * kPaddedDim);
    store_.readBox(blockMin - kPad, glm::ivec3(kPaddedDim), padded.data());
    const ptrdiff_t row = kPaddedDim, layer = ptrdiff_t(kPaddedDim) * kPaddedDim;
    // Along x (lines next to each other are a row apart), then y, then z.
    for (int z = 0; z < kPaddedDim; ++z) bsplinePrefilterLines(padded.data() + z * layer, kPaddedDim, 1, kPaddedDim, row);
    for (int z = 0; z < kPaddedDim; ++z) bsplinePrefilterLines(padded.data() + z * layer, kPaddedDim, row, kPaddedDim, 1);
    bsplinePrefilterLines(padded.data(), kPaddedDim, layer, int(layer), 1);
    for (int z = 0; z < kBlockDim; ++z)
      for (int y = 0; y < kBlockDim; ++y)
        std::copy_n(padded.data() + (z + kPad) * layer + (y + kPad) * row + kPad, kBlockDim,
                    b.halo.data() + (z * kBlockDim + y) * kBlockDim);
  }
}

}  // namespace fcc::render
