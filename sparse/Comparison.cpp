#include "Comparison.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "CubicBSpline.h"
#include "Error.h"
#include "LatticeSamples.h"

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
AngleStats statsOf(std::vector<double> angles) {
  AngleStats s;
  if (angles.empty()) return s;
  std::sort(angles.begin(), angles.end());
  for (double a : angles) s.mean += a;
  s.mean /= double(angles.size());
  s.p95 = angles[std::min(angles.size() - 1, size_t(std::ceil(0.95 * double(angles.size()))) - 1)];
  s.max = angles.back();
  return s;
}

std::vector<glm::dvec3> uniformPoints(int count, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<glm::dvec3> points(static_cast<size_t>(count));
  for (auto& p : points) p = glm::dvec3(u(rng), u(rng), u(rng));
  return points;
}

}  // namespace

LatticeSampling samplingFor(Lattice lattice, int64_t budget) {
  if (budget < 64) throw ValueError("a budget must be at least 64 samples (got " + std::to_string(budget) + ")");
  LatticeSampling s;
  s.lattice = lattice;
  s.budget = budget;
  s.worldPerIndex = std::cbrt(8.0 * latticeDensity(lattice) / double(budget));
  const int reach = int(std::floor(1.0 / s.worldPerIndex + 1e-9));
  s.boxMin = glm::ivec3(-reach - kPad);
  s.boxDims = glm::ivec3(2 * (reach + kPad) + 1);
  int64_t inside = 0;
  for (int z = -reach; z <= reach; ++z)
    for (int y = -reach; y <= reach; ++y)
      for (int x = -reach; x <= reach; ++x) inside += isLatticeSite(lattice, {x, y, z}) ? 1 : 0;
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
  std::vector<glm::dvec3> points;
  for (int attempt = 0; attempt < 50 * count && int(points.size()) < count; ++attempt) {
    glm::dvec3 p(u(rng), u(rng), u(rng));
    bool converged = false;
    for (int it = 0; it < 30; ++it) {
      const double f = field.value(p) - iso;
      if (std::abs(f) < 1e-12) {
        converged = true;
        break;
      }
      const glm::dvec3 g = field.gradient(p);
      const double g2 = glm::dot(g, g);
      if (g2 < 1e-20) break;
      glm::dvec3 step = f / g2 * g;
      // At most a tenth of the domain a step, so Newton stays near where it started.
      const double len = glm::length(step);
      if (len > 0.1) step *= 0.1 / len;
      p -= step;
    }
    if (converged && glm::all(glm::lessThanEqual(glm::abs(p), glm::dvec3(0.95)))) points.push_back(p);
  }
  return points;
}

std::vector<CompareRow> compareReconstructions(const AnalyticField& field, const CompareOptions& options) {
  for (const auto& name : options.reconstructions) findReconstruction(name);  // ValueError for unknown ones
  const std::vector<glm::dvec3> uniform = uniformPoints(options.points, options.seed);
  const std::vector<glm::dvec3> surface = isosurfacePoints(field, options.iso, options.points, options.seed + 1);
  std::vector<CompareRow> rows;
  for (int64_t budget : options.budgets) {
    for (Lattice lattice : {Lattice::Cc, Lattice::Bcc, Lattice::Fcc}) {
      const LatticeSampling sampling = samplingFor(lattice, budget);
      const double h = sampling.worldPerIndex;
      // One set of coefficients per prefilter the lattice's reconstructions use.
      std::map<Prefilter, std::unique_ptr<LatticeSamples>> coefficients;
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
          valueErrors[i] = double(r.value) - field.value(uniform[i]);
          gradientAngles[i] = angleDeg(glm::dvec3(r.gradient), field.gradient(uniform[i]));
        });
        tbb::parallel_for(size_t(0), surface.size(), [&](size_t i) {
          const auto r = recon->evaluate(glm::vec3(surface[i] / h), at);
          normalAngles[i] = angleDeg(glm::dvec3(r.gradient), field.gradient(surface[i]));
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
        rows.push_back(row);
      }
    }
  }
  return rows;
}

}  // namespace fcc
