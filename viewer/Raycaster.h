// The brick-paged isosurface raycaster (shaders/raycast.comp) over any lattice's brick source
// (viewer/BrickSource.h: an FCC .vdb, or a Cartesian grid rendered as it is with a CC reconstruction),
// and its streaming: bricks the rays request are decoded on the loader thread (viewer/BrickLoader.h), uploaded
// into pool slots (least recently used ones are evicted), and the frame continues where each ray
// stopped. A frame completes in as many passes as the pool size requires, so the image does not
// depend on the cache budgets. Two ways to drive it: render() completes a frame before it returns
// (`fccvdb render`, benchmarks); step() runs one pass per call and never waits for the file (the
// interactive viewer, which shows the image refining while bricks arrive).
// Needs a current OpenGL 4.5 context (fcc::EglContext, or the viewer's window).
#pragma once

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "BrickLoader.h"
#include "BrickPool.h"
#include "DvrLight.h"
#include "DvrTableGpu.h"
#include "BrickSource.h"
#include "Camera.h"
#include "GlProgram.h"
#include "GpuTimer.h"
#include "PixelRect.h"
#include "Residency.h"
#include "io/BrickStore.h"
#include "sparse/TransferFunction.h"

namespace fcc::render {

// What a ray shows: the first isosurface crossing, or emission and absorption through the volume.
enum class RenderMode { Iso, Dvr };
std::string renderModeName(RenderMode mode);  // "iso", "dvr"
RenderMode parseRenderMode(const std::string& name);  // ValueError naming the valid ones

// One isosurface of several drawn at once: its value, colour (linear RGB) and opacity in [0, 1].
struct Isosurface {
  float iso = 0.0f;
  glm::vec3 color{0.85f, 0.72f, 0.52f};
  float opacity = 1.0f;
  bool operator==(const Isosurface& o) const { return iso == o.iso && color == o.color && opacity == o.opacity; }
  bool operator!=(const Isosurface& o) const { return !(*this == o); }
};
inline constexpr int kMaxIsosurfaces = 4;
// The default colour of surface `index` (0: RenderOptions::surfaceColor's default), linear RGB.
glm::vec3 defaultSurfaceColor(int index);

struct RenderOptions {
  RenderMode mode = RenderMode::Iso;
  float iso = std::numeric_limits<float>::quiet_NaN();  // NaN: midway through the data's value range
  // RenderMode::Dvr: the transfer function as the GPU reads it (sparse/TransferFunction.h; its optical
  // scale applied); bricks and cells whose values it maps to zero extinction are skipped.
  std::shared_ptr<const TransferTable> transfer;
  // DVR: gradient shading, its highlight and its light (viewer/DvrLight.h; shaders/dvr.glsl; docs/DVR.md).
  DvrShading dvrShading;
  // FCC DVR: gather every piece of a unit cell's chord and sub-step each by itself, instead of the chord
  // from its two end pieces sub-stepped as one (shaders/march_fcc.glsl; docs/DVR.md, "A cell's chord
  // from its end pieces"). Slower; the images differ only by where the sub-steps lie: the reference the
  // tests compare with.
  bool dvrGatherCentral = false;
  float terminationOpacity = 0.995f;  // DVR: a ray stops once this opaque (and asks for no brick behind)
  // The clipping box, world space: rays are cut to it and bricks outside it are never loaded. The
  // default holds everything.
  glm::dvec3 clipLo{-1e30}, clipHi{1e30};
  // Sort-last distributed rendering (tools/mpi/, docs/MPI.md): the bricks this process renders. The
  // others are treated as bricks without the isovalue: never loaded, and rays pass them as skipped
  // bricks, so that the cells a process does march are marched from the same t as by one process
  // alone. Empty: every brick.
  std::function<bool(const glm::ivec3&)> ownsBrick;
  std::size_t gpuCacheBytes = std::size_t(512) << 20;   // the brick pool
  std::size_t hostCacheBytes = std::size_t(512) << 20;  // decoded bricks in host memory
  // How the pool stores bricks (viewer/BrickPool.h); unset: chooseBrickLayout below.
  std::optional<BrickLayout> layout;
  // Pixels per raycasting work group: 4x8 (one warp) measured fastest on the H200 (docs/BENCHMARKS.md).
  glm::ivec2 workGroup{4, 8};
  bool skipEmpty = true;   // skip nodes and bricks whose bounds exclude the isovalue
  // Bricks a stopped ray requests beyond its first missing one; kLookaheadAuto: none for render()'s
  // complete frames of one opaque isosurface at full resolution (a pass is cheaper than the file reads
  // of bricks requested ahead: the H200's full turn of blobs 2048^3 at 4x the GPU cache, 30.6-33.9 fps
  // against 27.2-28.7 with 2), two for step()'s progressive frames and with levels of detail (their
  // streams and full turn were faster with 2; docs/BENCHMARKS.md, session 13).
  static constexpr int kLookaheadAuto = -1;
  int lookahead = kLookaheadAuto;
  bool finiteDifferenceNormals = false;  // central differences instead of the analytic gradient
  bool timeGpu = false;    // time every raycasting pass on the GPU (FrameStats::gpuSeconds; benchmarks)
  // Count the bricks each pass drew (StepStats/FrameStats::bricksPerLevel; `bench stream`): reads the
  // pool slots' pass stamps back after the pass (4 bytes a slot), which the viewer does not pay for.
  bool countBricksDrawn = false;
  // Requested bricks read back with a pass's header (16 KiB); a pass asking for more reads the rest
  // from the buffer itself, which waits for anything queued after the pass. (Tests lower it.)
  uint32_t requestsReadBack = 4096;
  glm::vec3 surfaceColor{0.85f, 0.72f, 0.52f};  // the first surface's (`iso`'s) colour
  float surfaceOpacity = 1.0f;                  // and its opacity
  // Surfaces 2 to kMaxIsosurfaces. With any of them, or surfaceOpacity < 1, rays composite every
  // crossing front to back (the FCC_MULTI_ISO variant of shaders/raycast.comp) until the remaining
  // transmittance falls below 1 - terminationOpacity; else the first crossing is the pixel, as always.
  std::vector<Isosurface> moreSurfaces;
  // Direction towards the light in camera space: x right, y up, z towards the viewer.
  glm::vec3 lightInCamera = kDefaultLightInCamera;
  // Level of detail (docs/RENDERER.md, "Level of detail"): the pyramid's coarser levels, level 1 first
  // (sources whose index space is level 0's scaled by 2^-k; they outlive the raycaster). Empty: level 0
  // only, the full-resolution program and image, as without a pyramid. Drawn for the single opaque
  // isosurface only (DVR, several or translucent surfaces and ownsBrick stay at full resolution).
  std::vector<const BrickSource*> coarserLevels;
  // Added to log2 of a brick's pixels per level-0 voxel to choose its level: 0 draws the coarsest level
  // whose voxels are no larger than a pixel; > 0 coarser, < 0 finer.
  float lodBias = 0.0f;
  // Raise the bias (by whole levels) for the next frames when the GPU pool cannot hold the bricks a
  // frame wants, instead of streaming them through it pass after pass; lower it back once a frame
  // uses under an eighth of the pool.
  bool lodAdaptBias = true;
};

// The most pyramid levels the raycaster draws (shaders/raycast.comp's FCC_MAX_LEVELS).
inline constexpr int kMaxLodLevels = 16;

// Every surface of `options`: iso, surfaceColor and surfaceOpacity first, then moreSurfaces.
std::vector<Isosurface> surfacesOf(const RenderOptions& options);
// Whether `options` needs the compositing variant (several surfaces, or a translucent one).
bool compositesSurfaces(const RenderOptions& options);

// The layout when none is asked for, by measurement (docs/BENCHMARKS.md, H200): the one-channel
// embedding is 10-15% faster than the four-channel packing, but a brick costs twice the GPU bytes,
// and when the data outgrows the pool that halves what stays resident (10x slower while
// streaming). So: texture-scalar when every brick whose bounds vary fits the budget, else
// texture-vec4 (3D textures measured 2-3% ahead of SSBOs in long runs). A source of site blocks
// (SlotBlock::Sites) or of BCC cosets (BccPacked) has one channel: texture-scalar.
BrickLayout chooseBrickLayout(const BrickSource& source, std::size_t gpuCacheBytes);

// The output of a frame, row 0 at the top.
struct FrameImages {
  int width = 0, height = 0;
  std::vector<float> rgba;         // premultiplied shaded colour, 4 per pixel; A = 1 on a hit (several
                                   // surfaces: A = 1 - the transmittance left)
  std::vector<float> normalDepth;  // unit world gradient direction, then depth (+inf on a miss): the
                                   // first surface crossed
};

// Which pyramid levels a frame drew from.
struct LevelMix {
  // Per level (level 0 first; one entry without levels): the bricks the frame drew for rays that wanted
  // their level (a complete frame: the bricks its image is drawn from). Without levels: the bricks its
  // passes read plus those it loaded.
  std::vector<uint64_t> bricksPerLevel;
  // Per level: bricks drawn in the frame's passes as stand-ins for finer ones not yet resident (a
  // complete frame's image shows none of them; a progressive frame's may).
  std::vector<uint64_t> standInBricksPerLevel;
  // Of the pixels whose ray hit the surface, the share whose hit was drawn from level 0 (1 when no
  // pixel hit, or without levels). Progressive frames count final hits only. DVR (no hits): the share
  // of the bricks drawn that are level 0's.
  double fullResolutionFraction = 1.0;
  double lodBias = 0.0;  // the bias in effect: RenderOptions::lodBias plus what the renderer added
};

struct FrameStats {
  int passes = 0;
  uint64_t bricksUploaded = 0;
  uint64_t bricksNeeded = 0;     // bricks whose bounds hold the isovalue (every level's)
  double seconds = 0.0;
  double gpuSeconds = 0.0;       // the passes on the GPU alone (RenderOptions::timeGpu; else 0)
  // Bricks drawn per level of detail, level 0 first (LevelMix::bricksPerLevel), and the share of hit
  // pixels drawn from level 0: RenderOptions::countBricksDrawn (else empty and 1).
  std::vector<uint64_t> bricksPerLevel;
  double fullResolutionFraction = 1.0;
  double lodBias = 0.0;                  // LevelMix::lodBias at the frame's end
  int lodRestarts = 0;                   // times the frame started over with a raised bias
};

// What one step() of a progressive frame did.
struct StepStats {
  bool restarted = false;      // the view or a setting changed: every ray started over
  bool complete = false;       // every ray has finished: the image is final for this view
  bool dispatched = false;     // a pass ran (a complete frame needs none)
  uint32_t requested = 0;      // bricks the pass's rays asked for (where they stopped, and look-ahead)
  uint32_t missing = 0;        // of those, the bricks rays stopped at: their pixels wait for them
  uint32_t uploaded = 0;       // bricks uploaded into the pool this step
  uint64_t bytesUploaded = 0;  // the blocks of those bricks, as staged for the GPU
  std::size_t streaming = 0;   // bricks queued or decoding on the loader thread
  double gpuSeconds = 0.0;     // the pass on the GPU alone (RenderOptions::timeGpu; else 0)
  double uploadSeconds = 0.0;  // wall time of the step's uploads (before its pass)
  double dispatchSeconds = 0.0; // wall time of issuing the pass (the restart's clearing included)
  double passSeconds = 0.0;    // wall time of finishStep()'s wait for the pass and its results
  double requestSeconds = 0.0; // wall time of turning the pass's requests into the loader's queue
  // Resident bricks the pass's rays drew, per level of detail, level 0 first
  // (RenderOptions::countBricksDrawn; else empty). One level so far.
  std::vector<uint64_t> bricksPerLevel;
  double fullResolutionFraction = 1.0;  // share of hit pixels drawn from level-0 bricks (1: one level)
};

class Raycaster {
 public:
  // `source` outlives the raycaster.
  Raycaster(const BrickSource& source, const RenderOptions& options);
  // An FCC .vdb through a host cache of options.hostCacheBytes (an FccBrickSource of its own).
  Raycaster(const io::BrickStore& store, const RenderOptions& options);
  ~Raycaster();

