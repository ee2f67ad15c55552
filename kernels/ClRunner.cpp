#include "ClRunner.h"

#include <algorithm>
#include <cctype>
#include <sstream>

namespace fcc {

namespace {

// Numeric codes so that names of codes newer than the targeted OpenCL version are known too.
struct NamedCode {
  cl_int code;
  const char* name;
};
constexpr NamedCode kClErrorNames[] = {
    {0, "CL_SUCCESS"},
    {-1, "CL_DEVICE_NOT_FOUND"},
    {-2, "CL_DEVICE_NOT_AVAILABLE"},
    {-3, "CL_COMPILER_NOT_AVAILABLE"},
    {-4, "CL_MEM_OBJECT_ALLOCATION_FAILURE"},
    {-5, "CL_OUT_OF_RESOURCES"},
    {-6, "CL_OUT_OF_HOST_MEMORY"},
    {-7, "CL_PROFILING_INFO_NOT_AVAILABLE"},
    {-8, "CL_MEM_COPY_OVERLAP"},
    {-9, "CL_IMAGE_FORMAT_MISMATCH"},
    {-10, "CL_IMAGE_FORMAT_NOT_SUPPORTED"},
    {-11, "CL_BUILD_PROGRAM_FAILURE"},
    {-12, "CL_MAP_FAILURE"},
    {-13, "CL_MISALIGNED_SUB_BUFFER_OFFSET"},
    {-14, "CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST"},
    {-15, "CL_COMPILE_PROGRAM_FAILURE"},
    {-16, "CL_LINKER_NOT_AVAILABLE"},
    {-17, "CL_LINK_PROGRAM_FAILURE"},
    {-18, "CL_DEVICE_PARTITION_FAILED"},
    {-19, "CL_KERNEL_ARG_INFO_NOT_AVAILABLE"},
    {-30, "CL_INVALID_VALUE"},
    {-31, "CL_INVALID_DEVICE_TYPE"},
    {-32, "CL_INVALID_PLATFORM"},
    {-33, "CL_INVALID_DEVICE"},
    {-34, "CL_INVALID_CONTEXT"},
    {-35, "CL_INVALID_QUEUE_PROPERTIES"},
    {-36, "CL_INVALID_COMMAND_QUEUE"},
    {-37, "CL_INVALID_HOST_PTR"},
    {-38, "CL_INVALID_MEM_OBJECT"},
    {-39, "CL_INVALID_IMAGE_FORMAT_DESCRIPTOR"},
    {-40, "CL_INVALID_IMAGE_SIZE"},
    {-41, "CL_INVALID_SAMPLER"},
    {-42, "CL_INVALID_BINARY"},
    {-43, "CL_INVALID_BUILD_OPTIONS"},
    {-44, "CL_INVALID_PROGRAM"},
    {-45, "CL_INVALID_PROGRAM_EXECUTABLE"},
    {-46, "CL_INVALID_KERNEL_NAME"},
    {-47, "CL_INVALID_KERNEL_DEFINITION"},
    {-48, "CL_INVALID_KERNEL"},
    {-49, "CL_INVALID_ARG_INDEX"},
    {-50, "CL_INVALID_ARG_VALUE"},
    {-51, "CL_INVALID_ARG_SIZE"},
    {-52, "CL_INVALID_KERNEL_ARGS"},
    {-53, "CL_INVALID_WORK_DIMENSION"},
    {-54, "CL_INVALID_WORK_GROUP_SIZE"},
    {-55, "CL_INVALID_WORK_ITEM_SIZE"},
    {-56, "CL_INVALID_GLOBAL_OFFSET"},
    {-57, "CL_INVALID_EVENT_WAIT_LIST"},
    {-58, "CL_INVALID_EVENT"},
    {-59, "CL_INVALID_OPERATION"},
    {-60, "CL_INVALID_GL_OBJECT"},
    {-61, "CL_INVALID_BUFFER_SIZE"},
    {-62, "CL_INVALID_MIP_LEVEL"},
    {-63, "CL_INVALID_GLOBAL_WORK_SIZE"},
    {-64, "CL_INVALID_PROPERTY"},
    {-65, "CL_INVALID_IMAGE_DESCRIPTOR"},
    {-66, "CL_INVALID_COMPILER_OPTIONS"},
    {-67, "CL_INVALID_LINKER_OPTIONS"},
    {-68, "CL_INVALID_DEVICE_PARTITION_COUNT"},
    {-69, "CL_INVALID_PIPE_SIZE"},
    {-70, "CL_INVALID_DEVICE_QUEUE"},
    {-71, "CL_INVALID_SPEC_ID"},
    {-72, "CL_MAX_SIZE_RESTRICTION_EXCEEDED"},
    {-1001, "CL_PLATFORM_NOT_FOUND_KHR"},
};

constexpr const char* kNoPlatform = "no OpenCL platform found; install pocl-opencl-icd";

std::string trim(std::string s) {
  while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back())))) s.pop_back();
  std::size_t b = 0;
  while (b < s.size() && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  return s.substr(b);
}

