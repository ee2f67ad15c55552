#include "Raycaster.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "FccBrickSource.h"
#include "embedded_shaders.h"
#include "sparse/Error.h"

namespace fcc::render {
namespace {

constexpr std::size_t kSlotVoxels = 512;  // per-voxel cell bounds of a slot (shaders/pool.glsl)
constexpr std::size_t kSlotBoundsBytes = kSlotVoxels * 2 * sizeof(float);
constexpr std::size_t kUploadBatch = 256; // bricks the loader holds ready, and render()'s upload batch (4 MB)
constexpr std::size_t kStepUploadBatch = 32;  // step()'s upload batch, checked against its time budget
constexpr int kMaxPasses = 1 << 20;       // a frame that needs more has a bug, not a small pool

}  // namespace

std::string renderModeName(RenderMode mode) { return mode == RenderMode::Dvr ? "dvr" : "iso"; }

RenderMode parseRenderMode(const std::string& name) {
  if (name == "iso") return RenderMode::Iso;
  if (name == "dvr") return RenderMode::Dvr;
  throw ValueError("mode '" + name + "': valid modes are iso (the isosurface), dvr (direct volume rendering)");
}

BrickLayout chooseBrickLayout(const BrickSource& source, std::size_t gpuCacheBytes) {
  if (source.slotBlock() == SlotBlock::Sites) return BrickLayout::TextureScalar;
  const std::size_t varying = source.varyingBrickCount();
  const std::size_t scalarBytes = varying * (BrickPool::slotBytes(BrickLayout::TextureScalar) + kSlotBoundsBytes);
  return scalarBytes <= gpuCacheBytes ? BrickLayout::TextureScalar : BrickLayout::TextureVec4;
}

Raycaster::Raycaster(const io::BrickStore& store, const RenderOptions& options)
    : Raycaster(std::make_unique<FccBrickSource>(store, options.hostCacheBytes), options) {}

Raycaster::Raycaster(std::unique_ptr<BrickSource> owned, const RenderOptions& options)
    : Raycaster(*owned, options) {
  ownSource_ = std::move(owned);
}

Raycaster::Raycaster(const BrickSource& source, const RenderOptions& requested)
    : source_(source), options_(requested) {
  if (!options_.layout) options_.layout = chooseBrickLayout(source, options_.gpuCacheBytes);
  const RenderOptions& options = options_;
  const BrickLayout layout = *options.layout;
  glm::ivec3 boxLo, boxHi;
  source.brickBox(boxLo, boxHi);
  const bool empty = glm::any(glm::greaterThan(boxLo, boxHi));
  const glm::ivec3 brickMin = empty ? glm::ivec3(0) : boxLo;
  const glm::ivec3 brickDims = empty ? glm::ivec3(1) : boxHi - boxLo + 1;
  const std::size_t bricksInBox = std::size_t(brickDims.x) * brickDims.y * brickDims.z;

  // The GPU budget pays for a slot's data and its cell bounds.
  std::size_t slots = options.gpuCacheBytes / (BrickPool::slotBytes(layout) + kSlotBoundsBytes);
  slots = std::min({slots, BrickPool::maxSlots(layout), bricksInBox});
  slots = std::max<std::size_t>(slots, 1);
  pool_ = std::make_unique<BrickPool>(layout, slots, source.slotBlock());

  if (options.workGroup.x < 1 || options.workGroup.y < 1 || options.workGroup.x * options.workGroup.y > 1024)
    throw ValueError("work group " + std::to_string(options.workGroup.x) + "x" + std::to_string(options.workGroup.y) +
                     ": valid are 1 to 1024 invocations");
  // The reconstruction the shaders evaluate (sparse/ReconDispatch.h's FCC_RECON_* ids).
  std::string defines = pool_->glslDefines() + "#define FCC_RECON " + std::to_string(source.reconstruction().deviceId) + "\n";
  const bool dvr = options.mode == RenderMode::Dvr;
  if (dvr && !options.transfer) throw ValueError("direct volume rendering needs a transfer function");
  const std::string modeDefines =
      dvr ? std::string("#define FCC_MODE_DVR 1\n") + (options.dvrShading ? "#define FCC_DVR_SHADING 1\n" : "") : "";
  const std::string groupDefines = "#define FCC_GROUP_X " + std::to_string(options.workGroup.x) +
                                   "\n#define FCC_GROUP_Y " + std::to_string(options.workGroup.y) + "\n";
  raycastDefines_ = defines + modeDefines + groupDefines;
  program_ = GlProgram::compute(withDefines(embedded::shaders("shaders/raycast.comp"), raycastDefines_), "shaders/raycast.comp");
  // A CPU rasteriser gets the cheap coefficient-hull cell bounds, a GPU the BB-coefficient ones
  // (both conservative; the image is the same, only the work skipped differs).
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (!(renderer && std::string(renderer).find("llvmpipe") != std::string::npos)) defines += "#define FCC_SLOT_BOUNDS_BB 1\n";
  uniforms_ = uniformsOf(program_, dvr);
  slotBoundsProgram_ = GlProgram::compute(withDefines(embedded::shaders("shaders/slot_bounds.comp"), defines),
                                          "shaders/slot_bounds.comp");
  slotBoundsPassUniform_ = slotBoundsProgram_.uniformLocation("uPass");
  pageUpdateProgram_ = GlProgram::compute(embedded::shaders("shaders/page_update.comp"), "shaders/page_update.comp");
  pageUpdateCountUniform_ = pageUpdateProgram_.uniformLocation("uCount");
  pool_->setUniforms(program_);
  pool_->setUniforms(slotBoundsProgram_);

  residency_ = std::make_unique<Residency>(brickMin, brickDims, uint32_t(slots));

  requestCapacity_ = uint32_t(std::min<std::size_t>(bricksInBox, 1 << 16));
  slotBounds_ = std::make_unique<GlBuffer>(slots * kSlotBoundsBytes);
  uploadedSlots_ = std::make_unique<GlBuffer>(kUploadBatch * sizeof(uint32_t));
  pageTable_ = std::make_unique<GlBuffer>(bricksInBox * sizeof(uint32_t));
  nodeTable_ = std::make_unique<GlBuffer>(residency_->nodeEntries().size() * sizeof(uint32_t));
  requests_ = std::make_unique<GlBuffer>((kRequestsHeaderWords + std::size_t(requestCapacity_)) * sizeof(uint32_t));
  requestBits_ = std::make_unique<GlBuffer>((bricksInBox / 32 + 1) * sizeof(uint32_t));
  requestBits_->clear();
  passResultsReadback_ =
      std::make_unique<GlReadbackBuffer>((kRequestsHeaderWords + options_.requestsReadBack) * sizeof(uint32_t));
  if (options.timeGpu) passTimer_ = std::make_unique<GpuInterval>();
  slotUse_ = std::make_unique<GlBuffer>(slots * sizeof(uint32_t));
  slotUse_->clear();
  // Four batches ready, so decoding goes on while render() uploads one (16 MB of blocks); no more than
  // the pool has slots: a pass cannot use more, and the blocks count against the process's memory.
  loader_ = std::make_unique<BrickLoader>(source, std::min<std::size_t>(4 * kUploadBatch, std::max<std::size_t>(slots, kStepUploadBatch)));
  if (dvr) {
    tfEntries_ = std::make_unique<GlBuffer>(std::size_t(options.transfer->size()) * sizeof(glm::vec4));
    tfPrefix_ = std::make_unique<GlBuffer>(std::size_t(options.transfer->size() + 1) * sizeof(int32_t));
    uploadTransfer();
  }
  std::vector<Isosurface> surfaces = surfacesOf(options_);
  if (std::isnan(surfaces[0].iso)) surfaces[0].iso = 0.5f * (source.valueMin() + source.valueMax());
  setSurfaces(surfaces);
}

Raycaster::Uniforms Raycaster::uniformsOf(const GlProgram& program, bool lenient) const {
  // Uniforms one variant does not read are inactive there (-1: setting them is a no-op): DVR reads
  // none of the isosurface's, the compositing variant not the single surface's value and colour.
  const auto at = [&program, lenient](const char* name) {
    static const char* const isoOnly[] = {"uNormalFromIndex", "uIso", "uFiniteDifferenceNormals", "uSurfaceColor", "uLightDir"};
    if (lenient && std::find_if(std::begin(isoOnly), std::end(isoOnly), [&](const char* n) { return std::strcmp(n, name) == 0; }) != std::end(isoOnly))
      return glGetUniformLocation(program.id(), name);
    return program.uniformLocation(name);
  };
  return Uniforms{at("uResolution"), at("uEye"), at("uForward"), at("uRight"), at("uUp"), at("uIndexFromWorld"),
                  at("uNormalFromIndex"), at("uIso"), at("uBrickMin"), at("uBrickDims"), at("uNodeDims"),
                  at("uPass"), at("uFirstPass"), at("uFirstColumn"), at("uColumnOffset"),
                  at("uRequestCapacity"), at("uLookahead"), at("uSkipEmpty"), at("uFiniteDifferenceNormals"),
                  at("uSurfaceColor"), at("uLightDir"), at("uClipLo"), at("uClipHi")};
}

void Raycaster::buildSurfacesProgram() {
  if (surfacesProgram_.id() != 0) return;
  surfacesProgram_ = GlProgram::compute(
      withDefines(embedded::shaders("shaders/raycast.comp"), raycastDefines_ + "#define FCC_MULTI_ISO 1\n"),
      "shaders/raycast.comp (several surfaces)");
  surfacesUniforms_ = uniformsOf(surfacesProgram_, true);
  const GLuint id = surfacesProgram_.id();
  surfaceUniforms_ = SurfaceUniforms{glGetUniformLocation(id, "uSurfaceCount"), glGetUniformLocation(id, "uSurfaceIsos"),
                                     glGetUniformLocation(id, "uSurfaceColors"), glGetUniformLocation(id, "uSurfaceOpacities"),
                                     glGetUniformLocation(id, "uStopTransmittance")};
  pool_->setUniforms(surfacesProgram_);
}

void Raycaster::uploadTransfer() {
  const TransferTable& table = *options_.transfer;
  if (std::size_t(table.size()) * sizeof(glm::vec4) > tfEntries_->size()) {
    tfEntries_ = std::make_unique<GlBuffer>(std::size_t(table.size()) * sizeof(glm::vec4));
    tfPrefix_ = std::make_unique<GlBuffer>(std::size_t(table.size() + 1) * sizeof(int32_t));
  }
  tfEntries_->write(table.entries().data(), std::size_t(table.size()) * sizeof(glm::vec4));
  const std::vector<int>& prefix = table.nonZeroPrefix();
  const std::vector<int32_t> prefix32(prefix.begin(), prefix.end());
  tfPrefix_->write(prefix32.data(), prefix32.size() * sizeof(int32_t));
  // shaders/dvr.glsl's bins: the largest extinction of each run of entries, ends shared.
  constexpr int kBins = 16;
  const int size = table.size();
  const int binEntries = std::max(1, (size - 1 + kBins - 1) / kBins);
  float binMax[kBins] = {};
  for (int k = 0; k < kBins; ++k)
    for (int i = k * binEntries; i <= std::min((k + 1) * binEntries, size - 1); ++i)
      binMax[k] = std::max(binMax[k], table.entries()[std::size_t(i)].a);
  const GLuint p = program_.id();
  glProgramUniform1f(p, program_.uniformLocation("uTfMin"), float(table.vmin()));
  glProgramUniform1f(p, program_.uniformLocation("uTfScale"), float((size - 1) / (table.vmax() - table.vmin())));
  glProgramUniform1i(p, program_.uniformLocation("uTfSize"), size);
  glProgramUniform1fv(p, program_.uniformLocation("uTfBinMax"), kBins, binMax);
  glProgramUniform1i(p, program_.uniformLocation("uTfBinEntries"), binEntries);
  glProgramUniform1f(p, program_.uniformLocation("uStopTransmittance"), 1.0f - options_.terminationOpacity);
}

void Raycaster::setTransfer(std::shared_ptr<const TransferTable> transfer) {
  if (options_.mode != RenderMode::Dvr) throw Error("renderer: a transfer function outside DVR mode");
  if (!transfer) throw ValueError("direct volume rendering needs a transfer function");
  // The bricks needed depend on the table only through where it is zero (TransferTable::zeroOn: its
  // range, size and zero-prefix): an edit that moves no zero entry (a colour, an opacity above 0: the
  // viewer's editor while a point is dragged) uploads the table alone.
  const TransferTable& before = *options_.transfer;
  const bool sameZeros = before.size() == transfer->size() && before.vmin() == transfer->vmin() &&
                         before.vmax() == transfer->vmax() && before.nonZeroPrefix() == transfer->nonZeroPrefix();
  options_.transfer = std::move(transfer);
  uploadTransfer();
  ++settings_;
  if (!sameZeros) updateNeeded();
}

Raycaster::~Raycaster() = default;

std::size_t Raycaster::slotBytes() const { return BrickPool::slotBytes(*options_.layout) + kSlotBoundsBytes; }

std::size_t Raycaster::poolBytes() const { return std::size_t(residency_->slotCount()) * slotBytes(); }

void Raycaster::setIso(float iso) {
  if (!std::isfinite(iso)) throw ValueError("isovalue " + std::to_string(iso) + " is not finite");
  options_.iso = iso;
  ++settings_;
  updateNeeded();
}

void Raycaster::setSurfaces(const std::vector<Isosurface>& surfaces) {
  if (surfaces.empty() || surfaces.size() > std::size_t(kMaxIsosurfaces))
    throw ValueError(std::to_string(surfaces.size()) + " isosurfaces: valid are 1 to " + std::to_string(kMaxIsosurfaces));
  for (const Isosurface& s : surfaces) {
    if (!std::isfinite(s.iso)) throw ValueError("isovalue " + std::to_string(s.iso) + " is not finite");
    if (!(s.opacity >= 0.0f && s.opacity <= 1.0f))
      throw ValueError("surface opacity " + std::to_string(s.opacity) + ": valid is 0 to 1");
  }
  std::vector<Isosurface> before = surfacesOf(options_);
  options_.iso = surfaces[0].iso;
  options_.surfaceColor = surfaces[0].color;
  options_.surfaceOpacity = surfaces[0].opacity;
  options_.moreSurfaces.assign(surfaces.begin() + 1, surfaces.end());
  if (options_.mode == RenderMode::Iso && compositesSurfaces(options_)) buildSurfacesProgram();
  ++settings_;
  // A colour or an opacity changes no brick's need (the constructor's first call always updates).
  const bool sameValues = residency_ && before.size() == surfaces.size() && pageTable_ &&
                          std::equal(before.begin(), before.end(), surfaces.begin(),
                                     [](const Isosurface& a, const Isosurface& b) { return a.iso == b.iso; });
  if (!sameValues || !neededOnce_) updateNeeded();
  neededOnce_ = true;
}

void Raycaster::setClip(const glm::dvec3& lo, const glm::dvec3& hi) {
  options_.clipLo = lo;
  options_.clipHi = hi;
  ++settings_;
  updateNeeded();
}

void Raycaster::updateNeeded() {
  ++neededUpdates_;
  // The clipping box in index space: the bounding box of its corners (conservative for a rotated
  // transform), clamped so that a box of +-1e30 stays finite in float.
  const glm::dmat4 indexFromWorld = glm::inverse(source_.worldFromIndex());
  glm::dvec3 clipLo(std::numeric_limits<double>::max()), clipHi(-std::numeric_limits<double>::max());
  const bool clipEmpty = glm::any(glm::greaterThan(options_.clipLo, options_.clipHi));
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 pWorld((corner & 1) ? options_.clipHi.x : options_.clipLo.x, (corner & 2) ? options_.clipHi.y : options_.clipLo.y,
                            (corner & 4) ? options_.clipHi.z : options_.clipLo.z);
    const glm::dvec3 xyz = glm::clamp(glm::dvec3(indexFromWorld * glm::dvec4(pWorld, 1.0)), glm::dvec3(-1e12), glm::dvec3(1e12));
    clipLo = glm::min(clipLo, xyz);
    clipHi = glm::max(clipHi, xyz);
  }
  const auto insideClip = [&](const glm::ivec3& brick) {
    const glm::dvec3 lo = glm::dvec3(brick) * 16.0, hi = lo + 16.0;
    return !clipEmpty && glm::all(glm::lessThanEqual(lo, clipHi)) && glm::all(glm::greaterThanEqual(hi, clipLo));
  };
  std::vector<glm::ivec3> needed;
  const float iso = options_.iso;
  std::vector<float> isos;  // every surface's
  for (const Isosurface& s : surfacesOf(options_)) isos.push_back(s.iso);
  const TransferTable* transfer = options_.mode == RenderMode::Dvr ? options_.transfer.get() : nullptr;
  source_.forEachVaryingBrick([&](const glm::ivec3& brick, float lo, float hi) {
    const bool holds = transfer ? !transfer->zeroOn(lo, hi)
                                : (lo <= iso && iso <= hi) ||
                                      std::any_of(isos.begin() + 1, isos.end(), [&](float v) { return lo <= v && v <= hi; });
    if ((!options_.skipEmpty || holds) && insideClip(brick) && (!options_.ownsBrick || options_.ownsBrick(brick)))
      needed.push_back(brick);
  });
  residency_->setNeeded(needed);
  uploadPageTable();
}

