#include "ReferenceRaycast.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

namespace fcc {
namespace {

constexpr int kReach = 3;

// Bernstein coefficients from values at u = k / n, k = 0..n: the inverse of B(i, j) = B^n_j(i / n),
// computed once per degree in double.
struct BernsteinFromValues {
  std::array<std::array<std::array<double, 10>, 10>, 10> inverse{};
  BernsteinFromValues() {
    for (int n = 1; n <= 9; ++n) {
      double a[10][20] = {};
      for (int i = 0; i <= n; ++i) {
        const double u = double(i) / n;
        for (int j = 0; j <= n; ++j) {
          double binom = 1.0;
          for (int k = 1; k <= j; ++k) binom = binom * (n - j + k) / k;
          a[i][j] = binom * std::pow(u, j) * std::pow(1.0 - u, n - j);
        }
        a[i][n + 1 + i] = 1.0;
      }
      // Gauss-Jordan with partial pivoting.
      for (int c = 0; c <= n; ++c) {
        int p = c;
        for (int r = c + 1; r <= n; ++r)
          if (std::abs(a[r][c]) > std::abs(a[p][c])) p = r;
        for (int k = 0; k < 2 * (n + 1); ++k) std::swap(a[c][k], a[p][k]);
        const double pivot = a[c][c];
        for (int k = 0; k < 2 * (n + 1); ++k) a[c][k] /= pivot;
        for (int r = 0; r <= n; ++r) {
          if (r == c) continue;
          const double f = a[r][c];
          for (int k = 0; k < 2 * (n + 1); ++k) a[r][k] -= f * a[c][k];
        }
      }
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) inverse[n][i][j] = a[i][n + 1 + j];
    }
  }
};

const BernsteinFromValues& bernsteinFromValues() {
  static const BernsteinFromValues table;
  return table;
}

}  // namespace

CellBounds::CellBounds(const LatticeSamples& samples)
    : min_(samples.origin()), dims_(samples.dims()), background_(samples.at(samples.origin() - 1000)) {
  // Separable running min/max over [c - kReach, c + 1 + kReach] per axis.
  const size_t n = size_t(dims_.x) * dims_.y * dims_.z;
  std::vector<glm::vec2> a(n), b(n);
  auto index = [&](int x, int y, int z) { return (size_t(z) * dims_.y + y) * dims_.x + x; };
  for (int z = 0; z < dims_.z; ++z)
    for (int y = 0; y < dims_.y; ++y)
      for (int x = 0; x < dims_.x; ++x) {
        const glm::ivec3 ijk = min_ + glm::ivec3(x, y, z);
        const float v = isLatticeSite(samples.lattice(), ijk) ? samples.at(ijk) : std::numeric_limits<float>::quiet_NaN();
        a[index(x, y, z)] = std::isnan(v) ? glm::vec2(std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity())
                                          : glm::vec2(v, v);
      }
  auto pass = [&](const std::vector<glm::vec2>& in, std::vector<glm::vec2>& out, int axis) {
    tbb::parallel_for(0, dims_.z, [&](int z) {
      for (int y = 0; y < dims_.y; ++y)
        for (int x = 0; x < dims_.x; ++x) {
          glm::ivec3 p(x, y, z);
          glm::vec2 r(std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity());
          bool outside = false;
          for (int k = -kReach; k <= kReach + 1; ++k) {
            glm::ivec3 q = p;
            q[axis] += k;
            if (q[axis] < 0 || q[axis] >= dims_[axis]) {
              outside = true;
              continue;
            }
            const glm::vec2 v = in[index(q.x, q.y, q.z)];
            r = glm::vec2(std::min(r.x, v.x), std::max(r.y, v.y));
          }
          if (outside) r = glm::vec2(std::min(r.x, background_), std::max(r.y, background_));
          out[index(x, y, z)] = r;
        }
    });
  };
  pass(a, b, 0);
  pass(b, a, 1);
  pass(a, b, 2);
  ranges_.swap(b);
}