std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = char(std::tolower(static_cast<unsigned char>(c)));
  return r;
}

std::string typeName(cl_device_type type) {
  if (type & CL_DEVICE_TYPE_GPU) return "gpu";
  if (type & CL_DEVICE_TYPE_CPU) return "cpu";
  if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

// "0: PoCL / pthread-... (cpu), 1: ..." for error messages.
std::string listing(const std::vector<ClDeviceEntry>& all) {
  std::string s;
  for (const ClDeviceEntry& e : all) {
    if (!s.empty()) s += ", ";
    s += std::to_string(e.index) + ": " + e.describe() + " (" + typeName(e.type) + ")";
  }
  return s;
}

const ClDeviceEntry* firstOfType(const std::vector<ClDeviceEntry>& all, cl_device_type type) {
  for (const ClDeviceEntry& e : all)
    if (e.type & type) return &e;
  return nullptr;
}

ClDeviceEntry selectDevice(std::string_view selector) {
  const std::vector<ClDeviceEntry> all = ClRunner::devices();
  const std::string s = lower(trim(std::string(selector)));
  const std::string valid = "valid: auto, cpu, gpu, or a device index 0.." + std::to_string(all.size() - 1) +
                            " (" + listing(all) + ")";
  if (s == "auto" || s.empty()) {
    if (const ClDeviceEntry* e = firstOfType(all, CL_DEVICE_TYPE_GPU)) return *e;
    if (const ClDeviceEntry* e = firstOfType(all, CL_DEVICE_TYPE_CPU)) return *e;
    return all.front();
  }
  if (s == "cpu" || s == "gpu") {
    if (const ClDeviceEntry* e = firstOfType(all, s == "cpu" ? CL_DEVICE_TYPE_CPU : CL_DEVICE_TYPE_GPU)) return *e;
    throw ClError(std::string("no OpenCL ") + (s == "cpu" ? "CPU" : "GPU") + " device; available: " + listing(all),
                  CL_DEVICE_NOT_FOUND);
  }
  if (std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }) &&
      s.size() < 9) {
    const std::size_t n = std::stoul(s);
    if (n < all.size()) return all[n];
    throw ClError("OpenCL device index " + s + " is out of range; " + valid, CL_DEVICE_NOT_FOUND);
  }
  throw ClError("invalid OpenCL device selector '" + std::string(selector) + "'; " + valid, CL_INVALID_VALUE);
}

}  // namespace

const char* clErrorName(cl_int code) {
  for (const NamedCode& n : kClErrorNames)
    if (n.code == code) return n.name;
  thread_local std::string unknown;
  unknown = "CL_ERROR_" + std::to_string(code);
  return unknown.c_str();
}

ClError::ClError(const std::string& message, cl_int code, std::string buildLog)
    : Error(message), code_(code), buildLog_(std::move(buildLog)) {}

const char* ClError::codeName() const { return clErrorName(code_); }

void throwClError(const cl::Error& error, std::string_view doing) {
  std::string message(doing);
  message += ": ";
  if (error.what() && *error.what()) message += std::string(error.what()) + " failed: ";
  message += std::string(clErrorName(error.err())) + " (" + std::to_string(error.err()) + ")";
  throw ClError(message, error.err());
}

std::string ClDeviceEntry::describe() const { return platformName + " / " + deviceName; }