void Raycaster::setSkipEmpty(bool skip) {
  options_.skipEmpty = skip;
  setIso(options_.iso);
}

void Raycaster::setFiniteDifferenceNormals(bool on) {
  options_.finiteDifferenceNormals = on;
  ++settings_;
}

glm::vec3 defaultSurfaceColor(int index) {
  // Sand (the single surface's), then sky blue, sage and brick red: apart in hue and lightness.
  static const glm::vec3 palette[kMaxIsosurfaces] = {
      {0.85f, 0.72f, 0.52f}, {0.25f, 0.50f, 0.85f}, {0.45f, 0.75f, 0.35f}, {0.80f, 0.30f, 0.25f}};
  return palette[std::clamp(index, 0, kMaxIsosurfaces - 1)];
}

std::vector<Isosurface> surfacesOf(const RenderOptions& options) {
  std::vector<Isosurface> all{Isosurface{options.iso, options.surfaceColor, options.surfaceOpacity}};
  all.insert(all.end(), options.moreSurfaces.begin(), options.moreSurfaces.end());
  return all;
}

bool compositesSurfaces(const RenderOptions& options) {
  return options.mode == RenderMode::Iso && (!options.moreSurfaces.empty() || options.surfaceOpacity < 1.0f);
}

void Raycaster::setSurfaceColor(const glm::vec3& rgb) {
  options_.surfaceColor = rgb;
  ++settings_;
}