  // Bricks needed change; resident ones stay (no preprocessing, no reload for a revisited isovalue).
  void setIso(float iso);
  // Every surface at once (1 to kMaxIsosurfaces; the first becomes iso/surfaceColor/surfaceOpacity):
  // bricks needed change as for setIso; the shader variant follows compositesSurfaces. ValueError for
  // an empty or too long list, a value that is not finite or an opacity outside [0, 1].
  void setSurfaces(const std::vector<Isosurface>& surfaces);
  std::vector<Isosurface> surfaces() const { return surfacesOf(options_); }
  // DVR: another transfer function (the same: bricks needed change, resident ones stay).
  void setTransfer(std::shared_ptr<const TransferTable> transfer);
  // How often the bricks needed were recomputed (a walk of the bricks and a page-table upload): a
  // transfer function whose zero entries did not move costs none (setTransfer).
  uint64_t neededUpdates() const { return neededUpdates_; }
  // Another clipping box (world space; lo > hi on an axis: nothing shows). Bricks needed change.
  void setClip(const glm::dvec3& lo, const glm::dvec3& hi);
  float iso() const { return options_.iso; }

  // Renders a complete frame, passes and uploads until no ray waits for a brick.
  FrameStats render(const Camera& camera, int width, int height);
  // One step of a progressive frame: starts the rays over when the camera, the size, the isovalue
  // or an option changed since the last step; uploads bricks the loader has finished, for at most
  // `uploadSeconds` (at least one batch); runs one pass continuing every waiting ray unless the frame
  // is complete; queues the bricks the rays asked for. Pixels of rays still waiting show the
  // background. Never waits for the file. The first `coveredColumns` columns are hidden under
  // something opaque (the viewer's panel): no rays are cast there and the image keeps what it had.
  StepStats step(const Camera& camera, int width, int height, double uploadSeconds, int coveredColumns = 0);
  // step() in two halves, so that the caller can work on the CPU while the pass runs on the GPU (the
  // viewer builds its panel): startStep() does everything up to the pass's dispatch, finishStep()
  // waits for the pass and queues the bricks its rays asked for. Calls alternate.
  void startStep(const Camera& camera, int width, int height, double uploadSeconds, int coveredColumns = 0);
  StepStats finishStep();
  // The last frame's images; `withNormalDepth` false leaves normalDepth empty (a PNG needs only colour).
  FrameImages readImages(bool withNormalDepth = true) const;
  // The colour image (RGBA32F, premultiplied, row 0 at the top) for drawing on screen.
  const GlTexture2D& colorTexture() const { return color_; }
  // The normal and depth image (RGBA32F as FrameImages::normalDepth, row 0 at the top): the viewer
  // reads the pixel under its cursor.
  const GlTexture2D& normalDepthTexture() const { return normalDepth_; }
  // The pixels of the colour image that show the surface (A = 1), as of the last pass; the rest shows
  // the background. Empty when no ray hit.
  PixelRect surfaceRect() const { return surfaceRect_; }
  // The same on the GPU, where a pass leaves it, for drawing before the pass's results are read back
  // (startStep() then finishStep()): after the request count (uint32), the int32s first column,
  // first row, last column, last row (last < first: no surface); kPassResultsHeaderBytes in all.
  const GlBuffer& passResults() const { return *requests_; }
  static constexpr std::size_t kPassResultsHeaderBytes = 5 * sizeof(uint32_t);

