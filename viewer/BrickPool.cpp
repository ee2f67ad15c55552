#include "BrickPool.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "embedded_shaders.h"
#include "io/BrickCache.h"
#include "sparse/Error.h"

namespace fcc::render {
namespace {

constexpr int kPackedDim = io::kHaloBlockDim;  // 10: packed voxels per slot side
constexpr int kSiteDim = 2 * kPackedDim;       // 20: lattice sites per slot side (one-channel embedding)

bool isScalar(BrickLayout l) { return l == BrickLayout::SsboScalar || l == BrickLayout::TextureScalar; }
bool isTexture(BrickLayout l) { return l == BrickLayout::TextureVec4 || l == BrickLayout::TextureScalar; }
int slotDim(BrickLayout l) { return isScalar(l) ? kSiteDim : kPackedDim; }

// Slots per axis of a 3D texture holding `slots` blocks of dim^3 texels, close to a cube.
glm::ivec3 textureGrid(std::size_t slots, int dim) {
  GLint max3d = 0;
  glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
  const int perAxis = std::max(1, max3d / dim);
  const int x = std::clamp(int(std::ceil(std::cbrt(double(slots)))), 1, perAxis);
  const int y = std::clamp(int(std::ceil(std::sqrt(double(slots) / x))), 1, perAxis);
  const int z = int((slots + std::size_t(x) * y - 1) / (std::size_t(x) * y));
  if (z > perAxis)
    throw GlError("brick pool: " + std::to_string(slots) + " slots do not fit a 3D texture (GL_MAX_3D_TEXTURE_SIZE " +
                  std::to_string(max3d) + ")");
  return {x, y, z};
}

// Site l of a scalar slot (global 16b - 2 + l, an even offset) is packed voxel l >> 1 of the halo
// block, channel ((l.x & 1) << 1) | (l.y & 1); sites with an odd coordinate sum are not FCC sites.
void spreadOverSites(const float* haloBlock, float* sites) {
  for (int z = 0; z < kSiteDim; ++z)
    for (int y = 0; y < kSiteDim; ++y)
      for (int x = 0; x < kSiteDim; ++x) {
        const std::size_t site = (std::size_t(z) * kSiteDim + y) * kSiteDim + x;
        if ((x + y + z) & 1) {
          sites[site] = 0.0f;
          continue;
        }
        const std::size_t packed = (std::size_t(z >> 1) * kPackedDim + (y >> 1)) * kPackedDim + (x >> 1);
        sites[site] = haloBlock[packed * 4 + std::size_t(((x & 1) << 1) | (y & 1))];
      }
}

}  // namespace

const std::vector<BrickLayout>& allBrickLayouts() {
  static const std::vector<BrickLayout> all = {BrickLayout::SsboVec4, BrickLayout::SsboScalar, BrickLayout::TextureVec4,
                                               BrickLayout::TextureScalar};
  return all;
}

std::string brickLayoutName(BrickLayout layout) {
  switch (layout) {
    case BrickLayout::SsboVec4: return "ssbo-vec4";
    case BrickLayout::SsboScalar: return "ssbo-scalar";
    case BrickLayout::TextureVec4: return "texture-vec4";
    case BrickLayout::TextureScalar: return "texture-scalar";
  }
  return "?";
}

BrickLayout parseBrickLayout(const std::string& name) {
  std::string valid;
  for (BrickLayout l : allBrickLayouts()) {
    if (brickLayoutName(l) == name) return l;
    valid += (valid.empty() ? "" : ", ") + brickLayoutName(l);
  }
  throw ValueError("brick layout '" + name + "': valid layouts are " + valid);
}

std::size_t BrickPool::slotBytes(BrickLayout layout) {
  const std::size_t dim = std::size_t(slotDim(layout));
  return dim * dim * dim * (isScalar(layout) ? 1 : 4) * sizeof(float);
}

std::size_t BrickPool::maxSlots(BrickLayout layout) {
  if (isTexture(layout)) {
    GLint max3d = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
    const std::size_t perAxis = std::size_t(std::max(1, max3d / slotDim(layout)));
    return perAxis * perAxis * perAxis;
  }
  GLint64 maxBlock = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
  return std::size_t(maxBlock) / slotBytes(layout);
}

BrickPool::BrickPool(BrickLayout layout, std::size_t slots, SlotBlock block)
    : layout_(layout), slots_(std::max<std::size_t>(slots, 1)), block_(block) {
  if (block != SlotBlock::FccPacked && !isScalar(layout)) {
    std::string scalar;
    for (BrickLayout l : allBrickLayouts())
      if (isScalar(l)) scalar += (scalar.empty() ? "" : ", ") + brickLayoutName(l);
    throw ValueError("brick layout '" + brickLayoutName(layout) + "' packs the FCC lattice's four channels; this lattice's bricks need a one-channel layout: " + scalar);
  }
  // Three segments of 256 slots (4 or 8 MB each): the renderer's upload batch, with room for the GPU
  // to still copy two earlier batches.
  stagingSlots_ = std::min<std::size_t>(slots_, 256);
  staging_ = std::make_unique<GlUploadBuffer>(stagingSlots_ * slotBytes(layout), 3);
  batchSlots_ = std::make_unique<GlBuffer>(stagingSlots_ * sizeof(uint32_t));
  scatter_ = GlProgram::compute(withDefines(embedded::shaders("shaders/pool_upload.comp"), glslDefines()),
                                "shaders/pool_upload.comp");
  if (!isTexture(layout)) {
    buffer_ = std::make_unique<GlBuffer>(slots_ * slotBytes(layout));
    return;
  }
  const int dim = slotDim(layout);
  grid_ = textureGrid(slots_, dim);
  glCreateTextures(GL_TEXTURE_3D, 1, &texture_);
  glTextureStorage3D(texture_, 1, isScalar(layout) ? GL_R32F : GL_RGBA32F, grid_.x * dim, grid_.y * dim, grid_.z * dim);
  glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  setUniforms(scatter_);
  checkGl("creating the " + brickLayoutName(layout) + " brick pool of " + std::to_string(slots_) + " slots");
}

BrickPool::~BrickPool() {
  if (texture_) glDeleteTextures(1, &texture_);
}

std::string BrickPool::glslDefines() const {
  std::string defines = "#define FCC_POOL_LAYOUT " + std::to_string(int(layout_)) + "\n";
  if (block_ == SlotBlock::BccPacked) defines += "#define FCC_SLOT_BCC 1\n";  // pool.glsl's BCC site reader
  return defines;
}

void BrickPool::setUniforms(const GlProgram& program) const {
  if (!isTexture(layout_)) return;
  const GLint grid = glGetUniformLocation(program.id(), "uPoolGrid");
  if (grid >= 0) glProgramUniform2i(program.id(), grid, grid_.x, grid_.y);
}

void BrickPool::upload(const std::vector<uint32_t>& slots, const std::vector<const float*>& blocks) {
  if (slots.size() != blocks.size()) throw Error("brick pool: " + std::to_string(slots.size()) + " slots for " +
                                                 std::to_string(blocks.size()) + " blocks");
  const std::size_t bytes = slotBytes(layout_);
  for (std::size_t first = 0; first < slots.size(); first += stagingSlots_) {
    const std::size_t count = std::min(stagingSlots_, slots.size() - first);
    std::size_t segmentOffset = 0;
    char* segment = static_cast<char*>(staging_->begin(segmentOffset));
    tbb::parallel_for(std::size_t(0), count, [&](std::size_t i) {
      float* out = reinterpret_cast<float*>(segment + i * bytes);
      if (block_ != SlotBlock::FccPacked) std::memcpy(out, blocks[first + i], bytes);
      else if (isScalar(layout_)) spreadOverSites(blocks[first + i], out);
      else std::memcpy(out, blocks[first + i], bytes);
    });
    batchSlots_->write(slots.data() + first, count * sizeof(uint32_t));
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 8, staging_->id(), GLintptr(segmentOffset), GLsizeiptr(count * bytes));
    batchSlots_->bindBase(GL_SHADER_STORAGE_BUFFER, 9);
    if (buffer_) buffer_->bindBase(GL_SHADER_STORAGE_BUFFER, 10);
    else glBindImageTexture(3, texture_, 0, GL_TRUE, 0, GL_WRITE_ONLY, isScalar(layout_) ? GL_R32F : GL_RGBA32F);
    scatter_.use();
    const GLuint texels = GLuint(slotDim(layout_) * slotDim(layout_) * slotDim(layout_));
    glDispatchCompute((texels + 63) / 64, GLuint(count), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    staging_->end();
  }
  checkGl("uploading " + std::to_string(slots.size()) + " bricks into the " + brickLayoutName(layout_) + " pool");
}

void BrickPool::bind() const {
  if (buffer_) buffer_->bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  else glBindTextureUnit(3, texture_);
}

}  // namespace fcc::render
