#include "Comparison.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "CubicBSpline.h"
#include "Error.h"
#include "LatticeSamples.h"
#include "ReferenceRaycast.h"

namespace fcc {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Index units of samples kept beyond the domain: the widest stencil reach (2) plus the B-spline
// prefilter's reach, so the prefilter's mirrored boundary is below float precision inside.
constexpr int kPad = 2 + kBSplinePrefilterReach + 1;

double angleDeg(const glm::dvec3& a, const glm::dvec3& b) {
  const double la = glm::length(a), lb = glm::length(b);
  if (la == 0.0 || lb == 0.0) return 180.0;  // a vanished gradient has no direction: the worst error
  return std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0)) * 180.0 / kPi;
}

struct AngleStats {
  double mean = 0.0, p95 = 0.0, max = 0.0;
};
// Angles < 0 are points left out (no true gradient there). No points: NaN (JSON null), not 0.
AngleStats statsOf(std::vector<double> angles) {
  angles.erase(std::remove_if(angles.begin(), angles.end(), [](double a) { return a < 0.0; }), angles.end());
  AngleStats s;
  if (angles.empty()) return {NAN, NAN, NAN};
  std::sort(angles.begin(), angles.end());
  for (double a : angles) s.mean += a;
  s.mean /= double(angles.size());
  s.p95 = angles[std::min(angles.size() - 1, size_t(std::ceil(0.95 * double(angles.size()))) - 1)];
  s.max = angles.back();
  return s;
}

std::vector<glm::dvec3> uniformPoints(int count, uint64_t seed, const glm::dvec3& halfExtent) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<glm::dvec3> points(static_cast<size_t>(count));
  for (auto& p : points) p = halfExtent * glm::dvec3(u(rng), u(rng), u(rng));
  return points;
}

struct PixelRay {
  glm::dvec3 o, d;
  double t0 = 0.0, t1 = -1.0;  // inside [-1, 1]^3; empty when t1 < t0
};

PixelRay cameraRay(const CompareCamera& cam, const glm::dvec3& halfExtent, int x, int y, int width, int height) {
  const glm::dvec3 forward = glm::normalize(cam.lookAt - cam.eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, cam.up));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tanHalf = std::tan(cam.fovDeg * kPi / 360.0), aspect = double(width) / height;
  const double nx = (x + 0.5) / width * 2.0 - 1.0, ny = (y + 0.5) / height * 2.0 - 1.0;
  PixelRay ray;
  ray.o = cam.eye;
  ray.d = glm::normalize(forward + nx * tanHalf * aspect * right - ny * tanHalf * up);
  const glm::dvec3 inv = 1.0 / ray.d;
  const glm::dvec3 ta = (-halfExtent - ray.o) * inv, tb = (halfExtent - ray.o) * inv;
  const glm::dvec3 lo = glm::min(ta, tb), hi = glm::max(ta, tb);
  ray.t0 = std::max(0.0, std::max(std::max(lo.x, lo.y), lo.z));
  ray.t1 = std::min(std::min(hi.x, hi.y), hi.z);
  return ray;
}

const glm::vec3 kBackground(0.12f, 0.12f, 0.14f);

void putPixel(RgbImage& image, int x, int y, const glm::vec3& c) {
  const size_t i = (size_t(y) * image.width + x) * 3;
  for (int k = 0; k < 3; ++k) image.rgb[i + k] = (unsigned char)std::lround(255.0f * std::clamp(c[k], 0.0f, 1.0f));
}

RgbImage blankImage(int width, int height) {
  RgbImage image{width, height, std::vector<unsigned char>(size_t(width) * height * 3)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) putPixel(image, x, y, kBackground);
  return image;
}

// Two-sided Lambert, lit from the eye.
glm::vec3 shade(const glm::dvec3& normal, const glm::dvec3& d) {
  const double len = glm::length(normal);
  const double lambert = len > 0.0 ? std::abs(glm::dot(normal / len, d)) : 0.0;
  return glm::vec3(0.9f, 0.75f, 0.5f) * float(0.15 + 0.85 * lambert);
}

