// Deterministic test data on the FCC lattice, shared by the spline tests.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace fcc::test {

// A reproducible pseudo-random coefficient in [-1, 1] per site.
inline float hashedCoefficient(const glm::ivec3& ijk, uint32_t seed = 1) {
  uint32_t h = seed * 0x9E3779B9u;
  for (int v : {ijk.x, ijk.y, ijk.z}) {
    h ^= uint32_t(v) + 0x7F4A7C15u + (h << 6) + (h >> 2);
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
  }
  return float(h & 0xFFFFFF) / float(0x7FFFFF) - 1.0f;
}

// Random positions in a box, from a seeded engine.
struct PointSource {
  explicit PointSource(uint32_t seed, float lo = -3.0f, float hi = 3.0f) : rng(seed), dist(lo, hi) {}
  glm::vec3 next() { return glm::vec3(dist(rng), dist(rng), dist(rng)); }
  std::mt19937 rng;
  std::uniform_real_distribution<float> dist;
};


// Comparing the C++ path with the same header compiled as OpenCL C or GLSL:
// float32 round-off of two compilations of the same arithmetic (contraction into FMAs, operation
// order) for coefficients in [-1, 1]: values and gradient components are O(1).
constexpr float kValueTol = 1e-5f;
constexpr float kGradientTol = 2e-5f;
constexpr int kPoints = 10000;
constexpr int kBlockSide = 24;
constexpr float kBackground = 0.25f;

inline std::string str(const glm::vec3& v) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.9g, %.9g, %.9g)", v.x, v.y, v.z);
  return b;
}

// Every integer point of [origin, origin + dims) with x fastest, as the OpenCL kernel and the shader read it.
struct DenseBlock {
  glm::ivec3 origin;
  glm::ivec3 dims;
  float background;
  std::vector<float> values;

  DenseBlock(const glm::ivec3& o, int side, float bg, uint32_t seed) : origin(o), dims(side), background(bg) {
    values.resize(size_t(side) * side * side);
    for (int z = 0; z < side; ++z)
      for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
          values[(size_t(z) * side + y) * side + x] = test::hashedCoefficient(origin + glm::ivec3(x, y, z), seed);
  }
  float at(const glm::ivec3& ijk) const {
    const glm::ivec3 r = ijk - origin;
    if (glm::any(glm::lessThan(r, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(r, dims))) return background;
    return values[(size_t(r.z) * dims.y + r.y) * dims.x + r.x];
  }
};

// Points uniformly in [origin + margin, origin + dims - 1 - margin] per axis.
inline std::vector<glm::vec4> randomPoints(const DenseBlock& block, int count, float margin, uint32_t seed) {
  test::PointSource source(seed, margin, float(block.dims.x - 1) - margin);
  std::vector<glm::vec4> points(static_cast<size_t>(count));
  for (glm::vec4& p : points) p = glm::vec4(source.next() + glm::vec3(block.origin), 1.0f);
  return points;
}

}  // namespace fcc::test