void Raycaster::setLightInCamera(const glm::vec3& direction) {
  options_.lightInCamera = direction;
  ++settings_;
}

void Raycaster::computeSlotBounds(const std::vector<uint32_t>& slots) {
  uploadedSlots_->write(slots);
  pool_->bind();
  slotUse_->bindBase(GL_SHADER_STORAGE_BUFFER, 5);
  slotBounds_->bindBase(GL_SHADER_STORAGE_BUFFER, 6);
  uploadedSlots_->bindBase(GL_SHADER_STORAGE_BUFFER, 7);
  glProgramUniform1ui(slotBoundsProgram_.id(), slotBoundsPassUniform_, pass_);
  slotBoundsProgram_.use();
  glDispatchCompute(GLuint(kSlotVoxels / 64), GLuint(slots.size()), 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  checkGl("computing the cell bounds of " + std::to_string(slots.size()) + " uploaded bricks");
}

void Raycaster::updatePageTable() {
  const std::size_t entries = residency_->pageEntries().size();
  const bool all = residency_->allEntriesChanged();
  const std::vector<uint32_t> changed = residency_->takeChangedEntries();
  if (all || changed.size() > entries / 8) {  // a scatter would write as much as the table
    pageTable_->write(residency_->pageEntries());
    return;
  }
  if (changed.empty()) return;
  std::vector<uint32_t> pairs;
  pairs.reserve(2 * changed.size());
  for (uint32_t index : changed) {
    pairs.push_back(index);
    pairs.push_back(residency_->pageEntries()[index]);
  }
  if (!pageChanges_ || pageChanges_->size() < pairs.size() * sizeof(uint32_t))
    pageChanges_ = std::make_unique<GlBuffer>(std::max<std::size_t>(pairs.size(), 2 * 4096) * sizeof(uint32_t));
  pageChanges_->write(pairs);
  pageTable_->bindBase(GL_SHADER_STORAGE_BUFFER, 1);
  pageChanges_->bindBase(GL_SHADER_STORAGE_BUFFER, 11);
  glProgramUniform1ui(pageUpdateProgram_.id(), pageUpdateCountUniform_, GLuint(changed.size()));
  pageUpdateProgram_.dispatch("updating the page table", GLuint(changed.size()));
}

void Raycaster::uploadPageTable() {
  (void)residency_->takeChangedEntries();  // all of them are written now
  pageTable_->write(residency_->pageEntries());
  if (options_.skipEmpty) {
    nodeTable_->write(residency_->nodeEntries());
  } else {
    const std::vector<uint32_t> all(residency_->nodeEntries().size(), 1u);
    nodeTable_->write(all);
  }
}

void Raycaster::restartRays(int width, int height) {
  if (color_.width() != width || color_.height() != height) {
    color_ = GlTexture2D(GL_RGBA32F, width, height);
    normalDepth_ = GlTexture2D(GL_RGBA32F, width, height);
    resume_ = GlTexture2D(GL_R32F, width, height);
  }
  if (compositesSurfaces(options_) && (transmittance_.width() != width || transmittance_.height() != height))
    transmittance_ = GlTexture2D(GL_R32F, width, height);
  firstPass_ = true;  // every ray starts at t = 0; the first pass writes every pixel's resume value
  // No surface pixel yet: min column and row past any pixel, max ones before any.
  const int32_t noSurface[4] = {std::numeric_limits<int32_t>::max(), std::numeric_limits<int32_t>::max(), -1, -1};
  requests_->write(noSurface, sizeof noSurface, sizeof(uint32_t));
  surfaceRect_ = PixelRect{};
}

void Raycaster::dispatchPass(const CameraFrame& frame, int width, int height, int firstColumn) {
  // firstColumn is in [0, width]: step() clamps it (its key holds the clamped value), render() passes 0.
  ++pass_;
  // Only the count: entries past it are never read (clearing the whole 256 KiB list cost time per
  // pass); and the request bits only after a pass that set some.
  const uint32_t zero = 0;
  requests_->write(&zero, sizeof zero);
  if (requestBitsDirty_) requestBits_->clear();

  // The compositing variant draws several or translucent surfaces (RenderOptions::moreSurfaces).
  const bool composite = compositesSurfaces(options_);
  const GlProgram& program = composite ? surfacesProgram_ : program_;
  const GLuint p = program.id();
  const Uniforms& u = composite ? surfacesUniforms_ : uniforms_;
  const glm::dmat4 indexFromWorld = glm::inverse(source_.worldFromIndex());
  const glm::mat4 indexFromWorldF(indexFromWorld);
  const glm::mat3 normalFromIndex = glm::transpose(glm::mat3(indexFromWorldF));
  const glm::vec3 l = options_.lightInCamera;
  const glm::vec3 lightSum = l.x * glm::vec3(glm::normalize(frame.right)) + l.y * glm::vec3(glm::normalize(frame.up)) -
                             l.z * glm::vec3(frame.forward);
  const glm::vec3 lightDir = glm::length(lightSum) > 0.0f ? glm::normalize(lightSum) : -glm::vec3(frame.forward);
  glProgramUniform2i(p, u.resolution, width, height);
  const glm::vec3 eye(frame.eye), forward(frame.forward), right(frame.right), up(frame.up);
  glProgramUniform3fv(p, u.eye, 1, &eye.x);
  glProgramUniform3fv(p, u.forward, 1, &forward.x);
  glProgramUniform3fv(p, u.right, 1, &right.x);
  glProgramUniform3fv(p, u.up, 1, &up.x);
  glProgramUniformMatrix4fv(p, u.indexFromWorld, 1, GL_FALSE, &indexFromWorldF[0][0]);
  glProgramUniformMatrix3fv(p, u.normalFromIndex, 1, GL_FALSE, &normalFromIndex[0][0]);
  glProgramUniform1f(p, u.iso, options_.iso);
  glProgramUniform3iv(p, u.brickMin, 1, &residency_->brickMin().x);
  glProgramUniform3iv(p, u.brickDims, 1, &residency_->brickDims().x);
  glProgramUniform3iv(p, u.nodeDims, 1, &residency_->nodeDims().x);
  glProgramUniform1ui(p, u.pass, pass_);
  glProgramUniform1i(p, u.firstPass, firstPass_ ? 1 : 0);
  const glm::ivec2 group = options_.workGroup;
  const int columnOffset = firstColumn / group.x * group.x;
  glProgramUniform1i(p, u.firstColumn, firstColumn);
  glProgramUniform1i(p, u.columnOffset, columnOffset);
  glProgramUniform1ui(p, u.requestCapacity, requestCapacity_);
  glProgramUniform1i(p, u.lookahead, options_.lookahead);
  glProgramUniform1i(p, u.skipEmpty, options_.skipEmpty ? 1 : 0);
  glProgramUniform1i(p, u.finiteDifferenceNormals, options_.finiteDifferenceNormals ? 1 : 0);
  glProgramUniform3fv(p, u.surfaceColor, 1, &options_.surfaceColor.x);
  glProgramUniform3fv(p, u.lightDir, 1, &lightDir.x);
  const glm::vec3 clipLo(glm::clamp(options_.clipLo, glm::dvec3(-1e30), glm::dvec3(1e30)));
  const glm::vec3 clipHi(glm::clamp(options_.clipHi, glm::dvec3(-1e30), glm::dvec3(1e30)));
  glProgramUniform3fv(p, u.clipLo, 1, &clipLo.x);
  glProgramUniform3fv(p, u.clipHi, 1, &clipHi.x);
  if (composite) {
    const std::vector<Isosurface> surfaces = surfacesOf(options_);
    float isos[kMaxIsosurfaces] = {}, opacities[kMaxIsosurfaces] = {};
    glm::vec3 colors[kMaxIsosurfaces] = {};
    for (std::size_t k = 0; k < surfaces.size(); ++k) {
      isos[k] = surfaces[k].iso;
      opacities[k] = surfaces[k].opacity;
      colors[k] = surfaces[k].color;
    }
    const SurfaceUniforms& su = surfaceUniforms_;
    glProgramUniform1i(p, su.count, GLint(surfaces.size()));
    glProgramUniform4fv(p, su.isos, 1, isos);
    glProgramUniform4fv(p, su.opacities, 1, opacities);
    glProgramUniform3fv(p, su.colors, kMaxIsosurfaces, &colors[0].x);
    glProgramUniform1f(p, su.stopTransmittance, 1.0f - options_.terminationOpacity);
  }

  pool_->bind();
  pageTable_->bindBase(GL_SHADER_STORAGE_BUFFER, 1);
  nodeTable_->bindBase(GL_SHADER_STORAGE_BUFFER, 2);
  requests_->bindBase(GL_SHADER_STORAGE_BUFFER, 3);
  requestBits_->bindBase(GL_SHADER_STORAGE_BUFFER, 4);
  slotUse_->bindBase(GL_SHADER_STORAGE_BUFFER, 5);
  slotBounds_->bindBase(GL_SHADER_STORAGE_BUFFER, 6);
  if (tfEntries_) {
    tfEntries_->bindBase(GL_SHADER_STORAGE_BUFFER, 12);
    tfPrefix_->bindBase(GL_SHADER_STORAGE_BUFFER, 13);
  }
  // DVR rays, and compositing ones, read what they accumulated before they stopped for a brick.
  const GLenum imageAccess = options_.mode == RenderMode::Dvr || composite ? GL_READ_WRITE : GL_WRITE_ONLY;
  color_.bindImage(0, imageAccess);
  normalDepth_.bindImage(1, imageAccess);
  resume_.bindImage(2, GL_READ_WRITE);
  if (composite) transmittance_.bindImage(3, GL_READ_WRITE);

  program.use();
  if (passTimer_) passTimer_->begin();
  const int columns = width - columnOffset;
  glDispatchCompute(GLuint((columns + group.x - 1) / group.x), GLuint((height + group.y - 1) / group.y), 1);
  if (passTimer_) passTimer_->end();
  firstPass_ = false;
  // For the read-backs (buffer update, texture update) and the viewer's presenter, which reads the
  // surface rectangle as a uniform block and the colour image with imageLoad.
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                  GL_TEXTURE_UPDATE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT);
  checkGl("raycasting pass");
  // The header and the first requests in one copy: reading requests later, from the buffer itself,
  // would wait for whatever the viewer has queued after the pass meanwhile.
  passResultsReadback_->copy(*requests_,
                             (kRequestsHeaderWords + std::min(options_.requestsReadBack, requestCapacity_)) *
                                 sizeof(uint32_t));
}