  uint32_t slotCount() const { return residency_->slotCount(); }
  // Of every level drawn: level 0's source and the pyramid's coarser levels.
  HostCacheUse hostCacheUse() const {
    HostCacheUse sum;
    for (const BrickSource* level : levelSources_) {
      const HostCacheUse use = level->hostCacheUse();
      sum.bytesUsed += use.bytesUsed;
      sum.budgetBytes += use.budgetBytes;
    }
    return sum;
  }
  const BrickSource& source() const { return source_; }
  uint32_t residentCount() const { return residency_->residentCount(); }
  std::size_t neededCount() const { return residency_->neededCount(); }
  std::size_t missingCount() const { return residency_->missingCount(); }
  std::size_t slotBytes() const;  // GPU bytes one resident brick costs (data and cell bounds)
  std::size_t poolBytes() const;  // slotCount() * slotBytes()
  uint64_t bricksUploaded() const { return bricksUploaded_; }  // since construction
  // The bricks the last pass that asked for any asked for, stopping rays' first (tests, statistics):
  // level 0's (coordinates of every level with levelRequests()).
  std::vector<glm::ivec3> lastRequests() const;
  // The same with their levels, coarsest level first (the order they are loaded in).
  const std::vector<LevelBrick>& lastLevelRequests() const { return lastRequests_; }
  // Level of detail: the levels drawn (1 without, or when the mode cannot draw them), the bias in
  // effect, and the mix of the last frame (render()) or of the progressive frame so far (reads the
  // GPU's per-slot use: not for every frame of a benchmark).
  int levelCount() const { return lodDrawing() ? residency_->levelCount() : 1; }
  double lodBias() const { return double(options_.lodBias) + double(autoBias_); }
  LevelMix levelMix() const { return levelMix(viewFirstPass_); }
  LevelMix levelMix(uint32_t firstPass) const;  // counting the slots drawn from pass `firstPass` on
  // Whether every needed brick of the coarsest level is resident (a progressive frame's rays never
  // wait for a brick after that; true without levels).
  bool coarsestResident() const;
  uint64_t bricksDecoded() const { return loader_->loadedCount(); }
  const RenderOptions& options() const { return options_; }  // layout always set: the one in use
  // Settings that change without reloading anything (benchmarks and the viewer).
  void setSkipEmpty(bool skip);
  void setFiniteDifferenceNormals(bool on);
  void setSurfaceColor(const glm::vec3& rgb);
  void setLightInCamera(const glm::vec3& direction);
  // DVR: gradient shading (RenderOptions::dvrShading). Turning it on or off builds the raycasting
  // programs again; its highlight and light are uniforms. ValueError outside checkDvrShading's ranges,
  // GlError where a program fails to build: either way nothing changes. The directional light's
  // direction is setLightInCamera's.
  void setDvrShading(const DvrShading& shading);
  // DVR: the opacity at which a ray stops, in (0, 1] (ValueError otherwise; nothing changes).
  void setTerminationOpacity(float opacity);
  void setCountBricksDrawn(bool on) { options_.countBricksDrawn = on; }

