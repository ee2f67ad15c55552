// A GoogleTest fixture holding one headless EGL/OpenGL 4.5 context for a whole test suite: tests skip
// without one, or fail when the environment variable CI is set (CI must exercise GL).
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "sparse/Error.h"
#include "viewer/EglContext.h"

namespace fcc::test {

class GlSuite : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    try {
      context() = std::make_unique<EglContext>();
    } catch (const Error& e) {
      unavailable() = e.what();
    }
  }
  static void TearDownTestSuite() { context().reset(); }
  void SetUp() override {
    if (context()) return;
    if (std::getenv("CI")) FAIL() << "EGL/OpenGL 4.5 is required when CI is set: " << unavailable();
    GTEST_SKIP() << "no EGL/OpenGL 4.5: " << unavailable();
  }
  static std::unique_ptr<EglContext>& context() {
    static std::unique_ptr<EglContext> c;
    return c;
  }
  static std::string& unavailable() {
    static std::string s;
    return s;
  }
};

}  // namespace fcc::test
