#include "PrefilterBricks.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <memory>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include "BrickBounds.h"
#include "Lattice.h"
#include "Spline.h"

namespace fcc {
namespace {

using openvdb::Coord;
using openvdb::Vec4f;
using FccLeaf = FccTree::LeafNodeType;

constexpr int D = kBrickPackedDim;  // packed voxels per brick side
constexpr int H = D + 2;            // with the one-voxel halo
constexpr int kPlaneSize = H * H * H;
static_assert(FccLeaf::DIM == D, "a brick is a leaf of the FCC tree");

// Halo coordinates (x, y, z) in [0, H)^3 are packed voxel 8b - 1 + (x, y, z); z fastest, as in a leaf.
constexpr int haloIndex(int x, int y, int z) { return (x * H + y) * H + z; }

// The brick's packed voxels and their halo, one plane a channel.
struct HaloPlanes {
  alignas(64) float plane[4][kPlaneSize];
};

// Tap k of channel c: the neighbour site s + fcc_neighbour_offset(k) of the channel-c site s of a packed
// voxel p lies in packed voxel p + delta, channel c', the same for every p: one (plane, offset) pair.
struct Tap {
  int channel;
  int offset;  // haloIndex(delta), negative or positive
};
struct TapTable {
  Tap taps[4][12];
};

TapTable makeTapTable() {
  TapTable table{};
  for (int c = 0; c < 4; ++c) {
    const glm::ivec3 site = siteOfChannel(glm::ivec3(0), c);
    for (int k = 0; k < 12; ++k) {
      const glm::ivec3 neighbour = site + spline::fcc_neighbour_offset(k);
      const glm::ivec3 delta = packedVoxelOfSite(neighbour);
      table.taps[c][k] = Tap{channelOfSite(neighbour), haloIndex(delta.x, delta.y, delta.z)};
    }
  }
  return table;
}

const TapTable& tapTable() {
  static const TapTable table = makeTapTable();
  return table;
}

// Splits `count` interleaved Vec4f into the four planes at `dst`: four voxels at a time by a 4x4
// transpose in SSE registers (the copy was most of the gathering), the rest one by one.
inline void copyRunToPlanes(const Vec4f* src, int count, HaloPlanes& halo, int dst) {
  int z = 0;
#if defined(__SSE__)
  for (; z + 4 <= count; z += 4) {
    __m128 a = _mm_loadu_ps(src[z].asPointer()), b = _mm_loadu_ps(src[z + 1].asPointer());
    __m128 c = _mm_loadu_ps(src[z + 2].asPointer()), d = _mm_loadu_ps(src[z + 3].asPointer());
    _MM_TRANSPOSE4_PS(a, b, c, d);
    _mm_storeu_ps(halo.plane[0] + dst + z, a);
    _mm_storeu_ps(halo.plane[1] + dst + z, b);
    _mm_storeu_ps(halo.plane[2] + dst + z, c);
    _mm_storeu_ps(halo.plane[3] + dst + z, d);
  }
#endif
  for (; z < count; ++z)
    for (int c = 0; c < 4; ++c) halo.plane[c][dst + z] = src[z][c];
}

// Copies the values of packed voxels [8b - 1, 8b + 9)^3 into the planes: per neighbour brick, its
// leaf's buffer (z runs contiguous in both) or its one value (a tile or the background).
void gatherHalo(FccGrid::ConstAccessor& accessor, const Coord& brick, HaloPlanes& halo) {
  const Coord origin(brick.x() * D, brick.y() * D, brick.z() * D);
  for (int nx = -1; nx <= 1; ++nx)
    for (int ny = -1; ny <= 1; ++ny)
      for (int nz = -1; nz <= 1; ++nz) {
        const int n[3] = {nx, ny, nz};
        int lo[3], hi[3], local[3];  // halo range [lo, hi) per axis; local = the neighbour's coordinate at lo
        for (int a = 0; a < 3; ++a) {
          lo[a] = n[a] < 0 ? 0 : (n[a] == 0 ? 1 : D + 1);
          hi[a] = n[a] < 0 ? 1 : (n[a] == 0 ? D + 1 : H);
          local[a] = lo[a] - 1 - D * n[a];
        }
        const Coord neighbourOrigin = origin.offsetBy(D * nx, D * ny, D * nz);
        if (const FccLeaf* leaf = accessor.probeConstLeaf(neighbourOrigin)) {
          const Vec4f* values = leaf->buffer().data();
          for (int x = lo[0]; x < hi[0]; ++x)
            for (int y = lo[1]; y < hi[1]; ++y) {
              const Vec4f* src = values + (((local[0] + x - lo[0]) * D + local[1] + y - lo[1]) * D + local[2]);
              copyRunToPlanes(src, hi[2] - lo[2], halo, haloIndex(x, y, lo[2]));
            }
        } else {
          const Vec4f value = accessor.getValue(neighbourOrigin);
          for (int x = lo[0]; x < hi[0]; ++x)
            for (int y = lo[1]; y < hi[1]; ++y) {
              const int dst = haloIndex(x, y, lo[2]);
              for (int z = 0; z < hi[2] - lo[2]; ++z)
                for (int c = 0; c < 4; ++c) halo.plane[c][dst + z] = value[c];
            }
        }
      }
}

// q_fcc of the brick's 8^3 packed voxels: per output row (x, y), for each channel, 12 rows of
// neighbours summed in tap order (the order of spline::prefilterAt), then fcc_prefilter. Compiled
// for AVX2 too (a row of 8 floats is one register), chosen at load time where the CPU has it; the
// same operations in the same order either way (no FMA: -ffp-contract=off), so the same bits.
__attribute__((target_clones("avx2", "default"))) void filterHalo(const HaloPlanes& halo, const TapTable& table, Vec4f* out) {
  for (int x = 0; x < D; ++x)
    for (int y = 0; y < D; ++y) {
      const int base = haloIndex(x + 1, y + 1, 1);
      float result[4][D];
      for (int c = 0; c < 4; ++c) {
        float sum[D] = {};
        for (int k = 0; k < 12; ++k) {
          const float* row = halo.plane[table.taps[c][k].channel] + base + table.taps[c][k].offset;
          for (int z = 0; z < D; ++z) sum[z] += row[z];
        }
        const float* centre = halo.plane[c] + base;
        for (int z = 0; z < D; ++z) result[c][z] = spline::fcc_prefilter(centre[z], sum[z]);
      }
      Vec4f* dst = out + (x * D + y) * D;
      for (int z = 0; z < D; ++z) dst[z] = Vec4f(result[0][z], result[1][z], result[2][z], result[3][z]);
    }
}

}  // namespace

void prefilterBricks(const FccGrid& samples, const std::vector<Coord>& bricks,
                     const std::function<void(std::size_t i, const Vec4f* values)>& take) {
  const TapTable& table = tapTable();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, bricks.size(), 4), [&](const tbb::blocked_range<size_t>& r) {
    FccGrid::ConstAccessor accessor = samples.getConstAccessor();
    auto halo = std::make_unique<HaloPlanes>();
    std::vector<Vec4f> values(FccLeaf::SIZE);
    for (size_t i = r.begin(); i != r.end(); ++i) {
      gatherHalo(accessor, bricks[i], *halo);
      filterHalo(*halo, table, values.data());
      take(i, values.data());
    }
  });
}

void prefilterBricks(const FccGrid& samples, const std::vector<Coord>& bricks, Vec4f* out) {
  prefilterBricks(samples, bricks, [out](std::size_t i, const Vec4f* values) {
    std::copy(values, values + FccLeaf::SIZE, out + i * FccLeaf::SIZE);
  });
}

FccLeaf* makeCoefficientLeaf(const Coord& brick, const Vec4f* computed, const Vec4f& background) {
  // Uninitialised values (PartialCreate, then allocate): every one is written below.
  auto leaf = std::make_unique<FccLeaf>(openvdb::PartialCreate(), Coord(brick.x() * D, brick.y() * D, brick.z() * D),
                                        background, false);
  leaf->buffer().allocate();
  Vec4f* values = leaf->buffer().data();
  auto& active = leaf->getValueMask();
  for (openvdb::Index n = 0; n < FccLeaf::SIZE; ++n) {
    if (computed[n] == background) {
      values[n] = background;
    } else {
      values[n] = computed[n];
      active.setOn(n);
    }
  }
  return active.isOff() ? nullptr : leaf.release();
}

}  // namespace fcc