// 0 degrees dark blue, through cyan and yellow, to red at 20 degrees and beyond.
glm::vec3 heat(double angleDeg) {
  const float t = float(std::clamp(angleDeg / 20.0, 0.0, 1.0));
  const glm::vec3 stops[4] = {{0.05f, 0.05f, 0.45f}, {0.0f, 0.8f, 0.9f}, {1.0f, 0.9f, 0.1f}, {0.9f, 0.05f, 0.05f}};
  const float s = t * 3.0f;
  const int i = std::min(2, int(s));
  return glm::mix(stops[i], stops[i + 1], s - float(i));
}

struct TruthRender {
  int width = 0, height = 0;
  std::vector<WorldHit> hits;
};

TruthRender renderTruthHits(const AnalyticField& field, double iso, int width, int height) {
  TruthRender truth{width, height, std::vector<WorldHit>(size_t(width) * height)};
  const glm::dvec3 e = field.halfExtent();
  const CompareCamera cam(e);
  const double step = field.rootSeparatingStep();
  tbb::parallel_for(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      const PixelRay ray = cameraRay(cam, e, x, y, width, height);
      if (ray.t1 > ray.t0) truth.hits[size_t(y) * width + x] = firstHitAnalytic(field, ray.o, ray.d, ray.t0, ray.t1, iso, step);
    }
  });
  return truth;
}

// Renders one method and measures it against the truth's render.
void renderAndMeasure(const Reconstruction& recon, const SiteValue& at, const CellBounds& bounds, double h, double iso,
                      const glm::dvec3& halfExtent, const TruthRender& truth, CompareRow& row, bool keepImages) {
  const int width = truth.width, height = truth.height;
  const CompareCamera cam(halfExtent);
  row.shaded = blankImage(width, height);
  row.normalError = blankImage(width, height);
  std::vector<double> angles(size_t(width) * height, -1.0), depthErrors(size_t(width) * height, -1.0);
  std::vector<char> disagree(size_t(width) * height, 0);
  tbb::parallel_for(0, height, [&](int y) {
    for (int x = 0; x < width; ++x) {
      const size_t i = size_t(y) * width + x;
      const PixelRay ray = cameraRay(cam, halfExtent, x, y, width, height);
      RayHit hit;
      if (ray.t1 > ray.t0)
        hit = firstHit(recon, at, bounds, glm::vec3(ray.o / h), glm::vec3(ray.d / h), float(ray.t0), float(ray.t1), float(iso));
      const WorldHit& t = truth.hits[i];
      if (hit.hit) putPixel(row.shaded, x, y, shade(glm::dvec3(hit.gradient), ray.d));
      if (hit.hit && t.hit) {
        angles[i] = angleDeg(glm::dvec3(hit.gradient), t.gradient);
        depthErrors[i] = std::abs(double(hit.t) - t.t);
        putPixel(row.normalError, x, y, heat(angles[i]));
      } else if (hit.hit != t.hit) {
        disagree[i] = 1;
        putPixel(row.normalError, x, y, glm::vec3(1.0f, 0.0f, 1.0f));
      }
    }
  });
  std::vector<double> both;
  double depthSum = 0.0;
  for (size_t i = 0; i < angles.size(); ++i) {
    if (angles[i] >= 0.0) {
      both.push_back(angles[i]);
      depthSum += depthErrors[i];
    }
    row.renderHitMissPixels += disagree[i];
  }
  row.renderBothHitPixels = int64_t(both.size());
  if (!both.empty()) {
    const AngleStats stats = statsOf(both);
    row.renderNormalErrorMeanDeg = stats.mean;
    row.renderNormalErrorP95Deg = stats.p95;
    row.renderDepthErrorMean = depthSum / double(both.size());
  }
  if (!keepImages) row.shaded = row.normalError = RgbImage{};
}

