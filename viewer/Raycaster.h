// The brick-paged FCC isosurface raycaster (shaders/raycast.comp) and its streaming: bricks the rays
// request are decoded through the host cache, uploaded into pool slots (least recently used ones are
// evicted), and the frame continues where each ray stopped. A frame completes in as many passes as
// the pool size requires, so the image does not depend on the cache budgets.
// Needs a current OpenGL 4.5 context (fcc::EglContext, or the viewer's window).
#pragma once

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "Camera.h"
#include "GlProgram.h"
#include "Residency.h"
#include "io/BrickCache.h"
#include "io/BrickStore.h"

namespace fcc::render {

struct RenderOptions {
  std::size_t gpuCacheBytes = std::size_t(512) << 20;   // the brick pool
  std::size_t hostCacheBytes = std::size_t(512) << 20;  // decoded bricks in host memory
  bool skipEmpty = true;   // skip nodes and bricks whose bounds exclude the isovalue
  int lookahead = 2;       // bricks a stopped ray requests beyond its first missing one
  bool finiteDifferenceNormals = false;  // central differences instead of the analytic gradient
  glm::vec3 surfaceColor{0.85f, 0.72f, 0.52f};
};

// The output of a frame, row 0 at the top.
struct FrameImages {
  int width = 0, height = 0;
  std::vector<float> rgba;         // premultiplied shaded colour, 4 per pixel; A = 1 on a hit
  std::vector<float> normalDepth;  // unit world gradient direction, then depth (+inf on a miss)
};

struct FrameStats {
  int passes = 0;
  uint64_t bricksUploaded = 0;
  uint64_t bricksNeeded = 0;     // bricks whose bounds hold the isovalue
  double seconds = 0.0;
};

class Raycaster {
 public:
  Raycaster(const io::BrickStore& store, const RenderOptions& options);
  ~Raycaster();

  // Bricks needed change; resident ones stay (no preprocessing, no reload for a revisited isovalue).
  void setIso(float iso);
  float iso() const { return iso_; }

  // Renders a complete frame, passes and uploads until no ray waits for a brick.
  FrameStats render(const Camera& camera, int width, int height);
  FrameImages readImages() const;

  uint32_t slotCount() const { return residency_->slotCount(); }
  const io::BrickCache& hostCache() const { return *hostCache_; }
  uint32_t residentCount() const { return residency_->residentCount(); }
  const RenderOptions& options() const { return options_; }
  // Switches skipping or the normals without reloading anything (for benchmarks and the viewer).
  void setSkipEmpty(bool skip);
  void setFiniteDifferenceNormals(bool on) { options_.finiteDifferenceNormals = on; }

 private:
  void prepareImages(int width, int height);
  uint32_t dispatchPass(const CameraFrame& frame, int width, int height);
  uint64_t loadRequested(uint32_t requestCount);
  void uploadPageTable();
  void computeSlotBounds(const std::vector<uint32_t>& slots);

  const io::BrickStore& store_;
  RenderOptions options_;
  float iso_ = 0.0f;
  uint32_t pass_ = 0;
  uint32_t requestCapacity_ = 0;
  std::unique_ptr<Residency> residency_;
  std::unique_ptr<io::BrickCache> hostCache_;
  GlProgram program_, slotBoundsProgram_;
  std::unique_ptr<GlBuffer> pool_, slotBounds_, uploadedSlots_, pageTable_, nodeTable_, requests_, requestBits_, slotUse_;
  GlTexture2D color_, normalDepth_, resume_;
};

}  // namespace fcc::render
