// Google Benchmark: spline evaluations per second on one core (the CPU reference path), over a dense
// block of coefficients so the figure measures the spline, not a sparse lookup.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "sparse/Spline.h"

namespace {

constexpr int kSide = 64;  // sites per axis of the dense coefficient block

struct DenseBlock {
  std::vector<float> c = std::vector<float>(size_t(kSide) * kSide * kSide);
  DenseBlock() {
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> d(-1.0f, 1.0f);
    for (float& v : c) v = d(rng);
  }
  float operator()(const glm::ivec3& ijk) const { return c[(size_t(ijk.z) * kSide + ijk.y) * kSide + ijk.x]; }
};

std::vector<glm::vec3> randomPoints(size_t n) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> d(2.0f, float(kSide - 3));  // stencils stay inside the block
  std::vector<glm::vec3> p(n);
  for (auto& x : p) x = glm::vec3(d(rng), d(rng), d(rng));
  return p;
}

void BM_SplineValue(benchmark::State& state) {
  const DenseBlock block;
  const auto points = randomPoints(1 << 16);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(fcc::spline::evaluate(points[i], block));
    i = (i + 1) & (points.size() - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SplineValue);

void BM_SplineValueGradient(benchmark::State& state) {
  const DenseBlock block;
  const auto points = randomPoints(1 << 16);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(fcc::spline::evaluateWithGradient(points[i], block));
    i = (i + 1) & (points.size() - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_SplineValueGradient);

}  // namespace

BENCHMARK_MAIN();