glm::vec2 CellBounds::at(const glm::ivec3& cell) const {
  const glm::ivec3 r = cell - min_;
  if (r.x < 0 || r.y < 0 || r.z < 0 || r.x >= dims_.x || r.y >= dims_.y || r.z >= dims_.z)
    return glm::vec2(background_);
  return ranges_[(size_t(r.z) * dims_.y + r.y) * dims_.x + r.x];
}

RayHit firstHit(const Reconstruction& recon, const SiteValue& at, const CellBounds& bounds, const glm::vec3& o,
                const glm::vec3& dIn, float t0, float t1, float iso) {
  RayHit result;
  const int degree = std::max(1, recon.info().rayDegree);
  const auto& inverse = bernsteinFromValues().inverse[degree];
  glm::vec3 d = dIn;
  for (int i = 0; i < 3; ++i)
    if (std::abs(d[i]) < 1e-20f) d[i] = 1e-20f;
  const glm::vec3 invD = 1.0f / d;
  glm::ivec3 cell(glm::floor(o + t0 * d));
  const glm::ivec3 step(glm::sign(d));
  glm::vec3 tMax = (glm::vec3(cell) + glm::vec3(glm::greaterThan(d, glm::vec3(0.0f))) - o) * invD;
  const glm::vec3 tDelta = glm::abs(invD);
  float tCell = t0;
  int prevSign = 0;
  for (int guard = 0; guard < 1 << 20 && tCell < t1; ++guard) {
    const float tExit = std::min(std::min(std::min(tMax.x, tMax.y), tMax.z), t1);
    const glm::vec2 range = bounds.at(cell);
    if (tExit > tCell) {
      if (!(range.x <= iso && iso <= range.y)) {
        prevSign = range.x > iso ? 1 : -1;
      } else {
        const spline::FccSplits splits = recon.cellSplits(cell, o, d, tCell, tExit);
        float s0 = tCell;
        for (int k = 0; k <= splits.n; ++k) {
          const float s1 = k < splits.n ? splits.t[k] : tExit;
          if (s1 <= s0) continue;
          const glm::vec3 mid = o + (0.5f * (s0 + s1)) * d;
          double values[10];
          for (int i = 0; i <= degree; ++i)
            values[i] = recon.evaluateInPiece(mid, o + (s0 + (s1 - s0) * float(i) / degree) * d, at).value - iso;
          spline::FccBernstein9 b;
          b.n = degree;
          for (int i = 0; i <= degree; ++i) {
            double sum = 0.0;
            for (int j = 0; j <= degree; ++j) sum += inverse[i][j] * values[j];
            b.b[i] = float(sum);
          }
          // A sign change at the join with the previous piece (a discontinuity, or a root at the join
          // rounded differently by the two pieces) is a hit at its start.
          float u = (prevSign != 0 && (b.b[0] < 0.0f ? -1 : 1) != prevSign) ? 0.0f : spline::fcc_first_root_bernstein9(b);
          if (u >= 0.0f) {
            result.hit = true;
            result.t = s0 + u * (s1 - s0);
            result.gradient = recon.evaluateInPiece(mid, o + result.t * d, at).gradient;
            return result;
          }
          prevSign = b.b[degree] < 0.0f ? -1 : 1;
          s0 = s1;
        }
      }
    }
    if (tExit >= t1) break;
    tCell = std::max(tCell, tExit);
    if (tMax.x <= tMax.y && tMax.x <= tMax.z) {
      cell.x += step.x;
      tMax.x += tDelta.x;
    } else if (tMax.y <= tMax.z) {
      cell.y += step.y;
      tMax.y += tDelta.y;
    } else {
      cell.z += step.z;
      tMax.z += tDelta.z;
    }
  }
  return result;
}

