#include "ClBrickKernels.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <unordered_map>

#include "embedded_kernels.h"
#include "sparse/BrickBounds.h"

namespace fcc {
namespace {

using openvdb::Coord;
using FccLeaf = FccTree::LeafNodeType;
static_assert(sizeof(openvdb::Vec4f) == sizeof(cl_float4) && sizeof(openvdb::Vec2f) == sizeof(cl_float2),
              "VDB vectors and OpenCL vectors share a layout");

constexpr std::size_t kMaxGroupSize = 128;
// Bricks per launch: keeps the staged pool (up to 27 leaves of 8 KiB per brick, usually about one)
// and the results bounded.
constexpr std::size_t kLaunchBricks = 4096;

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

// One launch's inputs: the leaves the bricks read, their neighbour tables, the constant values.
struct ClBrickKernels::Staged {
  std::vector<openvdb::Vec4f> pool;
  std::vector<cl_int> neighbours;
  std::vector<openvdb::Vec4f> constants;

  void stage(const FccGrid& grid, const Coord* bricks, std::size_t count) {
    pool.clear();
    neighbours.clear();
    constants.clear();
    neighbours.reserve(count * 27);
    std::unordered_map<const FccLeaf*, cl_int> slots;
    auto accessor = grid.getConstAccessor();
    for (std::size_t i = 0; i < count; ++i)
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const Coord b = bricks[i].offsetBy(dx, dy, dz);
            const Coord packed(b.x() * kBrickPackedDim, b.y() * kBrickPackedDim, b.z() * kBrickPackedDim);
            if (const FccLeaf* leaf = accessor.probeConstLeaf(packed)) {
              auto [it, added] = slots.try_emplace(leaf, cl_int(slots.size()));
              if (added) pool.insert(pool.end(), leaf->buffer().data(), leaf->buffer().data() + FccLeaf::SIZE);
              neighbours.push_back(it->second);
            } else {
              // No leaf: the whole neighbour brick is one tile value or the background.
              const openvdb::Vec4f& v = accessor.getValue(packed);
              auto found = std::find(constants.begin(), constants.end(), v);
              if (found == constants.end()) found = constants.insert(constants.end(), v);
              neighbours.push_back(-1 - cl_int(found - constants.begin()));
            }
          }
  }
};

ClBrickKernels::ClBrickKernels(std::string_view selector) : runner_(std::make_unique<ClRunner>(selector)) {
  std::size_t maxGroup = kMaxGroupSize;
  try {
    maxGroup = runner_->device().getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
  } catch (const cl::Error& e) {
    throwClError(e, "querying the work-group size of " + runner_->describe());
  }
  groupSize_ = 1;
  while (groupSize_ * 2 <= std::min(maxGroup, kMaxGroupSize)) groupSize_ *= 2;
  const std::string source(embedded::kernels("kernels/preprocess.cl"));
  const std::string options = "-DFCC_GROUP_SIZE=" + std::to_string(groupSize_);
  boundsKernel_ = runner_->kernel(source, "fcc_brick_bounds", options);
  prefilterKernel_ = runner_->kernel(source, "fcc_brick_prefilter", options);
}

ClBrickKernels::~ClBrickKernels() = default;

std::string ClBrickKernels::describe() const { return "OpenCL: " + runner_->describe(); }

void ClBrickKernels::bounds(const FccGrid& coefficients, const std::vector<Coord>& bricks,
                            std::vector<openvdb::Vec2f>& out) {
  out.resize(bricks.size());
  Staged staged;
  for (std::size_t first = 0; first < bricks.size(); first += kLaunchBricks) {
    const std::size_t count = std::min(kLaunchBricks, bricks.size() - first);
    staged.stage(coefficients, bricks.data() + first, count);
    cl::Buffer pool = runner_->upload(staged.pool), table = runner_->upload(staged.neighbours),
               constants = runner_->upload(staged.constants);
    cl::Buffer results = runner_->allocate(count * sizeof(cl_float2), CL_MEM_WRITE_ONLY);
    const auto start = std::chrono::steady_clock::now();
    runner_->launchGroups("brick bounds", boundsKernel_, count, groupSize_, pool, table, constants, results);
    runner_->finish();
    computeSeconds += secondsSince(start);
    std::vector<openvdb::Vec2f> part(count);
    runner_->download(results, part);
    std::copy(part.begin(), part.end(), out.begin() + std::ptrdiff_t(first));
  }
}

void ClBrickKernels::prefilter(const FccGrid& samples, const std::vector<Coord>& bricks,
                               std::vector<openvdb::Vec4f>& out) {
  out.resize(bricks.size() * FccLeaf::SIZE);
  Staged staged;
  for (std::size_t first = 0; first < bricks.size(); first += kLaunchBricks) {
    const std::size_t count = std::min(kLaunchBricks, bricks.size() - first);
    staged.stage(samples, bricks.data() + first, count);
    cl::Buffer pool = runner_->upload(staged.pool), table = runner_->upload(staged.neighbours),
               constants = runner_->upload(staged.constants);
    cl::Buffer results = runner_->allocate(count * FccLeaf::SIZE * sizeof(cl_float4), CL_MEM_WRITE_ONLY);
    const auto start = std::chrono::steady_clock::now();
    runner_->launchGroups("brick prefilter", prefilterKernel_, count, groupSize_, pool, table, constants, results);
    runner_->finish();
    computeSeconds += secondsSince(start);
    try {
      runner_->queue().enqueueReadBuffer(results, CL_TRUE, 0, count * FccLeaf::SIZE * sizeof(cl_float4),
                                         out.data() + first * FccLeaf::SIZE);
    } catch (const cl::Error& e) {
      throwClError(e, "downloading prefiltered bricks from " + runner_->describe());
    }
  }
}

std::string checkDeviceSelector(std::string_view selector) {
  std::string s(selector);
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (s == "reference" || s == "auto" || s == "cpu" || s == "gpu") return {};
  if (!s.empty() && s.size() < 9 && std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
    return {};
  return "invalid OpenCL device '" + std::string(selector) + "'; valid: " + kDeviceSelectorHelp;
}

std::unique_ptr<BrickKernels> makeBrickKernels(std::string_view selector) {
  if (const std::string complaint = checkDeviceSelector(selector); !complaint.empty()) throw ValueError(complaint);
  std::string s(selector);
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (s == "reference") return makeReferenceBrickKernels();
  try {
    return std::make_unique<ClBrickKernels>(selector);
  } catch (const ClError& e) {
    // Unusable OpenCL falls back; a request for a device that is not there is the user's to fix.
    const bool noPlatform = e.code() == -1001;
    const bool noDeviceAtAll = e.code() == CL_DEVICE_NOT_FOUND && s == "auto";
    const bool noCompiler = e.code() == CL_BUILD_PROGRAM_FAILURE || e.code() == CL_COMPILER_NOT_AVAILABLE ||
                            e.code() == CL_INVALID_BUILD_OPTIONS;
    if (!noPlatform && !noDeviceAtAll && !noCompiler) throw;
    std::string reason = e.what();
    reason = reason.substr(0, reason.find('\n'));  // a build failure's log follows on further lines
    std::fprintf(stderr, "fccvdb: OpenCL unavailable (%s): using the CPU reference path\n", reason.c_str());
    return makeReferenceBrickKernels();
  }
}

}  // namespace fcc
