#include "AnalyticFields.h"

#include <cmath>
#include <algorithm>
#include <cmath>
#include <random>

#include "CubicBSpline.h"
#include "Error.h"
#include "SampleHistogram.h"

namespace fcc {
namespace {

constexpr double kPi = 3.14159265358979323846;

class MarschnerLobb final : public AnalyticField {
 public:
  std::string_view name() const override { return "marschner-lobb"; }
  double defaultIso() const override { return 0.5; }
  double value(const glm::dvec3& p) const override {
    const double r = std::sqrt(p.x * p.x + p.y * p.y);
    const double rho = std::cos(2.0 * kPi * kFm * std::cos(kPi * r / 2.0));
    return (1.0 - std::sin(kPi * p.z / 2.0) + kAlpha * (1.0 + rho)) / (2.0 * (1.0 + kAlpha));
  }
  glm::dvec3 gradient(const glm::dvec3& p) const override {
    const double r = std::sqrt(p.x * p.x + p.y * p.y);
    const double k = 1.0 / (2.0 * (1.0 + kAlpha));
    // d rho / dr = sin(2 pi fM cos(pi r / 2)) * 2 pi fM * sin(pi r / 2) * pi / 2.
    const double drho = std::sin(2.0 * kPi * kFm * std::cos(kPi * r / 2.0)) * 2.0 * kPi * kFm * std::sin(kPi * r / 2.0) * kPi / 2.0;
    const double radial = r > 1e-12 ? kAlpha * drho / r : 0.0;  // drho/dr ~ r near the axis
    return k * glm::dvec3(radial * p.x, radial * p.y, -kPi / 2.0 * std::cos(kPi * p.z / 2.0));
  }

 private:
  static constexpr double kFm = 6.0, kAlpha = 0.25;
};

class RandomWaves final : public AnalyticField {
 public:
  explicit RandomWaves(uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> phase(0.0, 2.0 * kPi);
    for (int i = 0; i < kWaves; ++i) {
      glm::dvec3 k(normal(rng), normal(rng), normal(rng));  // uniform direction on the sphere
      waves_.push_back({2.0 * kPi * kCyclesPerUnit * glm::normalize(k), phase(rng)});
    }
  }
  std::string_view name() const override { return "random-waves"; }
  double defaultIso() const override { return 0.0; }
  double value(const glm::dvec3& p) const override {
    double v = 0.0;
    for (const Wave& w : waves_) v += std::cos(glm::dot(w.k, p) + w.phase);
    return v / std::sqrt(double(kWaves));
  }
  glm::dvec3 gradient(const glm::dvec3& p) const override {
    glm::dvec3 g(0.0);
    for (const Wave& w : waves_) g -= std::sin(glm::dot(w.k, p) + w.phase) * w.k;
    return g / std::sqrt(double(kWaves));
  }

 private:
  static constexpr int kWaves = 64;
  static constexpr double kCyclesPerUnit = 3.0;
  struct Wave {
    glm::dvec3 k;
    double phase;
  };
  std::vector<Wave> waves_;
};

class VolumeField final : public AnalyticField {
 public:
  VolumeField(std::string name, const glm::ivec3& dims, const glm::dvec3& spacing, const std::vector<float>& values)
      : name_(std::move(name)), spline_(dims, values), dims_(dims), spacing_(spacing) {
    const glm::dvec3 extent = glm::dvec3(dims - 1) * spacing;
    worldPerVoxel_ = 2.0 / std::max(std::max(extent.x, extent.y), std::max(extent.z, 1e-300)) * spacing;
    halfExtent_ = 0.5 * glm::dvec3(dims - 1) * worldPerVoxel_;
    SampleSummary summary;
    summary.min = *std::min_element(values.begin(), values.end());
    summary.max = *std::max_element(values.begin(), values.end());
    summary.histogram.assign(kSampleHistogramBins, 0);
    for (float v : values) ++summary.histogram[size_t(summary.binOf(v))];
    iso_ = otsuThreshold(summary, values.front()).value_or(0.5 * (double(summary.min) + double(summary.max)));
  }
  std::string_view name() const override { return name_; }
  double defaultIso() const override { return iso_; }
  glm::dvec3 halfExtent() const override { return halfExtent_; }
  double rootSeparatingStep() const override {
    return 0.25 * std::min(worldPerVoxel_.x, std::min(worldPerVoxel_.y, worldPerVoxel_.z));
  }
  double value(const glm::dvec3& p) const override { return spline_.value(voxelOf(p)); }
  glm::dvec3 gradient(const glm::dvec3& p) const override { return spline_.gradient(voxelOf(p)) / worldPerVoxel_; }

 private:
  glm::dvec3 voxelOf(const glm::dvec3& p) const { return (p + halfExtent_) / worldPerVoxel_; }
  std::string name_;
  CubicBSplineVolume spline_;
  glm::ivec3 dims_;
  glm::dvec3 spacing_, worldPerVoxel_, halfExtent_;
  double iso_ = 0.0;
};

}  // namespace

std::unique_ptr<AnalyticField> makeVolumeField(std::string name, const glm::ivec3& dims, const glm::dvec3& spacing,
                                               const std::vector<float>& values) {
  if (glm::any(glm::lessThan(dims, glm::ivec3(4))))
    throw ValueError(name + ": a volume to compare against needs at least 4 voxels along every axis");
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw ValueError(name + ": voxel " + std::to_string(i) + " is not a finite number; a volume to compare against needs finite values");
  return std::make_unique<VolumeField>(std::move(name), dims, spacing, values);
}

const std::vector<std::string>& analyticFieldNames() {
  static const std::vector<std::string> names = {"marschner-lobb", "random-waves"};
  return names;
}

std::unique_ptr<AnalyticField> makeAnalyticField(std::string_view name, uint64_t seed) {
  if (name == "marschner-lobb") return std::make_unique<MarschnerLobb>();
  if (name == "random-waves") return std::make_unique<RandomWaves>(seed);
  std::string valid;
  for (const auto& n : analyticFieldNames()) valid += (valid.empty() ? "" : ", ") + n;
  throw ValueError("unknown field '" + std::string(name) + "' (valid: " + valid + ")");
}

}  // namespace fcc