std::vector<SurfaceCrossing> surfaceCrossings(const Reconstruction& recon, const SiteValue& at, const CellBounds* bounds,
                                              const glm::vec3& o, const glm::vec3& dIn, float t0, float t1,
                                              const std::vector<float>& isos, std::size_t maxCrossings) {
  std::vector<SurfaceCrossing> out;
  const int degree = std::max(1, recon.info().rayDegree);
  const auto& inverse = bernsteinFromValues().inverse[degree];
  const std::size_t surfaces = isos.size();
  glm::vec3 d = dIn;
  for (int i = 0; i < 3; ++i)
    if (std::abs(d[i]) < 1e-20f) d[i] = 1e-20f;
  const glm::vec3 invD = 1.0f / d;
  glm::ivec3 cell(glm::floor(o + t0 * d));
  const glm::ivec3 step(glm::sign(d));
  glm::vec3 tMax = (glm::vec3(cell) + glm::vec3(glm::greaterThan(d, glm::vec3(0.0f))) - o) * invD;
  const glm::vec3 tDelta = glm::abs(invD);
  float tCell = t0;
  std::vector<int> side(surfaces, 0);  // per surface: -1 below, +1 not, 0 unknown
  const auto sideOf = [](double v) { return v < 0.0 ? -1 : 1; };
  // de Casteljau in double.
  const auto valueAt = [degree](const double* b, double u) {
    double r[10];
    std::copy(b, b + degree + 1, r);
    for (int level = 1; level <= degree; ++level)
      for (int i = 0; i <= degree - level; ++i) r[i] = r[i] + u * (r[i + 1] - r[i]);
    return r[0];
  };
  constexpr int kSamples = 64;
  for (int guard = 0; guard < 1 << 20 && tCell < t1 && out.size() < maxCrossings; ++guard) {
    const float tExit = std::min(std::min(std::min(tMax.x, tMax.y), tMax.z), t1);
    if (tExit > tCell) {
      const glm::vec2 range = bounds ? bounds->at(cell) : glm::vec2(-INFINITY, INFINITY);
      bool any = false;
      for (std::size_t k = 0; k < surfaces; ++k) {
        if (range.x <= isos[k] && isos[k] <= range.y) any = true;
        else side[k] = range.x > isos[k] ? 1 : -1;
      }
      if (any) {
        const spline::FccSplits splits = recon.cellSplits(cell, o, d, tCell, tExit);
        float s0 = tCell;
        for (int piece = 0; piece <= splits.n; ++piece) {
          const float s1 = piece < splits.n ? splits.t[piece] : tExit;
          if (s1 <= s0) continue;
          const glm::vec3 mid = o + (0.5f * (s0 + s1)) * d;
          double values[10], value[10];
          for (int i = 0; i <= degree; ++i)
            values[i] = recon.evaluateInPiece(mid, o + (s0 + (s1 - s0) * float(i) / degree) * d, at).value;
          for (int i = 0; i <= degree; ++i) {
            double sum = 0.0;
            for (int j = 0; j <= degree; ++j) sum += inverse[i][j] * values[j];
            value[i] = sum;
          }
          std::vector<SurfaceCrossing> found;
          for (std::size_t k = 0; k < surfaces; ++k) {
            if (!(range.x <= isos[k] && isos[k] <= range.y)) continue;
            double b[10];
            for (int i = 0; i <= degree; ++i) b[i] = value[i] - isos[k];
            const auto add = [&](double u) {
              SurfaceCrossing c;
              c.t = float(double(s0) + u * double(s1 - s0));
              c.surface = int(k);
              c.gradient = recon.evaluateInPiece(mid, o + c.t * d, at).gradient;
              found.push_back(c);
            };
            double ua = 0.0, ga = b[0];
            if (side[k] != 0 && sideOf(ga) != side[k]) add(0.0);
            for (int j = 1; j <= kSamples; ++j) {
              const double ub = double(j) / kSamples, gb = j == kSamples ? b[degree] : valueAt(b, ub);
              if (sideOf(gb) != sideOf(ga)) {
                double lo = ua, hi = ub;
                for (int it = 0; it < 60; ++it) {
                  const double m = 0.5 * (lo + hi);
                  if (sideOf(valueAt(b, m)) == sideOf(ga)) lo = m;
                  else hi = m;
                }
                add(0.5 * (lo + hi));
              }
              ua = ub;
              ga = gb;
            }
            side[k] = sideOf(b[degree]);
          }
          std::sort(found.begin(), found.end(), [](const SurfaceCrossing& a, const SurfaceCrossing& b) { return a.t < b.t; });
          out.insert(out.end(), found.begin(), found.end());
          s0 = s1;
        }
      }
    }
    if (tExit >= t1) break;
    tCell = std::max(tCell, tExit);
    if (tMax.x <= tMax.y && tMax.x <= tMax.z) {
      cell.x += step.x;
      tMax.x += tDelta.x;
    } else if (tMax.y <= tMax.z) {
      cell.y += step.y;
      tMax.y += tDelta.y;
    } else {
      cell.z += step.z;
      tMax.z += tDelta.z;
    }
  }
  if (out.size() > maxCrossings) out.resize(maxCrossings);
  return out;
}