RgbImage truthImageOf(const TruthRender& truth, const glm::dvec3& halfExtent) {
  RgbImage image = blankImage(truth.width, truth.height);
  const CompareCamera cam(halfExtent);
  for (int y = 0; y < truth.height; ++y)
    for (int x = 0; x < truth.width; ++x) {
      const WorldHit& hit = truth.hits[size_t(y) * truth.width + x];
      if (hit.hit) putPixel(image, x, y, shade(hit.gradient, cameraRay(cam, halfExtent, x, y, truth.width, truth.height).d));
    }
  return image;
}

}  // namespace

namespace {

double worldPerIndexFor(Lattice lattice, int64_t budget, const glm::dvec3& halfExtent) {
  const double volume = 8.0 * halfExtent.x * halfExtent.y * halfExtent.z;
  return std::cbrt(volume * latticeDensity(lattice) / double(budget));
}

// Index units from the origin to the last site inside the domain, per axis.
glm::ivec3 reachFor(double worldPerIndex, const glm::dvec3& halfExtent) {
  return glm::ivec3(glm::floor(halfExtent / worldPerIndex + 1e-9));
}

glm::ivec3 boxDimsFor(const glm::ivec3& reach) { return 2 * (reach + kPad) + 1; }

double boxPoints(const glm::ivec3& dims) { return double(dims.x) * dims.y * dims.z; }

}  // namespace

LatticeSampling samplingFor(Lattice lattice, int64_t budget, const glm::dvec3& halfExtent) {
  if (budget < 64) throw ValueError("a budget must be at least 64 samples (got " + std::to_string(budget) + ")");
  LatticeSampling s;
  s.lattice = lattice;
  s.budget = budget;
  s.worldPerIndex = worldPerIndexFor(lattice, budget, halfExtent);
  const glm::ivec3 reach = reachFor(s.worldPerIndex, halfExtent);
  s.reach = reach;
  s.boxMin = -reach - kPad;
  s.boxDims = boxDimsFor(reach);
  // The box is held densely (LatticeSamples: every integer point, a float each, twice while prefiltered).
  const double points = boxPoints(s.boxDims);
  if (points > double(kMaxComparisonBoxPoints)) {
    // The largest budget whose box fits (the padding's share grows as budgets shrink), to two digits.
    double fits = double(budget) * double(kMaxComparisonBoxPoints) / points;
    while (fits > 64 && boxPoints(boxDimsFor(reachFor(worldPerIndexFor(lattice, int64_t(fits), halfExtent), halfExtent))) > double(kMaxComparisonBoxPoints))
      fits *= 0.97;
    const double unit = std::pow(10.0, std::floor(std::log10(fits)) - 1);
    fits = std::floor(fits / unit) * unit;
    throw ValueError("a budget of " + std::to_string(budget) + " samples needs " + std::to_string(int64_t(points)) +
                     " points of memory on the " + std::string(latticeName(lattice)) + " lattice (at most " +
                     std::to_string(kMaxComparisonBoxPoints) + "): use budgets up to " + std::to_string(int64_t(fits)));
  }
  int64_t inside = 0;
  for (int z = -reach.z; z <= reach.z; ++z)
    for (int y = -reach.y; y <= reach.y; ++y)
      for (int x = -reach.x; x <= reach.x; ++x) inside += isLatticeSite(lattice, {x, y, z}) ? 1 : 0;
  s.samples = inside;
  return s;
}

double nearestSiteDistance(const LatticeSampling& s) {
  switch (s.lattice) {
    case Lattice::Cc: return s.worldPerIndex;
    case Lattice::Bcc: return s.worldPerIndex * std::sqrt(3.0);
    case Lattice::Fcc: return s.worldPerIndex * std::sqrt(2.0);
  }
  return s.worldPerIndex;
}