 private:
  Raycaster(std::unique_ptr<BrickSource> owned, const RenderOptions& options);  // keeps `owned`
  void restartRays(int width, int height);
  void buildRaycastProgram();  // program_ (and lodProgram_ with levels) from options_, and their uniforms
  bool lodDrawing() const;  // the LOD program draws the frames (levels, iso mode, one opaque surface)
  int passLookahead() const;  // options_.lookahead, or what kLookaheadAuto means for this frame
  void requestCoarsest();   // the coarsest level's missing bricks, before anything else
  bool raiseBiasIfThrashing(uint64_t uploadedThisView);  // true: the bias rose, the rays must restart
  void finishLevelMix(FrameStats& stats);
  void noteFrameUse(const LevelMix& mix);  // whether the next frame may lower the raised bias
  void noteView(const CameraFrame& frame, int width, int height);  // a new view forgets thrashBias_
  void updateNeeded();  // the bricks the isovalue or the transfer function needs, and the page table
  void uploadTransfer();  // DVR: the table, its zero-prefix and bin maxima
  void setTransferUniforms();  // DVR: the programs' table uniforms and stop transmittance
  struct PassResult {
    uint32_t requested = 0;  // bricks the pass's rays asked for
    double gpuSeconds = 0.0;
  };
  // The Requests buffer (shaders/raycast.comp) starts with the count and the surface rectangle.
  static constexpr std::size_t kRequestsHeaderWords = kPassResultsHeaderBytes / sizeof(uint32_t);
  void dispatchPass(const CameraFrame& frame, int width, int height, int firstColumn);
  PassResult collectPass();  // waits for the pass dispatched last and reads what it tells the host
  // After collectPass(): the bricks rays stopped at first (`stopped` of them), then look-ahead ones;
  // with levels, coarsest level first.
  std::vector<LevelBrick> requestedBricks(uint32_t requestCount, uint32_t* stopped = nullptr) const;
  uint64_t slotsUsedSince(uint32_t pass) const;  // slots stamped by a pass after `pass`
  uint32_t upload(const std::vector<LoadedBrick>& loaded);  // after residency_->startAssigning
  std::vector<uint32_t> readSlotUse() const;
  void uploadPageTable();  // the whole page and node tables (a new isovalue or skip setting)
  void updatePageTable();  // the page entries changed since (uploads), scattered on the GPU
  void computeSlotBounds(const std::vector<uint32_t>& slots);

