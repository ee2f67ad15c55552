// Deterministic test data on the FCC lattice, shared by the spline tests.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <random>

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

}  // namespace fcc::test
