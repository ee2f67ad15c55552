// The compute shader shaders/spline_eval.comp against the C++ spline (sparse/Spline.h), on a headless
// EGL context (llvmpipe where there is no GPU), and the GL program errors. Without a usable EGL
// display the tests are skipped, or fail when the environment variable CI is set.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "embedded_shaders.h"
#include "sparse/Spline.h"
#include "tests/sparse/DialectComparison.h"
#include "tests/viewer/GlTestSuite.h"
#include "viewer/GlProgram.h"

using fcc::test::DenseBlock;

namespace fcc {
namespace {

constexpr const char* kShaderPath = "shaders/spline_eval.comp";
constexpr const char* kReconPath = "shaders/recon_eval.comp";

class Glsl : public test::GlSuite {
 protected:
  static void TearDownTestSuite() {
    program.reset();  // before its context
    reconProgram.reset();
    GlSuite::TearDownTestSuite();
  }

  // The spline shader, compiled once per test binary.
  static const GlProgram& splineProgram() {
    if (!program) program = GlProgram::compute(embedded::shaders(kShaderPath), kShaderPath);
    return *program;
  }

  // Runs a point-evaluation program (spline_eval.comp, recon_eval.comp: points, the block's values,
  // results at bindings 0, 1, 2) over `points`; `setUniforms` adds the program's own uniforms.
  template <class SetUniforms>
  static std::vector<glm::vec4> runPoints(const GlProgram& p, const char* what, const DenseBlock& block,
                                          const std::vector<glm::vec4>& points, SetUniforms&& setUniforms) {
    const GlBuffer pointBuffer(points), valueBuffer(block.values);
    const GlBuffer resultBuffer(points.size() * sizeof(glm::vec4));
    pointBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    valueBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, 1);
    resultBuffer.bindBase(GL_SHADER_STORAGE_BUFFER, 2);
    p.use();
    glUniform4i(p.uniformLocation("uOrigin"), block.origin.x, block.origin.y, block.origin.z, 0);
    glUniform4i(p.uniformLocation("uDims"), block.dims.x, block.dims.y, block.dims.z, 0);
    glUniform1f(p.uniformLocation("uBackground"), block.background);
    glUniform1ui(p.uniformLocation("uCount"), GLuint(points.size()));
    setUniforms(p);
    p.dispatch(what, GLuint(points.size()));
    std::vector<glm::vec4> results(points.size());
    resultBuffer.read(results);
    return results;
  }

  static std::vector<glm::vec4> evaluateOnDevice(const DenseBlock& block, const std::vector<glm::vec4>& points) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<glm::vec4> results = runPoints(splineProgram(), "spline evaluation", block, points, [](const GlProgram&) {});
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("[   INFO   ] %zu points on %s: %.1f ms (upload, dispatch, read back)\n", points.size(),
                context()->describe().c_str(), ms);
    return results;
  }

  static std::vector<glm::vec4> evaluateReconstruction(const DenseBlock& block, const std::vector<glm::vec4>& points,
                                                       int id, const glm::ivec3& params) {
    if (!reconProgram) reconProgram = GlProgram::compute(embedded::shaders(kReconPath), kReconPath);
    return runPoints(*reconProgram, "reconstruction evaluation", block, points, [&](const GlProgram& p) {
      glUniform1i(p.uniformLocation("uId"), id);
      glUniform3i(p.uniformLocation("uParams"), params.x, params.y, params.z);
      glUniform1i(p.uniformLocation("uMode"), 0);
    });
  }

  // The first root on each segment (endpoints in pairs, iso in the first's w): one result per pair.
  static std::vector<glm::vec4> segmentRoots(const DenseBlock& block, const std::vector<glm::vec4>& endpoints, int id,
                                             const glm::ivec3& params) {
    if (!reconProgram) reconProgram = GlProgram::compute(embedded::shaders(kReconPath), kReconPath);
    std::vector<glm::vec4> roots = runPoints(*reconProgram, "segment roots", block, endpoints, [&](const GlProgram& p) {
      glUniform1i(p.uniformLocation("uId"), id);
      glUniform3i(p.uniformLocation("uParams"), params.x, params.y, params.z);
      glUniform1i(p.uniformLocation("uMode"), 1);
      glUniform1ui(p.uniformLocation("uCount"), GLuint(endpoints.size() / 2));
    });
    roots.resize(endpoints.size() / 2);
    return roots;
  }

  static inline std::optional<GlProgram> program;
  static inline std::optional<GlProgram> reconProgram;
};

TEST(GlslEmbedding, VersionLineStaysFirst) {
  const std::string_view source = embedded::shaders(kShaderPath);
  ASSERT_FALSE(source.empty());
  EXPECT_EQ(source.substr(0, 18), "#version 450 core\n");
  EXPECT_NE(source.find("fcc_decasteljau3"), std::string_view::npos);  // from FccSplineTables.h
  EXPECT_EQ(source.find("#include \""), std::string_view::npos);
}

TEST_F(Glsl, ContextIsOpenGL45Core) {
  std::printf("[   INFO   ] %s\n", context()->describe().c_str());
  if (!context()->fallbacks().empty()) std::printf("[   INFO   ] not used: %s\n", context()->fallbacks().c_str());
  EXPECT_FALSE(context()->renderer().empty());
  GLint major = 0, minor = 0, profile = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
  EXPECT_GE(major * 10 + minor, 45);
  EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
}

TEST_F(Glsl, SplineMatchesCppAtRandomPoints) { test::expectMatchesCppAtRandomPoints("GLSL", evaluateOnDevice); }

TEST_F(Glsl, SplineUsesTheBackgroundOutsideTheBlock) { test::expectBackgroundOutsideTheBlock("GLSL", evaluateOnDevice); }

TEST_F(Glsl, EveryReconstructionMatchesCpp) {
  test::expectReconstructionsMatchCpp("GLSL", evaluateReconstruction);
}

TEST_F(Glsl, EveryReconstructionsSegmentRootMatchesCpp) {
  test::expectSegmentRootsMatchCpp("GLSL", segmentRoots);
}

TEST_F(Glsl, CompileErrorCarriesTheInfoLog) {
  const char* broken = "#version 450 core\nlayout(local_size_x = 1) in;\nvoid main() { fcc_no_such_name = 1.0; }\n";
  try {
    GlProgram::compute(broken, "broken.comp");
    FAIL() << "an invalid shader compiled";
  } catch (const GlError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("compiling compute shader 'broken.comp' failed"), std::string::npos) << what;
    EXPECT_NE(what.find("fcc_no_such_name"), std::string::npos) << what;  // from the info log
  }
}

TEST_F(Glsl, UnknownUniformIsNamed) {
  try {
    splineProgram().uniformLocation("uNoSuchUniform");
    FAIL() << "an unknown uniform had a location";
  } catch (const GlError& e) {
    EXPECT_NE(std::string(e.what()).find("uNoSuchUniform"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fcc
