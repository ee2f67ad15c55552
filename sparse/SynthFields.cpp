#include "SynthFields.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "Error.h"

namespace fcc {
namespace {

SiteBox boxOfDims(const glm::ivec3& dims) { return SiteBox{glm::ivec3(0), dims - 1}; }

// f = |x - c|^2 / R^2 in index space: quadratic, so the prefiltered spline reproduces it exactly and
// every isosurface f = r^2 is an exact sphere of radius r R about c.
class SphereField : public SampleField {
 public:
  explicit SphereField(const glm::ivec3& dims)
      : dims_(dims), center_(glm::dvec3(dims - 1) * 0.5), radius_(0.5 * double(minComponent(dims - 1))) {}
  float sample(const glm::ivec3& ijk) const override {
    if (!boxOfDims(dims_).intersects(SiteBox{ijk, ijk})) return background();
    const glm::dvec3 d = glm::dvec3(ijk) - center_;
    return float(glm::dot(d, d) / (radius_ * radius_));
  }
  SiteBox bounds() const override { return boxOfDims(dims_); }
  float background() const override { return 1.0f; }

 private:
  glm::ivec3 dims_;
  glm::dvec3 center_;
  double radius_;
};

// Marschner and Lobb's test signal (1994), fM = 6, alpha = 0.25, over [-1,1]^3.
class MarschnerLobbField : public SampleField {
 public:
  explicit MarschnerLobbField(const glm::ivec3& dims) : dims_(dims) {}
  static glm::dvec3 worldOf(const glm::ivec3& ijk, const glm::ivec3& dims) {
    return -1.0 + 2.0 * glm::dvec3(ijk) / glm::dvec3(dims - 1);
  }
  float sample(const glm::ivec3& ijk) const override {
    if (!boxOfDims(dims_).intersects(SiteBox{ijk, ijk})) return background();
    const glm::dvec3 p = worldOf(ijk, dims_);
    constexpr double fM = 6.0, alpha = 0.25, pi = 3.14159265358979323846;
    const double r = std::sqrt(p.x * p.x + p.y * p.y);
    const double rho = std::cos(2.0 * pi * fM * std::cos(pi * r / 2.0));
    return float((1.0 - std::sin(pi * p.z / 2.0) + alpha * (1.0 + rho)) / (2.0 * (1.0 + alpha)));
  }
  SiteBox bounds() const override { return boxOfDims(dims_); }
  float background() const override { return 0.0f; }

