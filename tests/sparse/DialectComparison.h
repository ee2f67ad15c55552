// Compares results of the spline header compiled for a device (OpenCL C, GLSL) with the C++ path.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "SplineTestData.h"
// The dispatch compiled in C++ too, reading a DenseBlock: what the device dialects are compared with.
#define FCC_SITE_PARAMS , const fcc::test::DenseBlock& block
#define FCC_SITE_ARGS , block
#define FCC_SITE_VALUE(ijk) block.at(ijk)
#include "sparse/Spline.h"
#include "sparse/ReconDispatch.h"
#include "sparse/Reconstruction.h"
#include "sparse/Spline.h"

namespace fcc::test {

// `device[i]` = (value, gradient) at points[i]; fails at the first point beyond the tolerances and
// prints the largest differences seen.
inline void expectMatchesCpp(const char* dialect, const DenseBlock& block, const std::vector<glm::vec4>& points,
                             const std::vector<glm::vec4>& device) {
  ASSERT_EQ(device.size(), points.size());
  float maxValue = 0.0f, maxGradient = 0.0f;
  for (size_t i = 0; i < points.size(); ++i) {
    const glm::vec3 p(points[i]);
    const auto cpu = spline::evaluateWithGradient(p, [&](const glm::ivec3& ijk) { return block.at(ijk); });
    const float dv = std::abs(device[i].x - cpu.value);
    const float dg = glm::max(glm::max(std::abs(device[i].y - cpu.gradient.x), std::abs(device[i].z - cpu.gradient.y)),
                              std::abs(device[i].w - cpu.gradient.z));
    ASSERT_LE(dv, kValueTol) << "value at point " << i << " " << str(p) << ": " << dialect << " " << device[i].x
                             << ", C++ " << cpu.value;
    ASSERT_LE(dg, kGradientTol) << "gradient at point " << i << " " << str(p) << ": " << dialect << " "
                                << str(glm::vec3(device[i].y, device[i].z, device[i].w)) << ", C++ " << str(cpu.gradient);
    maxValue = std::max(maxValue, dv);
    maxGradient = std::max(maxGradient, dg);
  }
  std::printf("[   INFO   ] %s: max |value diff| %.3g (tol %.0e), max |gradient diff| %.3g (tol %.0e)\n", dialect,
              maxValue, kValueTol, maxGradient, kGradientTol);
}

// The cases every device dialect runs, so OpenCL C and GLSL are checked on the same points.
// `evaluate(block, points)` returns the device's (value, gradient) per point.
template <class Evaluate>
void expectMatchesCppAtRandomPoints(const char* dialect, Evaluate&& evaluate) {
  // An odd origin: the block's storage parity differs from the lattice's.
  const DenseBlock block(glm::ivec3(-7, 3, 12), kBlockSide, kBackground, 21);
  const std::vector<glm::vec4> points = randomPoints(block, kPoints, 2.0f, 22);
  expectMatchesCpp(dialect, block, points, evaluate(block, points));
}

template <class Evaluate>
void expectBackgroundOutsideTheBlock(const char* dialect, Evaluate&& evaluate) {
  // Points up to 3 outside the block on every side: stencils straddle the boundary or miss the block.
  const DenseBlock block(glm::ivec3(4, -9, 0), 8, kBackground, 23);
  const std::vector<glm::vec4> points = randomPoints(block, 2000, -3.0f, 24);
  expectMatchesCpp(dialect, block, points, evaluate(block, points));
}

// Every reconstruction of the layer on a device against its C++ class, at random points of a block
// (an odd origin; points up to 2 outside it, so stencils also read the background). The stack schemes
// run with a view that picks axis x and mixed shears, so the axis permutation is exercised too.
// `evaluate(block, points, id, params)` returns the device's (value, gradient) per point.
template <class Evaluate>
void expectReconstructionsMatchCpp(const char* dialect, Evaluate&& evaluate) {
  const DenseBlock block(glm::ivec3(-7, 3, 12), kBlockSide, kBackground, 31);
  const std::vector<glm::vec4> points = randomPoints(block, 4000, -2.0f, 32);
  const glm::vec3 view(0.9f, -0.3f, 0.2f);
  const glm::ivec3 params = spline::bcc_sheared_params_for_view(view);
  ASSERT_EQ(params, glm::ivec3(0, -1, 1));
  for (const ReconstructionInfo& info : reconstructionInfos()) {
    const auto recon = makeReconstruction(info.name);
    recon->setView(view);
    const std::vector<glm::vec4> device = evaluate(block, points, reconstructionDeviceId(info), params);
    ASSERT_EQ(device.size(), points.size());
    float maxValue = 0.0f, maxGradient = 0.0f;
    for (size_t i = 0; i < points.size(); ++i) {
      const glm::vec3 p(points[i]);
      const auto cpu = recon->evaluate(p, [&](const glm::ivec3& ijk) { return block.at(ijk); });
      const float dv = std::abs(device[i].x - cpu.value);
      const glm::vec3 g(device[i].y, device[i].z, device[i].w);
      const float dg = glm::max(glm::max(std::abs(g.x - cpu.gradient.x), std::abs(g.y - cpu.gradient.y)),
                                std::abs(g.z - cpu.gradient.z));
      // A point within rounding of the nearest-plane scheme's step may land on either side of it.
      if (info.continuity < 0 && dv > 1e-3f) continue;
      ASSERT_LE(dv, kValueTol) << info.name << " value at point " << i << " " << str(p) << ": " << dialect << " "
                               << device[i].x << ", C++ " << cpu.value;
      ASSERT_LE(dg, kGradientTol) << info.name << " gradient at point " << i << " " << str(p) << ": " << dialect << " "
                                  << str(g) << ", C++ " << str(cpu.gradient);
      maxValue = std::max(maxValue, dv);
      maxGradient = std::max(maxGradient, dg);
    }
    std::printf("[   INFO   ] %s %s: max |value diff| %.3g, max |gradient diff| %.3g\n", dialect,
                std::string(info.name).c_str(), maxValue, maxGradient);
  }
}

// The ray fast path of every reconstruction (fcc_recon_segment_root: each piece's Bernstein form along
// a segment and its first root) on a device against the same function in C++, and the C++ against the
// piece's polynomial itself (evaluateInPiece): the root is a root, and no sign change comes before it.
// Segments of length up to 1 anywhere in the block, iso the piece's value somewhere on the segment.
// `evaluate(block, endpoints, id, params)` returns the device's roots (x of each result).
template <class Evaluate>
void expectSegmentRootsMatchCpp(const char* dialect, Evaluate&& evaluate) {
  const DenseBlock block(glm::ivec3(-7, 3, 12), kBlockSide, kBackground, 33);
  std::mt19937 rng(34);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const glm::vec3 view(0.9f, -0.3f, 0.2f);
  const glm::ivec3 params = spline::bcc_sheared_params_for_view(view);
  for (const ReconstructionInfo& info : reconstructionInfos()) {
    if (info.continuity < 0) continue;  // the nearest-plane scheme's steps are not a polynomial's roots
    const auto recon = makeReconstruction(info.name);
    recon->setView(view);
    const SiteValue at = [&](const glm::ivec3& ijk) { return block.at(ijk); };
    std::vector<glm::vec4> endpoints;
    const int kSegments = 3000;
    for (int i = 0; i < kSegments; ++i) {
      const glm::vec3 a = glm::vec3(block.origin) + 3.0f + (float(kBlockSide) - 7.0f) * glm::vec3(u(rng), u(rng), u(rng));
      const glm::vec3 b = a + glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
      const float iso = recon->evaluateInPiece(0.5f * (a + b), a + u(rng) * (b - a), at).value;
      endpoints.push_back(glm::vec4(a, iso));
      endpoints.push_back(glm::vec4(b, 0.0f));
    }
    const std::vector<glm::vec4> device = evaluate(block, endpoints, reconstructionDeviceId(info), params);
    ASSERT_EQ(device.size(), size_t(kSegments));
    int found = 0, differ = 0;
    for (int i = 0; i < kSegments; ++i) {
      const glm::vec3 a(endpoints[2 * i]), b(endpoints[2 * i + 1]);
      const float iso = endpoints[2 * i].w;
      const float cpu = spline::fcc_recon_segment_root(reconstructionDeviceId(info), a, b, iso, params, block);
      auto f = [&](float w) { return recon->evaluateInPiece(0.5f * (a + b), a + w * (b - a), at).value - iso; };
      if (cpu >= 0.0f) {
        ++found;
        ASSERT_LT(std::abs(f(cpu)), 2e-4f) << info.name << " segment " << i << ": the root " << cpu << " is not one";
        // No crossing before it, but within rounding of iso: a segment that starts on the surface (its
        // start's side is rounding's), or a pair of roots a hair apart that rounding may merge.
        const float f0 = f(0.0f);
        for (int k = 1; k < 200 && float(k) / 200 < cpu - 1e-3f; ++k) {
          const float fk = f(float(k) / 200);
          if ((fk < 0.0f) != (f0 < 0.0f)) {
            ASSERT_LT(std::min(std::abs(fk), std::abs(f0)), 1e-5f)
                << info.name << " segment " << i << ": a root before " << cpu << " (f " << f0 << " at 0, " << fk << " at "
                << float(k) / 200 << ")";
          }
        }
      }
      // The dialects agree but where the polynomial barely touches iso (rounding decides there).
      if ((cpu < 0.0f) != (device[i].x < 0.0f) || (cpu >= 0.0f && std::abs(cpu - device[i].x) > 1e-3f)) {
        if (++differ <= 3)
          std::printf("[   INFO   ] %s %s segment %d: C++ root %.6f, %s %.6f; f there %.3g and %.3g\n", dialect,
                      std::string(info.name).c_str(), i, cpu, dialect, device[i].x, cpu >= 0.0f ? f(cpu) : 0.0f,
                      device[i].x >= 0.0f ? f(device[i].x) : 0.0f);
      }
    }
    std::printf("[   INFO   ] %s %s: %d of %d segments with a root, %d differ from C++\n", dialect,
                std::string(info.name).c_str(), found, kSegments, differ);
    EXPECT_GT(found, kSegments / 2) << info.name;
    EXPECT_LE(differ, kSegments / 200) << info.name << ": " << dialect << " and C++ disagree on " << differ << " segments";
  }
}

}  // namespace fcc::test
