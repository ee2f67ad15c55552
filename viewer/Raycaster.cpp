#include "Raycaster.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "embedded_shaders.h"
#include "sparse/Error.h"

namespace fcc::render {
namespace {

constexpr std::size_t kSlotBytes = std::size_t(io::kHaloBlockVoxels) * 4 * sizeof(float);
constexpr std::size_t kSlotVoxels = 512;  // per-voxel cell bounds of a slot (shaders/pool.glsl)
constexpr std::size_t kSlotBoundsBytes = kSlotVoxels * 2 * sizeof(float);
constexpr int kLocalSize = 8;             // shaders/raycast.comp's local_size_x and _y
constexpr std::size_t kUploadBatch = 256; // bricks assembled per staging batch (4 MB)
constexpr int kMaxPasses = 1 << 20;       // a frame that needs more has a bug, not a small pool

glm::ivec3 toGlm(const openvdb::Coord& c) { return {c.x(), c.y(), c.z()}; }

}  // namespace

Raycaster::Raycaster(const io::BrickStore& store, const RenderOptions& options) : store_(store), options_(options) {
  program_ = GlProgram::compute(embedded::shaders("shaders/raycast.comp"), "shaders/raycast.comp");
  // A CPU rasteriser gets the cheap coefficient-hull cell bounds, a GPU the BB-coefficient ones
  // (both conservative; the image is the same, only the work skipped differs).
  std::string slotBounds(embedded::shaders("shaders/slot_bounds.comp"));
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (!(renderer && std::string(renderer).find("llvmpipe") != std::string::npos)) {
    const auto eol = slotBounds.find('\n');  // after #version, which must stay first
    slotBounds.insert(eol + 1, "#define FCC_SLOT_BOUNDS_BB 1\n");
  }
  slotBoundsProgram_ = GlProgram::compute(slotBounds, "shaders/slot_bounds.comp");

  const openvdb::CoordBBox box = store.activeBrickBox();
  const glm::ivec3 brickMin = box.empty() ? glm::ivec3(0) : toGlm(box.min());
  const glm::ivec3 brickDims = box.empty() ? glm::ivec3(1) : toGlm(box.dim());
  const std::size_t bricksInBox = std::size_t(brickDims.x) * brickDims.y * brickDims.z;

  GLint64 maxBlock = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
  // The GPU budget pays for a slot's data and its cell bounds.
  std::size_t slots = options.gpuCacheBytes / (kSlotBytes + kSlotBoundsBytes);
  slots = std::min(slots, std::size_t(maxBlock) / kSlotBytes);
  slots = std::min(slots, bricksInBox);
  slots = std::max<std::size_t>(slots, 1);
  residency_ = std::make_unique<Residency>(brickMin, brickDims, uint32_t(slots));
  hostCache_ = std::make_unique<io::BrickCache>(store, options.hostCacheBytes);

  requestCapacity_ = uint32_t(std::min<std::size_t>(bricksInBox, 1 << 16));
  pool_ = std::make_unique<GlBuffer>(slots * kSlotBytes);
  slotBounds_ = std::make_unique<GlBuffer>(slots * kSlotBoundsBytes);
  uploadedSlots_ = std::make_unique<GlBuffer>(kUploadBatch * sizeof(uint32_t));
  pageTable_ = std::make_unique<GlBuffer>(bricksInBox * sizeof(uint32_t));
  nodeTable_ = std::make_unique<GlBuffer>(residency_->nodeEntries().size() * sizeof(uint32_t));
  requests_ = std::make_unique<GlBuffer>((1 + std::size_t(requestCapacity_)) * sizeof(uint32_t));
  requestBits_ = std::make_unique<GlBuffer>((bricksInBox / 32 + 1) * sizeof(uint32_t));
  slotUse_ = std::make_unique<GlBuffer>(slots * sizeof(uint32_t));
  slotUse_->clear();
  setIso(0.5f * (store.valueMin() + store.valueMax()));
}

Raycaster::~Raycaster() = default;

void Raycaster::setIso(float iso) {
  if (!std::isfinite(iso)) throw ValueError("isovalue " + std::to_string(iso) + " is not finite");
  iso_ = iso;
  std::vector<glm::ivec3> needed;
  for (auto it = store_.bounds().cbeginValueOn(); it; ++it) {
    const openvdb::Vec2f range = *it;
    if (options_.skipEmpty && !(range[0] <= iso && iso <= range[1])) continue;
    needed.push_back(toGlm(it.getCoord()));
  }
  residency_->setNeeded(needed);
  uploadPageTable();
}

void Raycaster::setSkipEmpty(bool skip) {
  options_.skipEmpty = skip;
  setIso(iso_);
}

void Raycaster::computeSlotBounds(const std::vector<uint32_t>& slots) {
  uploadedSlots_->write(slots);
  pool_->bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  slotBounds_->bindBase(GL_SHADER_STORAGE_BUFFER, 6);
  uploadedSlots_->bindBase(GL_SHADER_STORAGE_BUFFER, 7);
  slotBoundsProgram_.use();
  glDispatchCompute(GLuint(kSlotVoxels / 64), GLuint(slots.size()), 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  checkGl("computing the cell bounds of " + std::to_string(slots.size()) + " uploaded bricks");
}

void Raycaster::uploadPageTable() {
  pageTable_->write(residency_->pageEntries());
  if (options_.skipEmpty) {
    nodeTable_->write(residency_->nodeEntries());
  } else {
    const std::vector<uint32_t> all(residency_->nodeEntries().size(), 1u);
    nodeTable_->write(all);
  }
}

void Raycaster::prepareImages(int width, int height) {
  if (color_.width() != width || color_.height() != height) {
    color_ = GlTexture2D(GL_RGBA32F, width, height);
    normalDepth_ = GlTexture2D(GL_RGBA32F, width, height);
    resume_ = GlTexture2D(GL_R32F, width, height);
  }
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  resume_.clear(zero);  // every ray starts at t = 0
}

uint32_t Raycaster::dispatchPass(const CameraFrame& frame, int width, int height) {
  ++pass_;
  requests_->clear();
  requestBits_->clear();

  const GLuint p = program_.id();
  const glm::dmat4 indexFromWorld = glm::inverse(store_.worldFromIndex());
  const glm::mat4 indexFromWorldF(indexFromWorld);
  const glm::mat3 normalFromIndex = glm::transpose(glm::mat3(indexFromWorldF));
  const glm::vec3 lightDir = glm::normalize(glm::vec3(-frame.forward) + 0.6f * glm::vec3(glm::normalize(frame.up)) +
                                            0.3f * glm::vec3(glm::normalize(frame.right)));
  glProgramUniform2i(p, program_.uniformLocation("uResolution"), width, height);
  const glm::vec3 eye(frame.eye), forward(frame.forward), right(frame.right), up(frame.up);
  glProgramUniform3fv(p, program_.uniformLocation("uEye"), 1, &eye.x);
  glProgramUniform3fv(p, program_.uniformLocation("uForward"), 1, &forward.x);
  glProgramUniform3fv(p, program_.uniformLocation("uRight"), 1, &right.x);
  glProgramUniform3fv(p, program_.uniformLocation("uUp"), 1, &up.x);
  glProgramUniformMatrix4fv(p, program_.uniformLocation("uIndexFromWorld"), 1, GL_FALSE, &indexFromWorldF[0][0]);
  glProgramUniformMatrix3fv(p, program_.uniformLocation("uNormalFromIndex"), 1, GL_FALSE, &normalFromIndex[0][0]);
  glProgramUniform1f(p, program_.uniformLocation("uIso"), iso_);
  glProgramUniform3iv(p, program_.uniformLocation("uBrickMin"), 1, &residency_->brickMin().x);
  glProgramUniform3iv(p, program_.uniformLocation("uBrickDims"), 1, &residency_->brickDims().x);
  glProgramUniform3iv(p, program_.uniformLocation("uNodeDims"), 1, &residency_->nodeDims().x);
  glProgramUniform1ui(p, program_.uniformLocation("uPass"), pass_);
  glProgramUniform1ui(p, program_.uniformLocation("uRequestCapacity"), requestCapacity_);
  glProgramUniform1i(p, program_.uniformLocation("uLookahead"), options_.lookahead);
  glProgramUniform1i(p, program_.uniformLocation("uSkipEmpty"), options_.skipEmpty ? 1 : 0);
  glProgramUniform1i(p, program_.uniformLocation("uFiniteDifferenceNormals"), options_.finiteDifferenceNormals ? 1 : 0);
  glProgramUniform3fv(p, program_.uniformLocation("uSurfaceColor"), 1, &options_.surfaceColor.x);
  glProgramUniform3fv(p, program_.uniformLocation("uLightDir"), 1, &lightDir.x);

  pool_->bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  pageTable_->bindBase(GL_SHADER_STORAGE_BUFFER, 1);
  nodeTable_->bindBase(GL_SHADER_STORAGE_BUFFER, 2);
  requests_->bindBase(GL_SHADER_STORAGE_BUFFER, 3);
  requestBits_->bindBase(GL_SHADER_STORAGE_BUFFER, 4);
  slotUse_->bindBase(GL_SHADER_STORAGE_BUFFER, 5);
  slotBounds_->bindBase(GL_SHADER_STORAGE_BUFFER, 6);
  color_.bindImage(0, GL_WRITE_ONLY);
  normalDepth_.bindImage(1, GL_WRITE_ONLY);
  resume_.bindImage(2, GL_READ_WRITE);

  program_.use();
  glDispatchCompute(GLuint((width + kLocalSize - 1) / kLocalSize), GLuint((height + kLocalSize - 1) / kLocalSize), 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                  GL_TEXTURE_UPDATE_BARRIER_BIT);
  checkGl("raycasting pass " + std::to_string(pass_));
  uint32_t count = 0;
  requests_->read(&count, sizeof count);
  return count;
}

uint64_t Raycaster::loadRequested(uint32_t requestCount) {
  const uint32_t n = std::min(requestCount, requestCapacity_);
  std::vector<uint32_t> raw(n);
  requests_->read(raw.data(), n * sizeof(uint32_t), sizeof(uint32_t));
  // The bricks rays stopped at come first: loading them guarantees progress; look-ahead ones follow.
  std::vector<glm::ivec3> bricks;
  bricks.reserve(n);
  for (uint32_t r : raw)
    if (!(r & 0x80000000u)) bricks.push_back(residency_->brickAt(r));
  for (uint32_t r : raw)
    if (r & 0x80000000u) bricks.push_back(residency_->brickAt(r & 0x7FFFFFFFu));

  std::vector<uint32_t> slotUse(residency_->slotCount());
  slotUse_->read(slotUse);
  const auto assigned = residency_->assign(bricks, slotUse);
  if (assigned.empty()) throw Error("renderer: rays requested bricks but none could be given a pool slot");

  std::vector<float> staging(std::min(kUploadBatch, assigned.size()) * io::kHaloBlockVoxels * 4);
  for (std::size_t begin = 0; begin < assigned.size(); begin += kUploadBatch) {
    const std::size_t end = std::min(assigned.size(), begin + kUploadBatch);
    tbb::parallel_for(begin, end, [&](std::size_t i) {
      io::assembleHaloBlock(store_, *hostCache_, assigned[i].first,
                            staging.data() + (i - begin) * io::kHaloBlockVoxels * 4);
    });
    std::vector<uint32_t> slots;
    for (std::size_t i = begin; i < end; ++i) {
      pool_->write(staging.data() + (i - begin) * io::kHaloBlockVoxels * 4, kSlotBytes,
                   std::size_t(assigned[i].second) * kSlotBytes);
      // Freshly loaded slots count as used now, so the next assignment does not evict them first.
      slotUse_->write(&pass_, sizeof pass_, std::size_t(assigned[i].second) * sizeof(uint32_t));
      slots.push_back(assigned[i].second);
    }
    computeSlotBounds(slots);
  }
  uploadPageTable();
  return assigned.size();
}

FrameStats Raycaster::render(const Camera& camera, int width, int height) {
  if (width <= 0 || height <= 0)
    throw ValueError("image size " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
  const auto start = std::chrono::steady_clock::now();
  const CameraFrame frame = cameraFrame(camera, double(width) / double(height));
  prepareImages(width, height);
  FrameStats stats;
  stats.bricksNeeded = residency_->neededCount();
  for (;;) {
    ++stats.passes;
    const uint32_t requested = dispatchPass(frame, width, height);
    if (requested == 0) break;
    if (stats.passes >= kMaxPasses) throw Error("renderer: the frame did not complete in " + std::to_string(kMaxPasses) + " passes");
    stats.bricksUploaded += loadRequested(requested);
  }
  glFinish();
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

FrameImages Raycaster::readImages() const {
  FrameImages out;
  out.width = color_.width();
  out.height = color_.height();
  out.rgba = color_.read(GL_RGBA, 4);
  out.normalDepth = normalDepth_.read(GL_RGBA, 4);
  return out;
}

}  // namespace fcc::render
