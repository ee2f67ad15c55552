// A GoogleTest fixture holding one OpenCL device object (ClRunner, ClBrickKernels, ...) built on the
// "auto" device for a whole test suite: tests skip without OpenCL, or fail when the environment
// variable CI is set (CI must exercise OpenCL). The OpenCL counterpart of tests/viewer/GlTestSuite.h.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "kernels/ClRunner.h"

namespace fcc::test {

template <class Device>
class ClSuite : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    try {
      device = std::make_unique<Device>("auto");
    } catch (const ClError& e) {
      unavailable = e.what();
    }
  }
  static void TearDownTestSuite() { device.reset(); }
  void SetUp() override {
    if (device) return;
    if (std::getenv("CI")) FAIL() << "OpenCL is required when CI is set: " << unavailable;
    GTEST_SKIP() << "no OpenCL device: " << unavailable;
  }
  static inline std::unique_ptr<Device> device;
  static inline std::string unavailable;
};

}  // namespace fcc::test
