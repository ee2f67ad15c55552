// A CPU reference ray caster for the renderer tests: the first crossing of s(x) = iso along a pixel's
// ray, found by dense sampling of the spline in double precision (step 1/32 of a lattice unit by
// default) and bisection, with no knowledge of the cells, pieces or roots the raycaster walks.
//
// The spline is evaluated from its definition on each piece: the piece is located with fcc_locate
// (on coordinates relative to an even cube, so that float rounding stays at 1e-7 of a lattice unit;
// the spline is C^1 across pieces, so a point a rounding error past a face sees the same value), its
// BB-coefficients are the exact integer combinations of the 19 coefficients (taken from fcc_cubic_*
// applied to unit samples) summed in double, and value and gradient come from the Bernstein form in
// double (the gradient by differentiating it, not through the derivative kernels the renderer uses).
//
// Near-tangent rays are told apart: a touch is an extremum of s along the ray that comes before the
// first crossing (a touch that misses) or between the first and the second crossing (a touch that
// hits), refined by golden-section search (a dip that the samples straddle but that crosses iso is
// found that way too); `tangency` is the closest touch's distance from the surface in lattice units. A small tangency means a float raycaster
// may legitimately see a hit where the reference misses, or the other way round, or a later crossing.
#pragma once

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "io/BrickStore.h"
#include "io/VdbFile.h"
#include "sparse/FccGrid.h"
#include "sparse/Lattice.h"
#include "sparse/Spline.h"
#include "viewer/Camera.h"

namespace fcc::test {

struct ReferenceRay {
  bool hit = false;
  double t = std::numeric_limits<double>::infinity();  // world distance along the unit world ray
  glm::dvec3 normal{0.0};                              // unit gradient direction, world space
  double gradientLattice = 0.0;  // |grad s| per lattice unit at the hit
  // The closest touch before the first crossing or inside the first crossing's interval: its
  // distance from the surface in lattice units (|s - iso| / (|grad s| + 1e-3 local coefficient
  // scale); +inf if none), |s - iso| there, and where along the ray (world distance).
  double tangency = std::numeric_limits<double>::infinity();
  double tangencyValue = std::numeric_limits<double>::infinity();
  double tangencyT = std::numeric_limits<double>::infinity();
  long evaluations = 0;
};

class ReferenceRayCaster {
 public:
  // Reads the FCC grid of `path` fully (coefficients, as `fccvdb synth`/`convert` write them).
  ReferenceRayCaster(const std::string& path, double iso, double stepLattice = 1.0 / 32.0)
      : iso_(iso), step_(stepLattice) {
    initializeVdb();
    const FccGrid::Ptr grid = io::readFccGrid(path);
    indexFromWorld_ = glm::inverse(io::BrickStore(path).worldFromIndex());  // as the renderer maps rays

    openvdb::CoordBBox leaves;
    grid->tree().evalLeafBoundingBox(leaves);
    const int margin = 8;
    lo_ = 2 * glm::ivec3(leaves.min().x(), leaves.min().y(), leaves.min().z()) - margin;
    dims_ = 2 * glm::ivec3(leaves.max().x() + 1, leaves.max().y() + 1, leaves.max().z() + 1) + margin - lo_;
    // Rays are clipped to where every stencil stays inside the array; beyond it the spline is the
    // background (the stored sites end `margin` sites further in).
    boxLo_ = glm::dvec3(lo_ + 4);
    boxHi_ = glm::dvec3(lo_ + dims_ - 4);
    coefficients_.assign(std::size_t(dims_.x) * dims_.y * dims_.z, 0.0f);
    tbb::parallel_for(0, dims_.z, [&](int z) {
      const FccGrid::ConstAccessor a = grid->getConstAccessor();
      for (int y = 0; y < dims_.y; ++y)
        for (int x = 0; x < dims_.x; ++x) {
          const glm::ivec3 ijk = lo_ + glm::ivec3(x, y, z);
          if (!spline::isFccSite(ijk)) continue;
          const glm::ivec3 v = packedVoxelOfSite(ijk);
          coefficients_[index(ijk)] = a.getValue(openvdb::Coord(v.x, v.y, v.z))[channelOfSite(ijk)];
        }
    });
    buildBounds();
    buildWeights();
  }