Raycaster::PassResult Raycaster::collectPass() {
  PassResult result;
  // Waits for the pass: every command before the copy (the pass included) has completed after it.
  passResults_ = static_cast<const uint32_t*>(passResultsReadback_->wait());
  uint32_t header[kRequestsHeaderWords];
  std::memcpy(header, passResults_, sizeof header);
  result.requested = header[0];
  int32_t surface[4];
  std::memcpy(surface, header + 1, sizeof surface);
  surfaceRect_ = surface[2] >= surface[0] ? PixelRect{surface[0], surface[1], surface[2] + 1, surface[3] + 1} : PixelRect{};
  requestBitsDirty_ = result.requested != 0;
  if (passTimer_) result.gpuSeconds = passTimer_->seconds();
  return result;
}

std::vector<glm::ivec3> Raycaster::requestedBricks(uint32_t requestCount) const {
  const uint32_t n = std::min(requestCount, requestCapacity_);
  const uint32_t copied = std::min(n, options_.requestsReadBack);
  std::vector<uint32_t> raw(passResults_ + kRequestsHeaderWords, passResults_ + kRequestsHeaderWords + copied);
  if (n > copied) {  // a heavy streaming pass: the rest straight from the buffer
    raw.resize(n);
    requests_->read(raw.data() + copied, (n - copied) * sizeof(uint32_t), (kRequestsHeaderWords + copied) * sizeof(uint32_t));
  }
  // The bricks rays stopped at come first: loading them guarantees progress; look-ahead ones follow.
  std::vector<glm::ivec3> bricks;
  bricks.reserve(n);
  for (uint32_t r : raw)
    if (!(r & 0x80000000u)) bricks.push_back(residency_->brickAt(r));
  for (uint32_t r : raw)
    if (r & 0x80000000u) bricks.push_back(residency_->brickAt(r & 0x7FFFFFFFu));
  // No more than the pool holds: every brick loaded in a pass keeps its slot through the pass.
  if (bricks.size() > residency_->slotCount()) bricks.resize(residency_->slotCount());
  return bricks;
}