 private:
  glm::ivec3 dims_;
};

// Sparse smooth blobs: sum of w (1 - r^2/R^2)^3 over random balls (C^2, compact support), filling
// roughly 10-20% of the domain; zero (the background) elsewhere.
class BlobsField : public SampleField {
 public:
  BlobsField(const glm::ivec3& dims, uint64_t seed) : dims_(dims) {
    std::mt19937_64 rng(seed);
    const double minDim = double(minComponent(dims));
    const double rMin = std::max(2.0, minDim / 32.0), rMax = std::max(3.0, minDim / 12.0);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    const double domain = double(dims.x) * dims.y * dims.z;
    double volume = 0.0;
    // Overlaps eat some of the summed volume: aim a little above the middle of 10-20%.
    while (volume < 0.17 * domain) {
      Blob b;
      b.radius = rMin + (rMax - rMin) * u01(rng);
      b.center = glm::dvec3(u01(rng), u01(rng), u01(rng)) * glm::dvec3(dims - 1);
      b.weight = 0.75 + 0.5 * u01(rng);
      blobs_.push_back(b);
      volume += 4.0 / 3.0 * 3.14159265358979323846 * b.radius * b.radius * b.radius;
    }
    // Uniform cells listing the blobs that reach into them: sample() visits only nearby blobs.
    cellSize_ = int(std::ceil(2.0 * rMax));
    cells_ = (dims + cellSize_ - 1) / cellSize_;
    lists_.resize(size_t(cells_.x) * cells_.y * cells_.z);
    for (size_t i = 0; i < blobs_.size(); ++i) {
      const glm::ivec3 lo = glm::clamp(glm::ivec3(glm::floor((blobs_[i].center - blobs_[i].radius) / double(cellSize_))),
                                       glm::ivec3(0), cells_ - 1);
      const glm::ivec3 hi = glm::clamp(glm::ivec3(glm::floor((blobs_[i].center + blobs_[i].radius) / double(cellSize_))),
                                       glm::ivec3(0), cells_ - 1);
      for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
          for (int x = lo.x; x <= hi.x; ++x) lists_[cellIndex({x, y, z})].push_back(uint32_t(i));
    }
  }
  float sample(const glm::ivec3& ijk) const override {
    if (!boxOfDims(dims_).intersects(SiteBox{ijk, ijk})) return 0.0f;
    double sum = 0.0;
    for (uint32_t i : lists_[cellIndex(ijk / cellSize_)]) {
      const Blob& b = blobs_[i];
      const glm::dvec3 d = glm::dvec3(ijk) - b.center;
      const double t = 1.0 - glm::dot(d, d) / (b.radius * b.radius);
      if (t > 0.0) sum += b.weight * t * t * t;
    }
    return float(sum);
  }
  bool mayHoldData(const SiteBox& box) const override {
    if (!box.intersects(bounds())) return false;
    const glm::ivec3 lo = glm::clamp(box.min / cellSize_, glm::ivec3(0), cells_ - 1);
    const glm::ivec3 hi = glm::clamp(box.max / cellSize_, glm::ivec3(0), cells_ - 1);
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x)
          for (uint32_t i : lists_[cellIndex({x, y, z})]) {
            const Blob& b = blobs_[i];
            // Distance from the blob's centre to the box.
            const glm::dvec3 nearest = glm::clamp(b.center, glm::dvec3(box.min), glm::dvec3(box.max));
            const glm::dvec3 d = nearest - b.center;
            if (glm::dot(d, d) < b.radius * b.radius) return true;
          }
    return false;
  }
  SiteBox bounds() const override { return boxOfDims(dims_); }
  float background() const override { return 0.0f; }

 private:
  struct Blob {
    glm::dvec3 center;
    double radius;
    double weight;
  };
  size_t cellIndex(const glm::ivec3& c) const { return (size_t(c.z) * cells_.y + c.y) * cells_.x + c.x; }
  glm::ivec3 dims_;
  std::vector<Blob> blobs_;
  int cellSize_ = 1;
  glm::ivec3 cells_{1};
  std::vector<std::vector<uint32_t>> lists_;
};

}  // namespace

const std::vector<std::string>& synthKinds() {
  static const std::vector<std::string> kinds = {"sphere", "marschner-lobb", "blobs"};
  return kinds;
}

SynthField makeSynthField(const SynthSpec& spec) {
  if (glm::any(glm::lessThan(spec.dims, glm::ivec3(2))))
    throw ValueError("--dims must be at least 2 in every axis");
  SynthField out;
  if (spec.kind == "sphere") {
    out.field = std::make_unique<SphereField>(spec.dims);
    out.suggestedIso = 0.5f;
  } else if (spec.kind == "marschner-lobb") {
    out.field = std::make_unique<MarschnerLobbField>(spec.dims);
    out.worldFromIndexScale = 2.0 / glm::dvec3(spec.dims - 1);
    out.worldFromIndexOrigin = glm::dvec3(-1.0);
    out.suggestedIso = 0.5f;
  } else if (spec.kind == "blobs") {
    out.field = std::make_unique<BlobsField>(spec.dims, spec.seed);
    out.suggestedIso = 0.5f;
  } else {
    std::string valid;
    for (const auto& k : synthKinds()) valid += (valid.empty() ? "" : ", ") + k;
    throw ValueError("unknown synth kind '" + spec.kind + "' (valid: " + valid + ")");
  }
  return out;
}

}  // namespace fcc
