// A small OpenCL host runner: device selection, one context and in-order queue, a program cache, and
// every OpenCL error turned into fcc::ClError (named code, and the build log for build failures).
//
//   fcc::ClRunner cl("auto");                                   // or "cpu", "gpu", "0", "1", ...
//   cl::Kernel k = cl.kernel(fcc::embedded::kernels("kernels/spline_eval.cl"), "fcc_spline_eval");
//   cl.launch("spline evaluation", k, n, points, cl_uint(n), ...);   // sets the arguments, enqueues
//
// Not thread-safe except for program(), which may be called concurrently.
#pragma once

#ifndef CL_HPP_TARGET_OPENCL_VERSION
#define CL_HPP_TARGET_OPENCL_VERSION 120
#endif
#ifndef CL_HPP_MINIMUM_OPENCL_VERSION
#define CL_HPP_MINIMUM_OPENCL_VERSION 110
#endif
#ifndef CL_HPP_ENABLE_EXCEPTIONS
#define CL_HPP_ENABLE_EXCEPTIONS
#endif
#include <CL/opencl.hpp>

#include <cstddef>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sparse/Error.h"

namespace fcc {

// An OpenCL failure: what was being done, the OpenCL error name (e.g. CL_INVALID_KERNEL_ARGS) and,
// for a program that does not build, the compiler's log (also part of what()).
struct ClError : Error {
  ClError(const std::string& message, cl_int code, std::string buildLog = {});
  cl_int code() const { return code_; }
  const char* codeName() const;
  const std::string& buildLog() const { return buildLog_; }

 private:
  cl_int code_;
  std::string buildLog_;
};

// "CL_INVALID_KERNEL_ARGS" for -52, ..., "CL_ERROR_<n>" for a code this table does not know.
const char* clErrorName(cl_int code);

// Rethrows an OpenCL C++ bindings error as ClError: "<doing>: <clFunction> failed: <NAME> (<code>)".
[[noreturn]] void throwClError(const cl::Error& error, std::string_view doing);

// One entry of the flattened platform x device list that the numeric selectors index.
struct ClDeviceEntry {
  int index = 0;
  std::string platformName;
  std::string deviceName;
  cl_device_type type = 0;
  cl::Platform platform;
  cl::Device device;
  std::string describe() const;  // "platform / device"
};

class ClRunner {
 public:
  // `selector`: "auto" (the first GPU, else the first CPU device such as PoCL's, else the first
  // device), "cpu", "gpu", or an index into devices(). Throws ClError when no platform exists, when
  // no device matches, or for a selector that is none of these (the message lists the valid ones).
  explicit ClRunner(std::string_view selector = "auto");

  // Every device of every platform, in platform order then device order. Throws ClError if there is
  // no OpenCL platform at all.
  static std::vector<ClDeviceEntry> devices();

  std::string describe() const { return entry_.describe(); }  // "platform / device", for logs
  const ClDeviceEntry& entry() const { return entry_; }
  const cl::Context& context() const { return context_; }
  const cl::Device& device() const { return entry_.device; }
  cl::CommandQueue& queue() { return queue_; }

  // The program built from `source` with `options`, cached by (source, options). A build failure
  // throws ClError (CL_BUILD_PROGRAM_FAILURE) whose message and buildLog() hold the compiler log.
  cl::Program program(std::string_view source, const std::string& options = {});
  // A new kernel object (kernels hold their arguments, so they are not shared) from a cached program.
  cl::Kernel kernel(std::string_view source, const std::string& name, const std::string& options = {});
  std::size_t cachedPrograms() const;

  // Buffers: `upload` copies host data into a new buffer, `allocate` makes an uninitialised one,
  // `download` blocks until the queue reaches the read.
  template <class T>
  cl::Buffer upload(const std::vector<T>& data, cl_mem_flags flags = CL_MEM_READ_ONLY);
  cl::Buffer allocate(std::size_t bytes, cl_mem_flags flags = CL_MEM_READ_WRITE);
  template <class T>
  void download(const cl::Buffer& buffer, std::vector<T>& out);

  // Sets the kernel's arguments in order (if any are given) and enqueues a 1D range of `count` work
  // items with the implementation's work-group size; the kernel must not assume a particular local
  // size. `description` names the launch in errors ("spline evaluation: argument 3 of fcc_spline_eval:
  // ... CL_INVALID_ARG_SIZE"). Does not wait; call finish() or download().
  template <class... Args>
  void launch(std::string_view description, cl::Kernel& kernel, std::size_t count, const Args&... args);
  // As launch(), for a kernel written for work-groups of `groupSize` items: `groups` of them.
  template <class... Args>
  void launchGroups(std::string_view description, cl::Kernel& kernel, std::size_t groups, std::size_t groupSize,
                    const Args&... args);
  void finish();

 private:
  template <class... Args>
  void setArgs(std::string_view description, cl::Kernel& kernel, const Args&... args);
  void enqueue(std::string_view description, cl::Kernel& kernel, std::size_t count, std::size_t groupSize = 0);
  static std::string kernelName(cl::Kernel& kernel);

  ClDeviceEntry entry_;
  cl::Context context_;
  cl::CommandQueue queue_;
  mutable std::mutex cacheMutex_;
  std::map<std::pair<std::string, std::string>, cl::Program> programs_;
};

template <class T>
cl::Buffer ClRunner::upload(const std::vector<T>& data, cl_mem_flags flags) {
  try {
    const std::size_t bytes = data.empty() ? sizeof(T) : data.size() * sizeof(T);
    cl::Buffer buffer(context_, flags, bytes);
    if (!data.empty()) queue_.enqueueWriteBuffer(buffer, CL_TRUE, 0, data.size() * sizeof(T), data.data());
    return buffer;
  } catch (const cl::Error& e) {
    throwClError(e, "uploading " + std::to_string(data.size() * sizeof(T)) + " bytes to " + describe());
  }
}

template <class T>
void ClRunner::download(const cl::Buffer& buffer, std::vector<T>& out) {
  if (out.empty()) return;
  try {
    queue_.enqueueReadBuffer(buffer, CL_TRUE, 0, out.size() * sizeof(T), out.data());
  } catch (const cl::Error& e) {
    throwClError(e, "downloading " + std::to_string(out.size() * sizeof(T)) + " bytes from " + describe());
  }
}

template <class... Args>
void ClRunner::launch(std::string_view description, cl::Kernel& kernel, std::size_t count, const Args&... args) {
  setArgs(description, kernel, args...);
  enqueue(description, kernel, count);
}

template <class... Args>
void ClRunner::launchGroups(std::string_view description, cl::Kernel& kernel, std::size_t groups,
                            std::size_t groupSize, const Args&... args) {
  setArgs(description, kernel, args...);
  enqueue(description, kernel, groups * groupSize, groupSize);
}

template <class... Args>
void ClRunner::setArgs(std::string_view description, cl::Kernel& kernel, const Args&... args) {
  if constexpr (sizeof...(Args) > 0) {
    cl_uint index = 0;
    auto set = [&](const auto& arg) {
      try {
        kernel.setArg(index, arg);
      } catch (const cl::Error& e) {
        throwClError(e, std::string(description) + ": argument " + std::to_string(index) + " of " + kernelName(kernel));
      }
      ++index;
    };
    (set(args), ...);
  }
}

}  // namespace fcc
