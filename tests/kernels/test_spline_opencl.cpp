// The OpenCL kernel kernels/spline_eval.cl against the C++ spline (sparse/Spline.h), and the runner's
// device selection and errors. Runs on whatever "auto" picks (PoCL's CPU device on a machine without
// a GPU). Without any OpenCL platform the tests are skipped, or fail when the environment variable CI
// is set.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "embedded_kernels.h"
#include "kernels/ClRunner.h"
#include "sparse/Spline.h"
#include "tests/kernels/ClTestSuite.h"
#include "tests/sparse/DialectComparison.h"

using fcc::test::DenseBlock;

namespace fcc {
namespace {

class OpenCl : public test::ClSuite<ClRunner> {
 protected:
  static std::string_view splineSource() { return embedded::kernels("kernels/spline_eval.cl"); }

  // (value, gradient) per point from the kernel.
  static std::vector<glm::vec4> evaluateOnDevice(const DenseBlock& block, const std::vector<glm::vec4>& points) {
    cl::Kernel kernel = device->kernel(std::string(splineSource()), "fcc_spline_eval");
    const auto start = std::chrono::steady_clock::now();
    cl::Buffer pointBuffer = device->upload(points);
    cl::Buffer coefficientBuffer = device->upload(block.values);
    cl::Buffer resultBuffer = device->allocate(points.size() * sizeof(glm::vec4), CL_MEM_WRITE_ONLY);
    const cl_int4 origin = {{block.origin.x, block.origin.y, block.origin.z, 0}};
    const cl_int4 dims = {{block.dims.x, block.dims.y, block.dims.z, 0}};
    device->launch("spline evaluation", kernel, points.size(), pointBuffer, cl_uint(points.size()), coefficientBuffer,
                   origin, dims, cl_float(block.background), resultBuffer);
    std::vector<glm::vec4> results(points.size());
    device->download(resultBuffer, results);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("[   INFO   ] %zu points on %s: %.1f ms (upload, launch, download)\n", points.size(),
                device->describe().c_str(), ms);
    return results;
  }

  // A kernel of kernels/recon_eval.cl (points, count, id, params, the block; one result per count).
  static std::vector<glm::vec4> runReconKernel(const char* name, const DenseBlock& block,
                                               const std::vector<glm::vec4>& points, size_t count, int id,
                                               const glm::ivec3& params) {
    cl::Kernel kernel = device->kernel(std::string(embedded::kernels("kernels/recon_eval.cl")), name);
    cl::Buffer pointBuffer = device->upload(points);
    cl::Buffer valueBuffer = device->upload(block.values);
    cl::Buffer resultBuffer = device->allocate(count * sizeof(glm::vec4), CL_MEM_WRITE_ONLY);
    const cl_int4 paramsCl = {{params.x, params.y, params.z, 0}};
    const cl_int4 origin = {{block.origin.x, block.origin.y, block.origin.z, 0}};
    const cl_int4 dims = {{block.dims.x, block.dims.y, block.dims.z, 0}};
    device->launch(name, kernel, count, pointBuffer, cl_uint(count), cl_int(id), paramsCl, valueBuffer, origin, dims,
                   cl_float(block.background), resultBuffer);
    std::vector<glm::vec4> results(count);
    device->download(resultBuffer, results);
    return results;
  }