std::vector<ClDeviceEntry> ClRunner::devices() {
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error& e) {
    // The ICD loader reports a missing platform as CL_PLATFORM_NOT_FOUND_KHR.
    if (e.err() == -1001) throw ClError(kNoPlatform, e.err());
    throwClError(e, "listing OpenCL platforms");
  }
  if (platforms.empty()) throw ClError(kNoPlatform, -1001);
  std::vector<ClDeviceEntry> all;
  for (cl::Platform& platform : platforms) {
    std::vector<cl::Device> devs;
    std::string platformName;
    try {
      platformName = trim(platform.getInfo<CL_PLATFORM_NAME>());
      platform.getDevices(CL_DEVICE_TYPE_ALL, &devs);
    } catch (const cl::Error& e) {
      if (e.err() == CL_DEVICE_NOT_FOUND) continue;  // a platform without devices
      throwClError(e, "listing the devices of OpenCL platform '" + platformName + "'");
    }
    for (cl::Device& device : devs) {
      ClDeviceEntry e;
      e.index = int(all.size());
      e.platformName = platformName;
      try {
        e.deviceName = trim(device.getInfo<CL_DEVICE_NAME>());
        e.type = device.getInfo<CL_DEVICE_TYPE>();
      } catch (const cl::Error& err) {
        throwClError(err, "querying a device of OpenCL platform '" + platformName + "'");
      }
      e.platform = platform;
      e.device = device;
      all.push_back(std::move(e));
    }
  }
  if (all.empty()) throw ClError("no OpenCL device found (platforms exist but list no device)", CL_DEVICE_NOT_FOUND);
  return all;
}

ClRunner::ClRunner(std::string_view selector) : entry_(selectDevice(selector)) {
  try {
    context_ = cl::Context(entry_.device);
    queue_ = cl::CommandQueue(context_, entry_.device);
  } catch (const cl::Error& e) {
    throwClError(e, "creating an OpenCL context and queue on " + describe());
  }
}

cl::Program ClRunner::program(std::string_view source, const std::string& options) {
  std::lock_guard<std::mutex> lock(cacheMutex_);
  auto key = std::make_pair(std::string(source), options);
  if (auto it = programs_.find(key); it != programs_.end()) return it->second;
  cl::Program program;
  try {
    program = cl::Program(context_, key.first);
  } catch (const cl::Error& e) {
    throwClError(e, "creating an OpenCL program on " + describe());
  }
  try {
    program.build(std::vector<cl::Device>{entry_.device}, options.c_str());
  } catch (const cl::BuildError& e) {
    std::string log;
    for (const auto& [device, text] : e.getBuildLog()) log += trim(text);
    std::string message = "building an OpenCL program";
    if (!options.empty()) message += " with options '" + options + "'";
    message += " on " + describe() + " failed: " + clErrorName(e.err());
    message += log.empty() ? std::string(" (the compiler left no log)") : "\n" + log;
    throw ClError(message, e.err(), log);
  } catch (const cl::Error& e) {
    throwClError(e, "building an OpenCL program on " + describe());
  }
  programs_.emplace(std::move(key), program);
  return program;
}

cl::Kernel ClRunner::kernel(std::string_view source, const std::string& name, const std::string& options) {
  cl::Program p = program(source, options);
  try {
    return cl::Kernel(p, name.c_str());
  } catch (const cl::Error& e) {
    throwClError(e, "creating OpenCL kernel '" + name + "'");
  }
}

std::size_t ClRunner::cachedPrograms() const {
  std::lock_guard<std::mutex> lock(cacheMutex_);
  return programs_.size();
}

cl::Buffer ClRunner::allocate(std::size_t bytes, cl_mem_flags flags) {
  try {
    return cl::Buffer(context_, flags, bytes == 0 ? 1 : bytes);
  } catch (const cl::Error& e) {
    throwClError(e, "allocating a " + std::to_string(bytes) + "-byte buffer on " + describe());
  }
}

std::string ClRunner::kernelName(cl::Kernel& kernel) {
  try {
    return "kernel '" + trim(kernel.getInfo<CL_KERNEL_FUNCTION_NAME>()) + "'";
  } catch (const cl::Error&) {
    return "the kernel";
  }
}

void ClRunner::enqueue(std::string_view description, cl::Kernel& kernel, std::size_t count, std::size_t groupSize) {
  if (count == 0) return;
  try {
    queue_.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(count),
                                groupSize ? cl::NDRange(groupSize) : cl::NullRange);
  } catch (const cl::Error& e) {
    throwClError(e, std::string(description) + ": launching " + kernelName(kernel) + " over " +
                        std::to_string(count) + " items on " + describe());
  }
}

void ClRunner::finish() {
  try {
    queue_.finish();
  } catch (const cl::Error& e) {
    throwClError(e, "waiting for the OpenCL queue on " + describe());
  }
}

}  // namespace fcc