std::vector<uint32_t> Raycaster::readSlotUse() const {
  std::vector<uint32_t> slotUse(residency_->slotCount());
  slotUse_->read(slotUse);
  return slotUse;
}

uint32_t Raycaster::upload(const std::vector<LoadedBrick>& loaded) {
  std::vector<glm::ivec3> bricks;
  bricks.reserve(loaded.size());
  for (const LoadedBrick& b : loaded) bricks.push_back(b.brick);
  const auto assigned = residency_->assign(bricks);  // skips bricks resident meanwhile
  if (assigned.empty()) return 0;
  std::vector<uint32_t> slots;
  std::vector<const float*> blocks;
  std::size_t next = 0;
  for (const auto& [brick, slot] : assigned) {
    while (loaded[next].brick != brick) ++next;  // assign() keeps the order
    blocks.push_back(loaded[next].halo.data());
    // Freshly loaded slots count as used now (computeSlotBounds marks them on the GPU), so the next
    // pass's eviction order does not evict them first; this pass's order never hands a slot out twice.
    slots.push_back(slot);
  }
  pool_->upload(slots, blocks);
  computeSlotBounds(slots);
  bricksUploaded_ += assigned.size();
  return uint32_t(assigned.size());
}

FrameStats Raycaster::render(const Camera& camera, int width, int height) {
  if (stepStarted_) throw Error("renderer: render() between startStep() and finishStep()");
  if (width <= 0 || height <= 0)
    throw ValueError("image size " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
  const auto start = std::chrono::steady_clock::now();
  const CameraFrame frame = cameraFrame(camera, double(width) / double(height));
  restartRays(width, height);
  stepKey_ = StepKey{};  // a later step() starts over
  FrameStats stats;
  stats.bricksNeeded = residency_->neededCount();
  for (;;) {
    ++stats.passes;
    dispatchPass(frame, width, height, 0);
    const PassResult pass = collectPass();
    stats.gpuSeconds += pass.gpuSeconds;
    const uint32_t requested = pass.requested;
    if (requested == 0) break;
    if (stats.passes >= kMaxPasses) throw Error("renderer: the frame did not complete in " + std::to_string(kMaxPasses) + " passes");
    lastRequests_ = requestedBricks(requested);
    loader_->request(lastRequests_);
    residency_->startAssigning(readSlotUse());
    uint64_t uploaded = 0;
    for (;;) {
      std::vector<LoadedBrick> loaded = loader_->take(kUploadBatch, true);
      if (loaded.empty()) break;
      uploaded += upload(loaded);
      loader_->recycle(std::move(loaded));
    }
    if (uploaded == 0) throw Error("renderer: rays requested bricks but none could be given a pool slot");
    updatePageTable();
    stats.bricksUploaded += uploaded;
  }
  // No glFinish: the last pass's read-back waited for every command of the frame.
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

StepStats Raycaster::step(const Camera& camera, int width, int height, double uploadSeconds, int coveredColumns) {
  startStep(camera, width, height, uploadSeconds, coveredColumns);
  return finishStep();
}

void Raycaster::startStep(const Camera& camera, int width, int height, double uploadSeconds, int coveredColumns) {
  if (width <= 0 || height <= 0)
    throw ValueError("image size " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
  if (stepStarted_) throw Error("renderer: startStep() twice without finishStep()");
  const CameraFrame frame = cameraFrame(camera, double(width) / double(height));
  StepStats& stats = startedStep_;
  stats = StepStats{};
  coveredColumns = std::clamp(coveredColumns, 0, width);
  const StepKey key{frame, width, height, coveredColumns, settings_};
  if (!(key.frame.eye == stepKey_.frame.eye && key.frame.forward == stepKey_.frame.forward &&
        key.frame.right == stepKey_.frame.right && key.frame.up == stepKey_.frame.up &&
        key.width == stepKey_.width && key.height == stepKey_.height &&
        key.coveredColumns == stepKey_.coveredColumns && key.settings == stepKey_.settings)) {
    stepKey_ = key;
    restartRays(width, height);
    loader_->cancelQueued();  // requests of the old view; what still arrives is uploaded all the same
    stepComplete_ = false;
    stats.restarted = true;
  }
  // Uploads first, so this step's pass already sees them; also once the frame is complete, so that
  // bricks still arriving (look-ahead requests) do not wait in the loader forever.
  const auto start = std::chrono::steady_clock::now();
  bool assigning = false;
  do {
    std::vector<LoadedBrick> loaded = loader_->take(kStepUploadBatch, false);
    if (loaded.empty()) break;
    if (!assigning) residency_->startAssigning(readSlotUse());
    assigning = true;
    stats.uploaded += upload(loaded);
    loader_->recycle(std::move(loaded));
  } while (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < uploadSeconds);
  if (stats.uploaded) updatePageTable();

  stepStarted_ = true;
  if (stepComplete_) return;
  stats.dispatched = true;
  dispatchPass(frame, width, height, coveredColumns);
}

StepStats Raycaster::finishStep() {
  if (!stepStarted_) throw Error("renderer: finishStep() without startStep()");
  stepStarted_ = false;
  StepStats stats = startedStep_;
  if (stats.dispatched) {
    const PassResult pass = collectPass();
    stats.requested = pass.requested;
    stats.gpuSeconds = pass.gpuSeconds;
    if (stats.requested == 0) stepComplete_ = true;
    else loader_->request(lastRequests_ = requestedBricks(stats.requested));
  }
  stats.complete = stepComplete_;
  stats.streaming = loader_->pending();
  return stats;
}

FrameImages Raycaster::readImages(bool withNormalDepth) const {
  FrameImages out;
  out.width = color_.width();
  out.height = color_.height();
  out.rgba = color_.read(GL_RGBA, 4);
  if (withNormalDepth) out.normalDepth = normalDepth_.read(GL_RGBA, 4);
  return out;
}

}  // namespace fcc::render
