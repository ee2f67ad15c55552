#include "Raycaster.h"

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

#include "FccBrickSource.h"
#include "embedded_shaders.h"
#include "sparse/BccShearedTrilinear.h"
#include "sparse/Error.h"

namespace fcc::render {
namespace {

constexpr std::size_t kSlotVoxels = 512;  // per-voxel cell bounds of a slot (shaders/pool.glsl)
constexpr std::size_t kSlotBoundsBytes = kSlotVoxels * 2 * sizeof(float);
constexpr std::size_t kUploadBatch = 256; // bricks the loader holds ready, and render()'s upload batch (4 MB)
constexpr std::size_t kStepUploadBatch = 32;  // step()'s upload batch, checked against its time budget
constexpr int kMaxPasses = 1 << 20;       // a frame that needs more has a bug, not a small pool

// FCCVDB_SHADER_DEFINES="NAME=VALUE;NAME2": extra #defines for the raycaster's programs, for measuring
// variants of a shader stage on a GPU without a rebuild (docs/RENDERER.md, "Measuring shader variants").
// Not a user setting: the defines it may set are the shaders' own measurement knobs.
std::string shaderDefinesFromEnvironment() {
  const char* spec = std::getenv("FCCVDB_SHADER_DEFINES");
  std::string out;
  if (!spec) return out;
  std::string item;
  for (const char* c = spec;; ++c) {
    if (*c == ';' || *c == '\0') {
      if (!item.empty()) {
        const std::size_t eq = item.find('=');
        out += "#define " + (eq == std::string::npos ? item + " 1" : item.substr(0, eq) + " " + item.substr(eq + 1)) + "\n";
      }
      item.clear();
      if (*c == '\0') break;
    } else if (std::isalnum(static_cast<unsigned char>(*c)) || *c == '_' || *c == '=' || *c == '.') {
      item += *c;
    } else {
      throw ValueError(std::string("FCCVDB_SHADER_DEFINES: '") + *c + "' is not allowed; valid: NAME=VALUE items separated by ';' (letters, digits, _ and .)");
    }
  }
  return out;
}

}  // namespace

std::string renderModeName(RenderMode mode) { return mode == RenderMode::Dvr ? "dvr" : "iso"; }

RenderMode parseRenderMode(const std::string& name) {
  if (name == "iso") return RenderMode::Iso;
  if (name == "dvr") return RenderMode::Dvr;
  throw ValueError("mode '" + name + "': valid modes are iso (the isosurface), dvr (direct volume rendering)");
}

BrickLayout chooseBrickLayout(const BrickSource& source, std::size_t gpuCacheBytes) {
  if (source.slotBlock() != SlotBlock::FccPacked) return BrickLayout::TextureScalar;
  const std::size_t varying = source.varyingBrickCount();
  const std::size_t scalarBytes = varying * (BrickPool::slotBytes(BrickLayout::TextureScalar) + kSlotBoundsBytes);
  return scalarBytes <= gpuCacheBytes ? BrickLayout::TextureScalar : BrickLayout::TextureVec4;
}

namespace {
// Level 0's share of --host-cache: what the pyramid's coarser levels (which have caches of their own,
// render::PyramidLevels) leave of it.
std::size_t levelZeroHostBytes(const RenderOptions& options) {
  std::size_t coarser = 0;
  for (const BrickSource* level : options.coarserLevels) coarser += level->hostCacheUse().budgetBytes;
  return options.hostCacheBytes > coarser ? options.hostCacheBytes - coarser : 0;
}
}  // namespace

Raycaster::Raycaster(const io::BrickStore& store, const RenderOptions& options)
    : Raycaster(std::make_unique<FccBrickSource>(store, levelZeroHostBytes(options)), options) {}

Raycaster::Raycaster(std::unique_ptr<BrickSource> owned, const RenderOptions& options)
    : Raycaster(*owned, options) {
  ownSource_ = std::move(owned);
}

Raycaster::Raycaster(const BrickSource& source, const RenderOptions& requested)
    : source_(source), options_(requested) {
  if (!options_.layout) options_.layout = chooseBrickLayout(source, options_.gpuCacheBytes);
  const RenderOptions& options = options_;
  const BrickLayout layout = *options.layout;
  levelSources_.push_back(&source);
  if (options_.coarserLevels.size() + 1 > std::size_t(kMaxLodLevels))
    throw ValueError(std::to_string(options_.coarserLevels.size() + 1) + " pyramid levels: the renderer draws at most " +
                     std::to_string(kMaxLodLevels));
  for (const BrickSource* level : options_.coarserLevels) {
    if (!level || level->slotBlock() != source.slotBlock() || level->reconstruction().deviceId != source.reconstruction().deviceId)
      throw ValueError("a pyramid level must be an FCC source like level 0");
    levelSources_.push_back(level);
  }
  // Each level's box of bricks (level 0 first), one page table over all of them.
  std::vector<Residency::LevelBox> levelBoxes;
  for (const BrickSource* level : levelSources_) {
    glm::ivec3 boxLo, boxHi;
    level->brickBox(boxLo, boxHi);
    const bool empty = glm::any(glm::greaterThan(boxLo, boxHi));
    levelBoxes.push_back(Residency::LevelBox{empty ? glm::ivec3(0) : boxLo, empty ? glm::ivec3(1) : boxHi - boxLo + 1});
  }
  std::size_t bricksInBox = 0;
  for (const Residency::LevelBox& box : levelBoxes)
    bricksInBox += std::size_t(box.brickDims.x) * box.brickDims.y * box.brickDims.z;

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
  checkDvrShading(options.dvrShading);
  buildRaycastProgram();
  // A CPU rasteriser gets the cheap coefficient-hull cell bounds, a GPU the BB-coefficient ones
  // (both conservative; the image is the same, only the work skipped differs).
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (!(renderer && std::string(renderer).find("llvmpipe") != std::string::npos)) defines += "#define FCC_SLOT_BOUNDS_BB 1\n";
  slotBoundsProgram_ = GlProgram::compute(withDefines(embedded::shaders("shaders/slot_bounds.comp"), defines),
                                          "shaders/slot_bounds.comp");
  slotBoundsPassUniform_ = slotBoundsProgram_.uniformLocation("uPass");
  pageUpdateProgram_ = GlProgram::compute(embedded::shaders("shaders/page_update.comp"), "shaders/page_update.comp");
  pageUpdateCountUniform_ = pageUpdateProgram_.uniformLocation("uCount");
  pool_->setUniforms(slotBoundsProgram_);
  if (levelSources_.size() > 1) {
    levelHits_ = std::make_unique<GlBuffer>(kMaxLodLevels * sizeof(uint32_t));
    levelHits_->clear();
    slotDrawn_ = std::make_unique<GlBuffer>(slots * sizeof(uint32_t));
    slotDrawn_->clear();
    slotStandIn_ = std::make_unique<GlBuffer>(slots * sizeof(uint32_t));
    slotStandIn_->clear();
  }

  residency_ = std::make_unique<Residency>(levelBoxes, uint32_t(slots));

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
  loader_ = std::make_unique<BrickLoader>(levelSources_, std::min<std::size_t>(4 * kUploadBatch, std::max<std::size_t>(slots, kStepUploadBatch)));
  if (dvr) {
    dvrTable_ = std::make_unique<DvrTableGpu>(*options.transfer);
    uploadTransfer();
  }
  std::vector<Isosurface> surfaces = surfacesOf(options_);
  if (std::isnan(surfaces[0].iso)) surfaces[0].iso = 0.5f * (source.valueMin() + source.valueMax());
  setSurfaces(surfaces);
}

Raycaster::Uniforms Raycaster::uniformsOf(const GlProgram& program, bool lenient, bool anyInactive) const {
  // Uniforms one variant does not read are inactive there (-1: setting them is a no-op): DVR reads
  // none of the isosurface's, the compositing variant not the single surface's value and colour.
  const auto at = [&program, lenient, anyInactive](const char* name) {
    if (anyInactive) return glGetUniformLocation(program.id(), name);  // the LOD variant reads per-level ones
    static const char* const isoOnly[] = {"uNormalFromIndex", "uIso", "uFiniteDifferenceNormals", "uSurfaceColor", "uLightDir"};
    if (lenient && std::find_if(std::begin(isoOnly), std::end(isoOnly), [&](const char* n) { return std::strcmp(n, name) == 0; }) != std::end(isoOnly))
      return glGetUniformLocation(program.id(), name);
    return program.uniformLocation(name);
  };
  return Uniforms{at("uResolution"), at("uEye"), at("uForward"), at("uRight"), at("uUp"), at("uIndexFromWorld"),
                  at("uNormalFromIndex"), at("uIso"), at("uBrickMin"), at("uBrickDims"), at("uNodeDims"),
                  at("uPass"), at("uFirstPass"), at("uFirstColumn"), at("uColumnOffset"),
                  at("uRequestCapacity"), at("uLookahead"), at("uSkipEmpty"), at("uFiniteDifferenceNormals"),
                  at("uSurfaceColor"), at("uLightDir"), at("uClipLo"), at("uClipHi"),
                  glGetUniformLocation(program.id(), "uBccParams")};  // BCC programs only (-1 elsewhere)
}

void Raycaster::buildRaycastProgram() {
  const RenderOptions& options = options_;
  const bool dvr = options.mode == RenderMode::Dvr;
  const std::string modeDefines =
      dvr ? std::string("#define FCC_MODE_DVR 1\n") + (options.dvrShading.on ? "#define FCC_DVR_SHADING 1\n" : "") +
                (options.dvrGatherCentral ? "#define FCC_DVR_GATHER_CENTRAL 1\n" : "")
          : "";
  const std::string groupDefines = "#define FCC_GROUP_X " + std::to_string(options.workGroup.x) +
                                   "\n#define FCC_GROUP_Y " + std::to_string(options.workGroup.y) + "\n";
  std::string defines = pool_->glslDefines() + "#define FCC_RECON " + std::to_string(source_.reconstruction().deviceId) +
                        "\n" + modeDefines + groupDefines + shaderDefinesFromEnvironment();
  // Both compiled before either replaces the one in use: a program that fails to build changes nothing.
  GlProgram program = GlProgram::compute(withDefines(embedded::shaders("shaders/raycast.comp"), defines), "shaders/raycast.comp");
  GlProgram lodProgram;
  if (levelSources_.size() > 1) {
    // The levels' variant, beside the full-resolution program (which stays the same text and speed).
    lodProgram = GlProgram::compute(withDefines(embedded::shaders("shaders/raycast.comp"), defines + "#define FCC_LOD 1\n"),
                                    "shaders/raycast.comp (level of detail)");
  }
  raycastDefines_ = std::move(defines);
  program_ = std::move(program);
  uniforms_ = uniformsOf(program_, dvr);
  pool_->setUniforms(program_);
  if (lodProgram.id() != 0) {
    lodProgram_ = std::move(lodProgram);
    lodUniforms_ = uniformsOf(lodProgram_, dvr, true);
    const auto at = [this](const char* name) { return lodProgram_.uniformLocation(name); };
    lodExtra_ = LodUniforms{at("uLevelCount"), at("uLevelBrickMin"), at("uLevelBrickDims"), at("uLevelNodeDims"),
                            at("uLevelPageOffset"), at("uLevelNodeOffset"), at("uLevelScale"), at("uLevelSize"),
                            at("uLodBias"), at("uPixelAngle")};
    pool_->setUniforms(lodProgram_);
  }
}

void Raycaster::setDvrShading(const DvrShading& shading) {
  if (options_.mode != RenderMode::Dvr) throw Error("renderer: gradient shading outside DVR mode");
  checkDvrShading(shading);
  if (options_.dvrShading == shading) return;
  const DvrShading before = options_.dvrShading;
  options_.dvrShading = shading;
  if (shading.on != before.on) {
    try {
      buildRaycastProgram();  // FCC_DVR_SHADING is the program's: the unshaded one stays as fast as it was
    } catch (...) {
      options_.dvrShading = before;  // the programs in use are still the old ones
      throw;
    }
  }
  // uDvrSpecular, uDvrSpecularPower, uDvrLight (inactive in unshaded programs).
  if (dvrTable_) setTransferUniforms();
  ++settings_;
}

void Raycaster::setTerminationOpacity(float opacity) {
  if (!(opacity > 0.0f && opacity <= 1.0f))
    throw ValueError("stop opacity " + std::to_string(opacity) + ": valid are (0, 1]");
  options_.terminationOpacity = opacity;
  if (dvrTable_) setTransferUniforms();  // uStopTransmittance; the compositing variant sets its own every pass
  ++settings_;
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
  dvrTable_->upload(*options_.transfer);
  setTransferUniforms();
}

void Raycaster::setTransferUniforms() {
  for (const GlProgram* program : {&program_, &lodProgram_}) {
    if (program->id() == 0) continue;
    dvrTable_->setUniforms(*program, 1.0f - options_.terminationOpacity);
    // The shaded programs' (location -1, ignored, in the others).
    glProgramUniform1f(program->id(), glGetUniformLocation(program->id(), "uDvrSpecular"), options_.dvrShading.specular);
    glProgramUniform1f(program->id(), glGetUniformLocation(program->id(), "uDvrSpecularPower"),
                       options_.dvrShading.specularPower);
    setDvrLightUniforms(program->id(), options_.dvrShading.light);
  }
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

std::size_t Raycaster::slotBytes() const {
  return BrickPool::slotBytes(*options_.layout) + kSlotBoundsBytes;
}

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
  const auto insideClip = [&](const glm::ivec3& brick, double size = 1.0) {  // size: 2^level
    const glm::dvec3 lo = glm::dvec3(brick) * (16.0 * size), hi = lo + 16.0 * size;
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
  std::vector<std::vector<glm::ivec3>> neededPerLevel{std::move(needed)};
  coarsestNeeded_.clear();
  if (lodDrawing()) {  // the coarser levels' bricks that hold the isovalue, each in its own bricks
    for (std::size_t k = 1; k < levelSources_.size(); ++k) {
      std::vector<glm::ivec3> level;
      const double size = double(uint64_t(1) << k);
      levelSources_[k]->forEachVaryingBrick([&](const glm::ivec3& brick, float lo, float hi) {
        const bool holds = transfer ? !transfer->zeroOn(lo, hi) : lo <= iso && iso <= hi;
        if ((!options_.skipEmpty || holds) && insideClip(brick, size)) level.push_back(brick);
      });
      neededPerLevel.push_back(std::move(level));
    }
    // The isosurface's stand-ins: the coarsest level, loaded first and kept (DVR has none).
    if (!transfer) coarsestNeeded_ = neededPerLevel.back();
  }
  residency_->setNeeded(neededPerLevel);
  // The coarsest level stays resident when it takes under half the pool: every ray then has a level
  // to draw (at most 8 bricks: docs/FORMAT.md).
  const bool pin = lodDrawing() && !coarsestNeeded_.empty() && coarsestNeeded_.size() * 2 < residency_->slotCount();
  residency_->setPinnedLevel(pin ? residency_->levelCount() - 1 : -1);
  uploadPageTable();
}

int Raycaster::passLookahead() const {
  if (options_.lookahead != RenderOptions::kLookaheadAuto) return options_.lookahead;
  const bool oneOpaqueSurfaceAtFullResolution = options_.mode == RenderMode::Iso && !compositesSurfaces(options_) && !lodDrawing();
  // step() marks its pass started before dispatching it; render()'s passes run outside one.
  const bool completeFrame = !stepStarted_;
  return completeFrame && oneOpaqueSurfaceAtFullResolution ? 0 : 2;
}

bool Raycaster::lodDrawing() const {
  // One opaque isosurface (with stand-ins), or DVR (each brick at the level it wants: march's FCC_LOD).
  const bool oneSurfaceOrDvr = options_.mode == RenderMode::Dvr || !compositesSurfaces(options_);
  return levelSources_.size() > 1 && lodProgram_.id() != 0 && oneSurfaceOrDvr && !options_.ownsBrick;
}

void Raycaster::requestCoarsest() {
  if (coarsestNeeded_.empty()) return;
  std::vector<LevelBrick> missing;
  const int coarsest = residency_->levelCount() - 1;
  for (const glm::ivec3& b : coarsestNeeded_)
    if (!residency_->isResident(b, coarsest)) missing.push_back(LevelBrick{b, coarsest});
  loader_->request(missing);
}

bool Raycaster::coarsestResident() const {
  if (!lodDrawing() || coarsestNeeded_.empty()) return true;
  return residency_->missingCount(residency_->levelCount() - 1) == 0;
}

bool Raycaster::raiseBiasIfThrashing(uint64_t uploadedThisView) {
  // More bricks loaded for one view than the pool holds: the wanted working set does not fit, and
  // the frame would stream it through the pool pass after pass. A level coarser needs about a quarter
  // of the bricks (a surface's bricks) to an eighth (a volume's).
  if (!lodDrawing() || !options_.lodAdaptBias || uploadedThisView <= residency_->slotCount()) return false;
  if (double(options_.lodBias) + double(autoBias_) >= double(residency_->levelCount() - 1)) return false;
  autoBias_ += 1.0f;
  return true;
}

std::vector<glm::ivec3> Raycaster::lastRequests() const {
  std::vector<glm::ivec3> level0;
  for (const LevelBrick& b : lastRequests_)
    if (b.level == 0) level0.push_back(b.brick);
  return level0;
}

LevelMix Raycaster::levelMix(uint32_t firstPass) const {
  LevelMix mix;
  mix.lodBias = lodBias();
  const int levels = levelCount();
  mix.bricksPerLevel.assign(std::size_t(levels), 0);
  // Drawn, not loaded: the level-of-detail program stamps the slots it draws from apart (the coarsest
  // level is loaded up front); without levels the slots' last use (a pass's reads, or its uploads).
  std::vector<uint32_t> slotUse(residency_->slotCount());
  if (lodDrawing()) slotDrawn_->read(slotUse);
  else slotUse_->read(slotUse);
  for (uint32_t slot = 0; slot < residency_->slotCount(); ++slot) {
    const int64_t index = residency_->slotBrick(slot);
    if (index < 0 || slotUse[slot] < firstPass) continue;
    const int level = residency_->levelOf(uint32_t(index));
    if (level < levels) ++mix.bricksPerLevel[std::size_t(level)];
  }
  if (lodDrawing()) {
    mix.standInBricksPerLevel.assign(std::size_t(levels), 0);
    slotStandIn_->read(slotUse);
    for (uint32_t slot = 0; slot < residency_->slotCount(); ++slot) {
      const int64_t index = residency_->slotBrick(slot);
      if (index >= 0 && slotUse[slot] >= firstPass) ++mix.standInBricksPerLevel[std::size_t(residency_->levelOf(uint32_t(index)))];
    }
    std::vector<uint32_t> hits(kMaxLodLevels);
    levelHits_->read(hits);
    uint64_t all = 0;
    for (uint32_t h : hits) all += h;
    mix.fullResolutionFraction = all ? double(hits[0]) / double(all) : 1.0;
    if (options_.mode == RenderMode::Dvr) {  // no hits: the share of the bricks drawn that are level 0's
      uint64_t drawn = 0;
      for (uint64_t n : mix.bricksPerLevel) drawn += n;
      mix.fullResolutionFraction = drawn ? double(mix.bricksPerLevel[0]) / double(drawn) : 1.0;
    }
  }
  return mix;
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
  if (lodDrawing() && (resumeState_.width() != width || resumeState_.height() != height))
    resumeState_ = GlTexture2D(GL_R32F, width, height);
  firstPass_ = true;  // every ray starts at t = 0; the first pass writes every pixel's resume value
  viewFirstPass_ = pass_ + 1;
  uploadedThisView_ = 0;
  if (levelHits_) levelHits_->clear();
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
  const bool lod = lodDrawing();
  const GlProgram& program = composite ? surfacesProgram_ : (lod ? lodProgram_ : program_);
  const GLuint p = program.id();
  const Uniforms& u = composite ? surfacesUniforms_ : (lod ? lodUniforms_ : uniforms_);
  const glm::dmat4 indexFromWorld = glm::inverse(source_.worldFromIndex());
  const glm::mat4 indexFromWorldF(indexFromWorld);
  const glm::mat3 normalFromIndex = glm::transpose(glm::mat3(indexFromWorldF));
  const glm::vec3 lightDir = lightTowardsWorld(frame, options_.lightInCamera);
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
  glProgramUniform1i(p, u.lookahead, passLookahead());
  glProgramUniform1i(p, u.skipEmpty, options_.skipEmpty ? 1 : 0);
  glProgramUniform1i(p, u.finiteDifferenceNormals, options_.finiteDifferenceNormals ? 1 : 0);
  glProgramUniform3fv(p, u.surfaceColor, 1, &options_.surfaceColor.x);
  glProgramUniform3fv(p, u.lightDir, 1, &lightDir.x);
  if (options_.mode == RenderMode::Dvr && options_.dvrShading.on && options_.dvrShading.light == DvrLight::Kit)
    setDvrLightFrameUniforms(p, frame);
  const glm::vec3 clipLo(glm::clamp(options_.clipLo, glm::dvec3(-1e30), glm::dvec3(1e30)));
  const glm::vec3 clipHi(glm::clamp(options_.clipHi, glm::dvec3(-1e30), glm::dvec3(1e30)));
  glProgramUniform3fv(p, u.clipLo, 1, &clipLo.x);
  glProgramUniform3fv(p, u.clipHi, 1, &clipHi.x);
  if (source_.slotBlock() == SlotBlock::BccPacked) {
    // The BCC stack schemes' axis and shears, once per frame from the view (march_bcc.glsl): the same
    // choice as Reconstruction::setView with the forward direction in index space.
    const glm::ivec3 params = spline::bcc_sheared_params_for_view(glm::vec3(glm::dmat3(indexFromWorld) * frame.forward));
    glProgramUniform3iv(p, u.bccParams, 1, &params.x);
  }
  if (lod) {
    const int levels = residency_->levelCount();
    glm::ivec3 brickMin[kMaxLodLevels], brickDims[kMaxLodLevels], nodeDims[kMaxLodLevels];
    GLuint pageOffset[kMaxLodLevels], nodeOffset[kMaxLodLevels];
    float scale[kMaxLodLevels], size[kMaxLodLevels];
    for (int k = 0; k < levels; ++k) {
      brickMin[k] = residency_->levelBox(k).brickMin;
      brickDims[k] = residency_->levelBox(k).brickDims;
      nodeDims[k] = residency_->levelNodeDims(k);
      pageOffset[k] = residency_->pageOffset(k);
      nodeOffset[k] = residency_->nodeOffset(k);
      size[k] = std::ldexp(1.0f, k);  // powers of two: exact
      scale[k] = std::ldexp(1.0f, -k);
    }
    const LodUniforms& lu = lodExtra_;
    glProgramUniform1i(p, lu.levelCount, levels);
    glProgramUniform3iv(p, lu.brickMin, levels, &brickMin[0].x);
    glProgramUniform3iv(p, lu.brickDims, levels, &brickDims[0].x);
    glProgramUniform3iv(p, lu.nodeDims, levels, &nodeDims[0].x);
    glProgramUniform1uiv(p, lu.pageOffset, levels, pageOffset);
    glProgramUniform1uiv(p, lu.nodeOffset, levels, nodeOffset);
    glProgramUniform1fv(p, lu.scale, levels, scale);
    glProgramUniform1fv(p, lu.size, levels, size);
    glProgramUniform1f(p, lu.bias, float(lodBias()));
    // frame.up is scaled by tan(fov / 2): a pixel is 2 tan(fov / 2) / height at unit distance.
    glProgramUniform1f(p, lu.pixelAngle, float(2.0 * glm::length(frame.up) / double(height)));
    levelHits_->bindBase(GL_SHADER_STORAGE_BUFFER, 8);
    slotDrawn_->bindBase(GL_SHADER_STORAGE_BUFFER, 9);
    slotStandIn_->bindBase(GL_SHADER_STORAGE_BUFFER, 10);
    resumeState_.bindImage(4, GL_READ_WRITE);
  }
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
  if (dvrTable_) dvrTable_->bind();
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

std::vector<LevelBrick> Raycaster::requestedBricks(uint32_t requestCount, uint32_t* stopped) const {
  const uint32_t n = std::min(requestCount, requestCapacity_);
  const uint32_t copied = std::min(n, options_.requestsReadBack);
  std::vector<uint32_t> raw(passResults_ + kRequestsHeaderWords, passResults_ + kRequestsHeaderWords + copied);
  if (n > copied) {  // a heavy streaming pass: the rest straight from the buffer
    raw.resize(n);
    requests_->read(raw.data() + copied, (n - copied) * sizeof(uint32_t), (kRequestsHeaderWords + copied) * sizeof(uint32_t));
  }
  // The bricks rays stopped at come first: loading them guarantees progress; look-ahead ones follow.
  std::vector<LevelBrick> bricks;
  bricks.reserve(n);
  const auto add = [&](uint32_t index) { bricks.push_back(LevelBrick{residency_->brickAt(index), residency_->levelOf(index)}); };
  for (uint32_t r : raw)
    if (!(r & 0x80000000u)) add(r);
  if (stopped) *stopped = uint32_t(bricks.size());
  for (uint32_t r : raw)
    if (r & 0x80000000u) add(r & 0x7FFFFFFFu);
  // Coarse levels first: a few coarse bricks give every waiting ray something to draw, finer ones
  // replace them as they arrive.
  if (residency_->levelCount() > 1)
    std::stable_sort(bricks.begin(), bricks.end(), [](const LevelBrick& a, const LevelBrick& b) { return a.level > b.level; });
  // No more than the pool holds: every brick loaded in a pass keeps its slot through the pass.
  if (bricks.size() > residency_->slotCount()) bricks.resize(residency_->slotCount());
  return bricks;
}

uint64_t Raycaster::slotsUsedSince(uint32_t pass) const {
  uint64_t n = 0;
  for (uint32_t stamp : readSlotUse()) n += stamp > pass && stamp <= pass_;
  return n;
}

std::vector<uint32_t> Raycaster::readSlotUse() const {
  std::vector<uint32_t> slotUse(residency_->slotCount());
  slotUse_->read(slotUse);
  return slotUse;
}

uint32_t Raycaster::upload(const std::vector<LoadedBrick>& loaded) {
  std::vector<uint32_t> indices;
  indices.reserve(loaded.size());
  for (const LoadedBrick& b : loaded) indices.push_back(residency_->brickIndex(b.brick, b.level));
  const auto assigned = residency_->assignIndices(indices);  // skips bricks resident meanwhile
  if (assigned.empty()) return 0;
  std::vector<uint32_t> slots;
  std::vector<const float*> blocks;
  std::size_t next = 0;
  for (const auto& [index, slot] : assigned) {
    while (indices[next] != index) ++next;  // assignIndices() keeps the order
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
  if (lodDrawing()) noteView(frame, width, height);
  if (lowerBiasPending_ && autoBias_ - 1.0f > thrashBias_) autoBias_ -= 1.0f;
  lowerBiasPending_ = false;
  restartRays(width, height);
  requestCoarsest();
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
    uploadedThisView_ += uploaded;
    if (raiseBiasIfThrashing(uploadedThisView_)) {  // coarser bricks for every ray, from the start
      thrashBias_ = autoBias_ - 1.0f;
      ++stats.lodRestarts;
      restartRays(width, height);
      requestCoarsest();
    }
  }
  // No glFinish: the last pass's read-back waited for every command of the frame.
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The mix reads the slots' stamps back (4 bytes a slot), outside the frame's time; the bias's rule
  // reads it too.
  if (options_.countBricksDrawn || (lodDrawing() && autoBias_ > 0.0f)) finishLevelMix(stats);
  stats.lodBias = lodBias();
  return stats;
}

void Raycaster::finishLevelMix(FrameStats& stats) {
  const LevelMix mix = levelMix();
  stats.bricksPerLevel = mix.bricksPerLevel;
  stats.fullResolutionFraction = mix.fullResolutionFraction;
  stats.lodBias = mix.lodBias;
  noteFrameUse(mix);
}

void Raycaster::noteFrameUse(const LevelMix& mix) {
  // A frame that used under an eighth of the pool would fit a level finer (about four times the
  // bricks): the next frame tries it, unless this view already streamed through the pool there.
  uint64_t used = 0;
  for (uint64_t n : mix.bricksPerLevel) used += n;
  lowerBiasPending_ = lodDrawing() && autoBias_ > 0.0f && used * 8 < residency_->slotCount() && autoBias_ - 1.0f > thrashBias_;
}

void Raycaster::noteView(const CameraFrame& frame, int width, int height) {
  if (frame.eye == lodView_.frame.eye && frame.forward == lodView_.frame.forward && frame.right == lodView_.frame.right &&
      frame.up == lodView_.frame.up && width == lodView_.width && height == lodView_.height)
    return;
  lodView_.frame = frame;
  lodView_.width = width;
  lodView_.height = height;
  thrashBias_ = -1.0f;  // a new view may fit where the last did not
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
    if (lodDrawing()) noteView(frame, width, height);
    restartRays(width, height);
    loader_->cancelQueued();  // requests of the old view; what still arrives is uploaded all the same
    requestCoarsest();
    stepComplete_ = false;
    stats.restarted = true;
  } else if (lowerBiasPending_) {  // the completed frame used little of the pool: a level finer
    lowerBiasPending_ = false;
    autoBias_ -= 1.0f;
    restartRays(width, height);
    stepComplete_ = false;
    stats.restarted = true;
  }
  // Uploads first, so this step's pass already sees them; also once the frame is complete, so that
  // bricks still arriving (look-ahead requests) do not wait in the loader forever.
  // A batch starts only if the time so far and the longest batch yet fit in uploadSeconds (the first
  // always runs): stopping once the time is spent let the last batch run past it.
  const auto start = std::chrono::steady_clock::now();
  bool assigning = false;
  double longestBatch = 0.0, elapsed = 0.0;
  do {
    std::vector<LoadedBrick> loaded = loader_->take(kStepUploadBatch, false);
    if (loaded.empty()) break;
    if (!assigning) residency_->startAssigning(readSlotUse());  // once a step: not a batch's own time
    assigning = true;
    const auto batchStart = std::chrono::steady_clock::now();
    stats.uploaded += upload(loaded);
    loader_->recycle(std::move(loaded));
    const auto batchEnd = std::chrono::steady_clock::now();
    longestBatch = std::max(longestBatch, std::chrono::duration<double>(batchEnd - batchStart).count());
    elapsed = std::chrono::duration<double>(batchEnd - start).count();
  } while (elapsed + longestBatch <= uploadSeconds);
  if (stats.uploaded) updatePageTable();
  stats.uploadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  uploadedThisView_ += stats.uploaded;
  if (!stepComplete_ && raiseBiasIfThrashing(uploadedThisView_)) {  // coarser bricks, from the start
    thrashBias_ = autoBias_ - 1.0f;
    restartRays(width, height);
    loader_->cancelQueued();
    requestCoarsest();
    stats.restarted = true;
  }
  stats.bytesUploaded = uint64_t(stats.uploaded) * slotBlockFloats(source_.slotBlock()) * sizeof(float);

  stepStarted_ = true;
  if (stepComplete_) return;
  stats.dispatched = true;
  const auto dispatch = std::chrono::steady_clock::now();
  dispatchPass(frame, width, height, coveredColumns);
  stats.dispatchSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - dispatch).count();
}

StepStats Raycaster::finishStep() {
  if (!stepStarted_) throw Error("renderer: finishStep() without startStep()");
  stepStarted_ = false;
  StepStats stats = startedStep_;
  if (stats.dispatched) {
    const auto wait = std::chrono::steady_clock::now();
    const PassResult pass = collectPass();
    const auto collected = std::chrono::steady_clock::now();
    stats.passSeconds = std::chrono::duration<double>(collected - wait).count();
    stats.requested = pass.requested;
    stats.gpuSeconds = pass.gpuSeconds;
    if (stats.requested == 0) {
      stepComplete_ = true;
      if (lodDrawing() && autoBias_ > 0.0f) noteFrameUse(levelMix());
    } else {
      loader_->request(lastRequests_ = requestedBricks(stats.requested, &stats.missing));
    }
    stats.requestSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - collected).count();
    // Slots uploaded before the pass carry the pass before's stamp: only what the rays drew counts
    // (with levels: the slots this pass drew from, wanted or stand-in, per level).
    if (options_.countBricksDrawn) {
      if (lodDrawing()) {
        const LevelMix mix = levelMix(pass_);
        stats.bricksPerLevel = mix.bricksPerLevel;
        for (std::size_t k = 0; k < mix.standInBricksPerLevel.size(); ++k) stats.bricksPerLevel[k] += mix.standInBricksPerLevel[k];
        stats.fullResolutionFraction = mix.fullResolutionFraction;
      } else {
        stats.bricksPerLevel = {slotsUsedSince(pass_ - 1)};
      }
    }
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
