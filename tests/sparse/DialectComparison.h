// Compares results of the spline header compiled for a device (OpenCL C, GLSL) with the C++ path.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "SplineTestData.h"
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

}  // namespace fcc::test