  static std::vector<glm::vec4> evaluateReconstruction(const DenseBlock& block, const std::vector<glm::vec4>& points,
                                                       int id, const glm::ivec3& params) {
    return runReconKernel("fcc_recon_eval", block, points, points.size(), id, params);
  }
};

TEST_F(OpenCl, EveryReconstructionsSegmentRootMatchesCpp) {
  test::expectSegmentRootsMatchCpp("OpenCL", [](const DenseBlock& block, const std::vector<glm::vec4>& endpoints, int id,
                                                const glm::ivec3& params) {
    return runReconKernel("fcc_recon_segment_roots", block, endpoints, endpoints.size() / 2, id, params);
  });
}

TEST_F(OpenCl, EveryReconstructionMatchesCpp) {
  test::expectReconstructionsMatchCpp("OpenCL", evaluateReconstruction);
}

TEST_F(OpenCl, SplineMatchesCppAtRandomPoints) { test::expectMatchesCppAtRandomPoints("OpenCL", evaluateOnDevice); }

TEST_F(OpenCl, SplineUsesTheBackgroundOutsideTheBlock) { test::expectBackgroundOutsideTheBlock("OpenCL", evaluateOnDevice); }

TEST_F(OpenCl, ProgramCacheBuildsEachSourceOnce) {
  const std::string source(splineSource());
  device->kernel(source, "fcc_spline_eval");
  const size_t cached = device->cachedPrograms();
  device->kernel(source, "fcc_spline_eval");
  EXPECT_EQ(device->cachedPrograms(), cached);
}

TEST_F(OpenCl, EmbeddedSourceHasTheHeaderInlined) {
  const std::string_view source = splineSource();
  EXPECT_NE(source.find("fcc_locate"), std::string_view::npos);
  EXPECT_NE(source.find("fcc_decasteljau3"), std::string_view::npos);  // from FccSplineTables.h
  EXPECT_EQ(source.find("#include \""), std::string_view::npos);
}

TEST_F(OpenCl, BuildFailureCarriesTheLog) {
  const std::string broken = "__kernel void broken(__global float* x) { x[0] = fcc_no_such_name; }\n";
  try {
    device->program(broken);
    FAIL() << "an invalid kernel built";
  } catch (const ClError& e) {
    EXPECT_EQ(e.code(), CL_BUILD_PROGRAM_FAILURE) << e.what();
    EXPECT_FALSE(e.buildLog().empty());
    EXPECT_NE(e.buildLog().find("fcc_no_such_name"), std::string::npos) << e.buildLog();
    EXPECT_NE(std::string(e.what()).find(e.buildLog()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("CL_BUILD_PROGRAM_FAILURE"), std::string::npos) << e.what();
  }
}

TEST_F(OpenCl, LaunchErrorsNameTheCodeAndTheLaunch) {
  cl::Kernel kernel = device->kernel(std::string(splineSource()), "fcc_spline_eval");
  try {
    device->launch("spline evaluation without arguments", kernel, 16);  // no argument set
    device->finish();
    FAIL() << "a kernel without arguments launched";
  } catch (const ClError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.code(), CL_INVALID_KERNEL_ARGS) << what;
    EXPECT_NE(what.find("CL_INVALID_KERNEL_ARGS"), std::string::npos) << what;
    EXPECT_NE(what.find("spline evaluation without arguments"), std::string::npos) << what;
    EXPECT_NE(what.find("fcc_spline_eval"), std::string::npos) << what;
  }
  try {
    device->kernel(std::string(splineSource()), "fcc_no_such_kernel");
    FAIL() << "a missing kernel was created";
  } catch (const ClError& e) {
    EXPECT_NE(std::string(e.what()).find("CL_INVALID_KERNEL_NAME"), std::string::npos) << e.what();
  }
}

TEST_F(OpenCl, SelectsTheCpuDevice) {
  bool hasCpu = false;
  for (const ClDeviceEntry& e : ClRunner::devices()) hasCpu |= (e.type & CL_DEVICE_TYPE_CPU) != 0;
  if (!hasCpu) GTEST_SKIP() << "no OpenCL CPU device here";
  const ClRunner cpu("cpu");
  EXPECT_TRUE(cpu.entry().type & CL_DEVICE_TYPE_CPU);
  EXPECT_NE(cpu.describe().find(" / "), std::string::npos);
  std::printf("[   INFO   ] auto: %s; cpu: %s\n", device->describe().c_str(), cpu.describe().c_str());
  const ClRunner byIndex(std::to_string(cpu.entry().index));
  EXPECT_EQ(byIndex.describe(), cpu.describe());
}

TEST_F(OpenCl, NonsenseSelectorListsTheValidOnes) {
  try {
    ClRunner("banana");
    FAIL() << "selector 'banana' was accepted";
  } catch (const ClError& e) {
    const std::string what = e.what();
    for (const char* word : {"'banana'", "auto", "cpu", "gpu", "index", " / "})
      EXPECT_NE(what.find(word), std::string::npos) << "missing '" << word << "' in: " << what;
  }
  EXPECT_THROW(ClRunner("4096"), ClError);
}

TEST(ClErrorNames, KnownAndUnknownCodes) {
  EXPECT_STREQ(clErrorName(CL_INVALID_KERNEL_ARGS), "CL_INVALID_KERNEL_ARGS");
  EXPECT_STREQ(clErrorName(-1001), "CL_PLATFORM_NOT_FOUND_KHR");
  EXPECT_STREQ(clErrorName(-9999), "CL_ERROR_-9999");
}

}  // namespace
}  // namespace fcc