SurfacePixel compositeCrossings(const std::vector<SurfaceCrossing>& crossings, const std::vector<SurfaceLook>& looks,
                                const glm::dmat3& normalFromIndex, const glm::dvec3& dirWorld,
                                const glm::dvec3& lightWorld, double stopTransmittance) {
  SurfacePixel px;
  glm::dvec3 color(0.0);
  double transmittance = 1.0;
  for (const SurfaceCrossing& c : crossings) {
    glm::dvec3 n = normalFromIndex * glm::dvec3(c.gradient);
    n = glm::length(n) > 0.0 ? glm::normalize(n) : -dirWorld;
    const glm::dvec3 facing = glm::dot(n, dirWorld) > 0.0 ? -n : n;
    const double diffuse = std::max(glm::dot(facing, lightWorld), 0.0);
    const SurfaceLook& look = looks.at(std::size_t(c.surface));
    color += transmittance * look.opacity * look.color * (0.15 + 0.85 * diffuse);
    transmittance *= 1.0 - look.opacity;
    if (std::isinf(px.depth)) {
      px.depth = c.t;
      px.normal = n;
    }
    if (transmittance <= stopTransmittance) break;
  }
  px.rgba = glm::dvec4(color, 1.0 - transmittance);
  return px;
}

WorldHit firstHitAnalytic(const AnalyticField& field, const glm::dvec3& o, const glm::dvec3& d, double t0, double t1,
                          double iso, double step) {
  WorldHit result;
  double ta = t0, fa = field.value(o + t0 * d) - iso;
  // At most 2^20 steps a ray: a step too short to advance t (a degenerate spacing) ends the walk.
  for (int n = 0; ta < t1 && n < (1 << 20); ++n) {
    const double tb = std::min(ta + step, t1);
    if (!(tb > ta)) break;
    const double fb = field.value(o + tb * d) - iso;
    if (fa == 0.0 || (fa < 0.0) != (fb < 0.0)) {
      double lo = ta, hi = tb;
      for (int i = 0; i < 60 && fa != 0.0; ++i) {
        const double mid = 0.5 * (lo + hi);
        const double fm = field.value(o + mid * d) - iso;
        if ((fm < 0.0) == (fa < 0.0)) lo = mid;
        else hi = mid;
      }
      result.hit = true;
      result.t = fa == 0.0 ? ta : 0.5 * (lo + hi);
      result.gradient = field.gradient(o + result.t * d);
      return result;
    }
    ta = tb;
    fa = fb;
  }
  return result;
}

}  // namespace fcc