  std::unique_ptr<BrickSource> ownSource_;  // the BrickStore constructor's
  const BrickSource& source_;
  RenderOptions options_;
  uint32_t pass_ = 0;
  bool firstPass_ = true;          // the next pass starts every ray at the eye (no resume image read)
  bool requestBitsDirty_ = false;  // the last pass requested bricks: their bits need clearing
  PixelRect surfaceRect_;
  uint32_t requestCapacity_ = 0;
  uint64_t bricksUploaded_ = 0;
  std::unique_ptr<Residency> residency_;
  std::unique_ptr<BrickLoader> loader_;
  // What the progressive frame was started for; a difference restarts it.
  struct StepKey {
    CameraFrame frame;
    int width = 0, height = 0;
    int coveredColumns = 0;
    uint64_t settings = 0;
  } stepKey_;
  uint64_t settings_ = 1;  // bumped by every change of the isovalue or an option
  bool stepComplete_ = false;
  bool neededOnce_ = false;   // updateNeeded() has run (setSurfaces skips it when only colours change)
  uint64_t neededUpdates_ = 0;
  bool stepStarted_ = false;  // startStep() ran, finishStep() has not
  StepStats startedStep_;     // what startStep() did
  GlProgram program_, slotBoundsProgram_, pageUpdateProgram_;
  // The compositing variant (FCC_MULTI_ISO) of program_, built the first time it is needed.
  GlProgram surfacesProgram_;
  std::string raycastDefines_;  // what program_ was built with, for surfacesProgram_
  struct SurfaceUniforms {
    GLint count, isos, colors, opacities, stopTransmittance;
  } surfaceUniforms_{};
  void buildSurfacesProgram();
  GLint slotBoundsPassUniform_ = -1;  // its uPass: the pass that marks freshly uploaded slots used
  GLint pageUpdateCountUniform_ = -1; // pageUpdateProgram_'s uCount: the pairs to write
  // raycast.comp's uniform locations, looked up once.
  struct Uniforms {
    GLint resolution, eye, forward, right, up, indexFromWorld, normalFromIndex, iso, brickMin, brickDims, nodeDims,
        pass, firstPass, firstColumn, columnOffset, requestCapacity, lookahead, skipEmpty, finiteDifferenceNormals, surfaceColor, lightDir, clipLo, clipHi,
        bccParams;
  } uniforms_{}, surfacesUniforms_{};
  Uniforms uniformsOf(const GlProgram& program, bool dvr, bool anyInactive = false) const;
  std::unique_ptr<GlReadbackBuffer> passResultsReadback_;
  const uint32_t* passResults_ = nullptr;  // the last pass's header and first requests, as read back
  std::vector<LevelBrick> lastRequests_;
  // Level of detail.
  std::vector<const BrickSource*> levelSources_;  // level 0 first
  float autoBias_ = 0.0f;            // whole levels added to options_.lodBias (lodAdaptBias)
  uint64_t uploadedThisView_ = 0;    // bricks uploaded since the rays last started over
  uint32_t viewFirstPass_ = 1;       // the first pass of the current view (for LevelMix)
  bool lowerBiasPending_ = false;    // the last complete frame used little of the pool
  float thrashBias_ = -1.0f;         // the highest raised bias this view streamed through the pool at
  struct {
    CameraFrame frame{};
    int width = 0, height = 0;
  } lodView_;
  std::vector<glm::ivec3> coarsestNeeded_;
  GlProgram lodProgram_;             // FCC_LOD: built when there are levels
  Uniforms lodUniforms_{};
  struct LodUniforms {
    GLint levelCount, brickMin, brickDims, nodeDims, pageOffset, nodeOffset, scale, size, bias, pixelAngle;
  } lodExtra_{};
  std::unique_ptr<GlBuffer> levelHits_, slotDrawn_, slotStandIn_;  // raycast.comp's LevelHits, SlotDrawn, SlotStandIn
  GlTexture2D resumeState_;                          // FCC_LOD: what a provisional ray's march carried
  std::unique_ptr<GpuInterval> passTimer_;
  std::unique_ptr<BrickPool> pool_;
  std::unique_ptr<GlBuffer> slotBounds_, uploadedSlots_, pageTable_, nodeTable_, requests_, requestBits_, slotUse_;
  std::unique_ptr<GlBuffer> pageChanges_;  // (index, value) pairs for updatePageTable
  std::unique_ptr<DvrTableGpu> dvrTable_;  // DVR: the transfer table as shaders/dvr.glsl reads it
  GlTexture2D color_, normalDepth_, resume_;
  GlTexture2D transmittance_;  // FCC_MULTI_ISO: a waiting ray's transmittance, kept exactly
};

}  // namespace fcc::render