std::vector<glm::dvec3> isosurfacePoints(const AnalyticField& field, double iso, int count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.95, 0.95);
  const glm::dvec3 e = field.halfExtent();
  const double scale = std::max(e.x, std::max(e.y, e.z));
  // Converged: |f - iso| within rounding of the values (relative, for volumes of large values), or a
  // step below 1e-12 of the domain.
  const double valueTolerance = 1e-12 * (1.0 + std::abs(iso));
  std::vector<glm::dvec3> points;
  for (int attempt = 0; attempt < 50 * count && int(points.size()) < count; ++attempt) {
    // An isovalue the field never takes near its samples would cost 50 attempts a point: give up when
    // a tenth of the attempts found no point at all.
    if (points.empty() && attempt >= 5 * count) break;
    glm::dvec3 p = e * glm::dvec3(u(rng), u(rng), u(rng));
    bool converged = false;
    for (int it = 0; it < 30; ++it) {
      const double f = field.value(p) - iso;
      if (std::abs(f) <= valueTolerance) {
        converged = true;
        break;
      }
      const glm::dvec3 g = field.gradient(p);
      const double g2 = glm::dot(g, g);
      if (!(g2 > 1e-300)) break;
      glm::dvec3 step = f / g2 * g;
      // At most a tenth of the domain a step, so Newton stays near where it started.
      const double len = glm::length(step);
      if (len > 0.1 * scale) step *= 0.1 * scale / len;
      p -= step;
      if (len < 1e-12 * scale) {
        converged = std::abs(field.value(p) - iso) <= 1e-6 * (1.0 + std::abs(iso));
        break;
      }
    }
    if (converged && glm::all(glm::lessThanEqual(glm::abs(p), 0.95 * e))) points.push_back(p);
  }
  return points;
}