  double iso() const { return iso_; }
  const glm::dmat4& indexFromWorld() const { return indexFromWorld_; }

  // s(xyz) - iso and its gradient (index space) at xyz in the lattice's index space, in double.
  double value(const glm::dvec3& xyz, glm::dvec3* gradient = nullptr) const {
    const Piece piece = pieceAt(xyz);
    return evaluate(piece, xyz, gradient);
  }

  // The reference for the ray from `eyeWorld` along the unit world direction `dirWorld`.
  ReferenceRay cast(const glm::dvec3& eyeWorld, const glm::dvec3& dirWorld) const {
    ReferenceRay out;
    const glm::dvec3 o = glm::dvec3(indexFromWorld_ * glm::dvec4(eyeWorld, 1.0));
    const glm::dvec3 d = glm::dmat3(indexFromWorld_) * dirWorld;
    const double latticePerT = glm::length(d);
    double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      if (d[a] == 0.0) {
        if (o[a] < boxLo_[a] || o[a] > boxHi_[a]) return out;
        continue;
      }
      double ta = (boxLo_[a] - o[a]) / d[a], tb = (boxHi_[a] - o[a]) / d[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    if (!(t0 < t1)) return out;
    const double h = step_ / latticePerT;
    // Past the first crossing, how far to look for the second (the end of a touch that hits).
    const double insideReach = 4.0 / latticePerT;
    Piece cache;
    auto g = [&](double t, glm::dvec3* grad = nullptr) {
      const glm::dvec3 p = o + t * d;
      if (!cache.contains(p)) cache = pieceAt(p);
      ++out.evaluations;
      return evaluate(cache, p, grad);
    };
    // The sign of s - iso at t, from the per-voxel bounds where they exclude iso (value then NaN).
    struct Sample {
      double t, g;
      bool neg;
    };
    auto sample = [&](double t) {
      const glm::dvec3 p = o + t * d;
      const glm::ivec3 v = glm::ivec3(glm::floor(p * 0.5)) - (lo_ >> 1);
      const glm::vec2 b = bounds_[(std::size_t(v.z) * bdims_.y + v.y) * bdims_.x + v.x];
      const double slack = 1e-6 * (1.0 + std::abs(iso_));
      if (b.x - iso_ > slack) return Sample{t, std::numeric_limits<double>::quiet_NaN(), false};
      if (iso_ - b.y > slack) return Sample{t, std::numeric_limits<double>::quiet_NaN(), true};
      const double v0 = g(t);
      return Sample{t, v0, v0 < 0.0};
    };
    auto bisect = [&](double a, bool aNeg, double b) {
      for (int it = 0; it < 64 && b - a > 1e-13 * (1.0 + std::abs(b)); ++it) {
        const double m = 0.5 * (a + b);
        if ((g(m) < 0.0) == aNeg) a = m;
        else b = m;
      }
      return 0.5 * (a + b);
    };
    // Extremum of sign * g on [a, b] (minimum of |g| for a dip towards iso): golden section.
    auto extremum = [&](double a, double b, double sign, double& tExt) {
      const double r = 0.5 * (std::sqrt(5.0) - 1.0);
      double x1 = b - r * (b - a), x2 = a + r * (b - a);
      double f1 = sign * g(x1), f2 = sign * g(x2);
      for (int it = 0; it < 48; ++it) {
        if (f1 < f2) {
          b = x2;
          x2 = x1;
          f2 = f1;
          x1 = b - r * (b - a);
          f1 = sign * g(x1);
        } else {
          a = x1;
          x1 = x2;
          f1 = f2;
          x2 = a + r * (b - a);
          f2 = sign * g(x2);
        }
      }
      tExt = 0.5 * (a + b);
      return sign * g(tExt);
    };
    // A touch with |s - iso| = value at t, in lattice units: how far the surface is from the ray there,
    // value / |grad s|, with value rounding of 1e-6 of the local coefficients counted as 1e-3 units.
    auto touch = [&](double value, double t) {
      glm::dvec3 grad;
      g(t, &grad);
      double scale = 0.0;
      for (double b : cache.b) scale = std::max(scale, std::abs(b));
      const double distance = std::abs(value) / (glm::length(grad) + 1e-3 * scale);
      if (distance < out.tangency) {
        out.tangency = distance;
        out.tangencyValue = std::abs(value);
        out.tangencyT = t;
      }
    };
    auto exact = [&](Sample& x) {
      if (std::isnan(x.g)) x.g = g(x.t);
    };
    double tHit = 0.0, insideMax = 0.0, insideMaxT = 0.0;
    bool inside = false;  // between the first crossing and the second
    // A crossing at tRoot; returns true at the second (the end of the first crossing's interval).
    auto crossing = [&](double tRoot) {
      if (!inside) {
        inside = true;
        tHit = tRoot;
        insideMax = 0.0;
        insideMaxT = tRoot;
        return false;
      }
      touch(insideMax, insideMaxT);
      return true;
    };
    Sample s2{0, 0, false}, s1{0, 0, false};
    const long steps = long(std::ceil((t1 - t0) / h));
    for (long k = 0; k <= steps; ++k) {
      Sample s0 = sample(std::min(t0 + double(k) * h, t1));
      bool done = false;
      // Beside an evaluated sample, its neighbours are evaluated too (for the extremum test).
      if (k >= 1 && !std::isnan(s1.g)) exact(s0);
      if (k >= 2 && !std::isnan(s1.g)) exact(s2);
      // A local minimum of |g| at s1 with s2, s1, s0 on one side of iso: a touch, or a dip between
      // samples that crosses iso (twice).
      if (k >= 2 && !std::isnan(s1.g) && s2.neg == s1.neg && s1.neg == s0.neg && std::abs(s1.g) <= std::abs(s2.g) &&
          std::abs(s1.g) <= std::abs(s0.g)) {
        const double sign = s1.neg ? -1.0 : 1.0;
        double tExt = s1.t;
        const double ext = extremum(s2.t, s0.t, sign, tExt);
        if (ext > 0.0) {
          if (!inside) touch(ext, tExt);
        } else if (!inside) {
          crossing(bisect(s2.t, s2.neg, tExt));
          insideMax = -ext;
          insideMaxT = tExt;
          done = crossing(bisect(tExt, !s2.neg, s0.t));
        } else {
          done = crossing(bisect(s2.t, s2.neg, tExt));
        }
      }
      if (!done && k >= 1 && s1.neg != s0.neg) done = crossing(bisect(s1.t, s1.neg, s0.t));
      if (done || (inside && s0.t > tHit + insideReach)) break;
      if (inside) {
        if (std::isnan(s0.g)) insideMax = std::numeric_limits<double>::infinity();
        else if (std::abs(s0.g) > insideMax) insideMax = std::abs(s0.g), insideMaxT = s0.t;
      }
      s2 = s1;
      s1 = s0;
    }
    if (inside) {
      out.hit = true;
      out.t = tHit;
      glm::dvec3 grad;
      g(tHit, &grad);
      out.gradientLattice = glm::length(grad);
      // World gradient: transpose of the linear part of indexFromWorld applied to the index gradient.
      const glm::dvec3 nWorld = glm::transpose(glm::dmat3(indexFromWorld_)) * grad;
      out.normal = glm::length(nWorld) > 0.0 ? glm::normalize(nWorld) : glm::dvec3(0.0);
    }
    return out;
  }

 private:
  struct Piece {
    glm::ivec3 origin{0}, axis{0};
    int type = -1;
    glm::dvec3 cellLo{1.0}, cellHi{0.0};  // the unit cube of the point it was located for
    double b[20] = {};                     // BB-coefficients, true scale
    // Reuse for points in the same unit cube and piece (the piece test in double).
    bool contains(const glm::dvec3& p) const {
      if (type < 0 || glm::any(glm::lessThan(p, cellLo)) || glm::any(glm::greaterThanEqual(p, cellHi))) return false;
      const glm::dvec3 q = glm::dvec3(axis) * (p - glm::dvec3(origin));
      if (type == 0) return q.x + q.y + q.z <= 1.0 && q.x >= 0.0 && q.y >= 0.0 && q.z >= 0.0;
      const double l3 = 0.5 * (q.x + q.y + q.z - 1.0);
      return l3 >= 0.0 && q.x >= l3 && q.y >= l3 && q.z >= l3;
    }
  };

  std::size_t index(const glm::ivec3& ijk) const {
    const glm::ivec3 l = ijk - lo_;
    return (std::size_t(l.z) * dims_.y + l.y) * dims_.x + l.x;
  }

  // Per packed voxel: min and max of the coefficients of sites [2v - 2, 2v + 4)^3, which bound the
  // spline on the voxel's eight unit cells (M_fcc >= 0, partition of unity).
  void buildBounds() {
    bdims_ = dims_ / 2;
    const std::size_t n = std::size_t(bdims_.x) * bdims_.y * bdims_.z;
    bounds_.assign(n, glm::vec2(0.0f));
    auto at = [&](int x, int y, int z) -> glm::vec2& { return bounds_[(std::size_t(z) * bdims_.y + y) * bdims_.x + x]; };
    for (int z = 0; z < bdims_.z; ++z)
      for (int y = 0; y < bdims_.y; ++y)
        for (int x = 0; x < bdims_.x; ++x) {
          float mn = std::numeric_limits<float>::infinity(), mx = -mn;
          for (int c = 0; c < 8; ++c) {
            const glm::ivec3 ijk = lo_ + 2 * glm::ivec3(x, y, z) + glm::ivec3(c & 1, (c >> 1) & 1, c >> 2);
            if (!spline::isFccSite(ijk)) continue;
            mn = std::min(mn, coefficients_[index(ijk)]);
            mx = std::max(mx, coefficients_[index(ijk)]);
          }
          at(x, y, z) = glm::vec2(mn, mx);
        }
    // Dilate by one packed voxel along each axis in turn.
    for (int axis = 0; axis < 3; ++axis) {
      const std::vector<glm::vec2> src = bounds_;
      for (int z = 0; z < bdims_.z; ++z)
        for (int y = 0; y < bdims_.y; ++y)
          for (int x = 0; x < bdims_.x; ++x) {
            glm::ivec3 c(x, y, z);
            glm::vec2 b = src[(std::size_t(z) * bdims_.y + y) * bdims_.x + x];
            for (int s = -1; s <= 1; s += 2) {
              glm::ivec3 nb = c;
              nb[axis] += s;
              if (nb[axis] < 0 || nb[axis] >= bdims_[axis]) continue;
              const glm::vec2 o = src[(std::size_t(nb.z) * bdims_.y + nb.y) * bdims_.x + nb.x];
              b = glm::vec2(std::min(b.x, o.x), std::max(b.y, o.y));
            }
            at(x, y, z) = b;
          }
    }
  }

  // The integer weights of the BB-coefficients of each piece type in the 19 stencil coefficients.
  void buildWeights() {
    for (int t = 0; t < 2; ++t)
      for (int i = 0; i < FCC_STENCIL_SIZE; ++i) {
        spline::FccSamples unit{};
        unit.v[i] = 1.0f;
        const spline::FccCubic c = spline::fcc_cubic(unit, t == 0 ? 0 : 4);
        for (int n = 0; n < 20; ++n) weights_[t][n][i] = double(c.b[n]) / double(FCC_CUBIC_DENOM);
      }
    // Multi-indices (i, j, k, l) of the BB order (sparse/FccSplineTables.h) and their multinomials.
    int n = 0;
    for (int i = 3; i >= 0; --i)
      for (int j = 3 - i; j >= 0; --j)
        for (int k = 3 - i - j; k >= 0; --k) {
          exps_[n] = glm::ivec4(i, j, k, 3 - i - j - k);
          const int f[4] = {1, 1, 2, 6};
          multinomial_[n] = 6.0 / (f[i] * f[j] * f[k] * f[3 - i - j - k]);
          ++n;
        }
  }

  Piece pieceAt(const glm::dvec3& xyz) const {
    // Locate relative to an even cube near xyz, so that the float coordinates fcc_locate sees are small.
    glm::ivec3 base(glm::floor(xyz));
    if (!spline::isFccSite(base)) base.x -= 1;
    const spline::FccFrame f = spline::fcc_locate(glm::vec3(xyz - glm::dvec3(base)));
    Piece p;
    p.origin = f.origin + base;
    p.axis = f.axis;
    p.type = f.type;
    p.cellLo = glm::floor(xyz);
    p.cellHi = p.cellLo + 1.0;
    double c[FCC_STENCIL_SIZE];
    for (int i = 0; i < FCC_STENCIL_SIZE; ++i) {
      const glm::ivec3 site =
          p.origin + p.axis * glm::ivec3(spline::fcc_stencil_dx[i], spline::fcc_stencil_dy[i], spline::fcc_stencil_dz[i]);
      const glm::ivec3 l = site - lo_;
      c[i] = glm::all(glm::greaterThanEqual(l, glm::ivec3(0))) && glm::all(glm::lessThan(l, dims_))
                 ? double(coefficients_[index(site)])
                 : std::numeric_limits<double>::quiet_NaN();
    }
    const int t = p.type == 0 ? 0 : 1;
    for (int n = 0; n < 20; ++n) {
      double b = 0.0;
      for (int i = 0; i < FCC_STENCIL_SIZE; ++i)
        if (weights_[t][n][i] != 0.0) b += weights_[t][n][i] * c[i];
      p.b[n] = b;
    }
    return p;
  }

  // s(xyz) - iso on `piece` (its polynomial, also a little outside it), and optionally the gradient.
  double evaluate(const Piece& piece, const glm::dvec3& xyz, glm::dvec3* gradient) const {
    const glm::dvec3 q = glm::dvec3(piece.axis) * (xyz - glm::dvec3(piece.origin));
    double l[4];
    if (piece.type == 0) {
      l[0] = 1.0 - q.x - q.y - q.z, l[1] = q.x, l[2] = q.y, l[3] = q.z;
    } else {
      const double l3 = 0.5 * (q.x + q.y + q.z - 1.0);
      l[0] = q.x - l3, l[1] = q.y - l3, l[2] = q.z - l3, l[3] = l3;
    }
    double pw[4][4];
    for (int m = 0; m < 4; ++m) {
      pw[m][0] = 1.0;
      for (int e = 1; e < 4; ++e) pw[m][e] = pw[m][e - 1] * l[m];
    }
    double value = 0.0, dl[4] = {0.0, 0.0, 0.0, 0.0};
    for (int n = 0; n < 20; ++n) {
      const glm::ivec4 e = exps_[n];
      const double w = piece.b[n] * multinomial_[n];
      value += w * pw[0][e.x] * pw[1][e.y] * pw[2][e.z] * pw[3][e.w];
      if (gradient) {
        if (e.x) dl[0] += w * e.x * pw[0][e.x - 1] * pw[1][e.y] * pw[2][e.z] * pw[3][e.w];
        if (e.y) dl[1] += w * e.y * pw[0][e.x] * pw[1][e.y - 1] * pw[2][e.z] * pw[3][e.w];
        if (e.z) dl[2] += w * e.z * pw[0][e.x] * pw[1][e.y] * pw[2][e.z - 1] * pw[3][e.w];
        if (e.w) dl[3] += w * e.w * pw[0][e.x] * pw[1][e.y] * pw[2][e.z] * pw[3][e.w - 1];
      }
    }
    if (gradient) {
      // d lambda / d q: type 0 (-1,-1,-1), e_x, e_y, e_z; type 4: e_a - (1/2)(1,1,1) for a < 3, (1/2)(1,1,1).
      glm::dvec3 gq;
      if (piece.type == 0) gq = glm::dvec3(dl[1] - dl[0], dl[2] - dl[0], dl[3] - dl[0]);
      else {
        const double common = 0.5 * (dl[3] - dl[0] - dl[1] - dl[2]);
        gq = glm::dvec3(dl[0], dl[1], dl[2]) + common;
      }
      *gradient = gq * glm::dvec3(piece.axis);
    }
    return value - iso_;
  }

  double iso_, step_;
  glm::dmat4 indexFromWorld_{1.0};
  glm::ivec3 lo_{0}, dims_{0}, bdims_{0};
  glm::dvec3 boxLo_{0.0}, boxHi_{0.0};
  std::vector<float> coefficients_;
  std::vector<glm::vec2> bounds_;
  double weights_[2][20][FCC_STENCIL_SIZE] = {};
  glm::ivec4 exps_[20];
  double multinomial_[20] = {};
};

}  // namespace fcc::test
