// The OpenCL implementation of the per-brick preprocessing work (sparse/BrickKernels.h): stages a
// batch of bricks (a pool of the FCC leaves they read plus a 27-entry neighbour table per brick) and
// runs kernels/preprocess.cl, one work-group per brick.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "kernels/ClRunner.h"
#include "sparse/BrickKernels.h"

namespace fcc {

class ClBrickKernels : public BrickKernels {
 public:
  // Picks the device (ClRunner selectors) and builds the program now, so that a device without a
  // working compiler fails here (ClError), not halfway through a conversion.
  explicit ClBrickKernels(std::string_view selector);
  ~ClBrickKernels() override;

  std::string describe() const override;
  void bounds(const FccGrid& coefficients, const std::vector<openvdb::Coord>& bricks,
              std::vector<openvdb::Vec2f>& out) override;
  void prefilter(const FccGrid& samples, const std::vector<openvdb::Coord>& bricks,
                 std::vector<openvdb::Vec4f>& out) override;

  ClRunner& runner() { return *runner_; }

 private:
  struct Staged;
  std::unique_ptr<ClRunner> runner_;
  // Kept between calls: a streamed conversion calls once per slab, and fresh staging memory each
  // time cost as much in page faults as the copies themselves.
  std::unique_ptr<Staged> staged_;
  std::size_t groupSize_ = 0;
  cl::Kernel boundsKernel_, prefilterKernel_;
};

// The --cl-device values: "reference" (the C++/TBB path), "auto", "cpu", "gpu", or a device index.
inline constexpr const char* kDeviceSelectorHelp = "auto (a GPU, else PoCL's CPU device), cpu, gpu, N (a device index), or reference (the C++/TBB path)";
// Empty when `selector` is one of those forms, else the one-line complaint listing the valid values.
std::string checkDeviceSelector(std::string_view selector);

// The kernels for `selector`: "reference" gives the C++/TBB path; so does OpenCL that cannot be used
// at all (no platform, no device, a program that does not build), after one line on stderr
// ("OpenCL unavailable (...): using the CPU reference path"). A selector naming a device that does
// not exist (an index out of range, gpu without a GPU) throws ClError.
std::unique_ptr<BrickKernels> makeBrickKernels(std::string_view selector);

}  // namespace fcc