std::vector<CompareRow> compareReconstructions(const AnalyticField& field, const CompareOptions& options,
                                               RgbImage* truthImage) {
  // Everything that can be refused is refused before any work: names, budgets (memory).
  for (const auto& name : options.reconstructions) findReconstruction(name);
  const glm::dvec3 e = field.halfExtent();
  for (int64_t budget : options.budgets)
    for (Lattice lattice : {Lattice::Cc, Lattice::Bcc, Lattice::Fcc}) samplingFor(lattice, budget, e);
  if (int64_t(options.width) * options.height > kMaxComparisonPixels)
    throw ValueError("renders of " + std::to_string(options.width) + "x" + std::to_string(options.height) +
                     " pixels are too large for a comparison (at most " + std::to_string(kMaxComparisonPixels) + " pixels)");
  const std::vector<glm::dvec3> uniform = uniformPoints(options.points, options.seed, e);
  // The truth at the measured points, once for every row.
  std::vector<double> uniformValues(uniform.size());
  std::vector<glm::dvec3> uniformGradients(uniform.size());
  tbb::parallel_for(size_t(0), uniform.size(), [&](size_t i) {
    uniformValues[i] = field.value(uniform[i]);
    uniformGradients[i] = field.gradient(uniform[i]);
  });
  // The isovalue must be one the field takes: its range at the uniform points, widened by a tenth.
  const auto [fMinAt, fMaxAt] = std::minmax_element(uniformValues.begin(), uniformValues.end());
  const double fMin = *fMinAt, fMax = *fMaxAt;
  const double margin = 0.1 * (fMax - fMin);
  if (!(options.iso >= fMin - margin && options.iso <= fMax + margin)) {
    char msg[256];
    std::snprintf(msg, sizeof msg, "--iso %g is outside the values of %s (%g .. %g at the points measured)", options.iso,
                  std::string(field.name()).c_str(), fMin, fMax);
    throw ValueError(msg);
  }
  const std::vector<glm::dvec3> surface = isosurfacePoints(field, options.iso, options.points, options.seed + 1);
  std::vector<glm::dvec3> surfaceGradients(surface.size());
  tbb::parallel_for(size_t(0), surface.size(), [&](size_t i) { surfaceGradients[i] = field.gradient(surface[i]); });
  // The truth's gradient direction is measured only where it has one: points where |grad f| is below
  // 1e-9 of its largest (constant air around a scan) are left out.
  double gradientMax = 0.0;
  for (const auto& g : uniformGradients) gradientMax = std::max(gradientMax, glm::length(g));
  const double gradientFloor = 1e-9 * gradientMax;
  const bool render = options.width > 0 && options.height > 0;
  TruthRender truth;
  if (render) truth = renderTruthHits(field, options.iso, options.width, options.height);
  if (render && truthImage) *truthImage = truthImageOf(truth, e);
  std::vector<CompareRow> rows;
  for (int64_t budget : options.budgets) {
    for (Lattice lattice : {Lattice::Cc, Lattice::Bcc, Lattice::Fcc}) {
      const LatticeSampling sampling = samplingFor(lattice, budget, e);
      const double h = sampling.worldPerIndex;
      // One set of coefficients (and of cell bounds for the renders) per prefilter the lattice's
      // reconstructions use.
      std::map<Prefilter, std::unique_ptr<LatticeSamples>> coefficients;
      std::map<Prefilter, std::unique_ptr<CellBounds>> cellBounds;
      for (const ReconstructionInfo& info : reconstructionInfos()) {
        if (info.lattice != lattice) continue;
        if (!options.reconstructions.empty() &&
            std::find(options.reconstructions.begin(), options.reconstructions.end(), info.name) ==
                options.reconstructions.end())
          continue;
        auto& samples = coefficients[info.prefilter];
        if (!samples) {
          samples = std::make_unique<LatticeSamples>(lattice, sampling.boxMin, sampling.boxDims, 0.0f);
          samples->fill([&](const glm::ivec3& ijk) { return float(field.value(h * glm::dvec3(ijk))); });
          samples->prefilter(info.prefilter);
        }
        const auto recon = makeReconstruction(info.name);
        const SiteValue at = samples->accessor();
        CompareRow row;
        row.lattice = std::string(latticeName(lattice));
        row.reconstruction = std::string(info.name);
        row.budget = budget;
        row.samples = sampling.samples;
        row.spacing = nearestSiteDistance(sampling);
        row.stencil = info.stencil;
        std::vector<double> valueErrors(uniform.size()), gradientAngles(uniform.size()), normalAngles(surface.size());
        tbb::parallel_for(size_t(0), uniform.size(), [&](size_t i) {
          const auto r = recon->evaluate(glm::vec3(uniform[i] / h), at);
          valueErrors[i] = double(r.value) - uniformValues[i];
          const glm::dvec3& truthGradient = uniformGradients[i];
          gradientAngles[i] = glm::length(truthGradient) > gradientFloor ? angleDeg(glm::dvec3(r.gradient), truthGradient) : -1.0;
        });
        tbb::parallel_for(size_t(0), surface.size(), [&](size_t i) {
          const auto r = recon->evaluate(glm::vec3(surface[i] / h), at);
          normalAngles[i] = angleDeg(glm::dvec3(r.gradient), surfaceGradients[i]);
        });
        double sum2 = 0.0;
        for (double e : valueErrors) {
          sum2 += e * e;
          row.valueMaxError = std::max(row.valueMaxError, std::abs(e));
        }
        row.valueRmsError = std::sqrt(sum2 / double(std::max<size_t>(1, valueErrors.size())));
        const AngleStats g = statsOf(gradientAngles), n = statsOf(normalAngles);
        row.gradientErrorMeanDeg = g.mean;
        row.gradientErrorP95Deg = g.p95;
        row.gradientErrorMaxDeg = g.max;
        row.normalErrorMeanDeg = n.mean;
        row.normalErrorP95Deg = n.p95;
        row.normalErrorMaxDeg = n.max;
        row.surfacePoints = int(surface.size());
        if (render) {
          // The stack schemes take their planes from the view, as a raycaster would.
          const auto viewed = makeReconstruction(info.name);
          const CompareCamera cam(e);
          viewed->setView(glm::vec3(glm::normalize(cam.lookAt - cam.eye)));
          auto& bounds = cellBounds[info.prefilter];
          if (!bounds) bounds = std::make_unique<CellBounds>(*samples);
          renderAndMeasure(*viewed, at, *bounds, h, options.iso, e, truth, row, options.keepImages);
        }
        rows.push_back(row);
      }
    }
  }
  return rows;
}

}  // namespace fcc
