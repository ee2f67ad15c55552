// The GPU pool of resident bricks in one of four layouts (shaders/pool.glsl describes them), so the
// layouts can be compared by measurement (`fccvdb bench render --layout all`). A slot is filled from
// io::assembleHaloBlock's 10^3 packed voxels; the scalar layouts spread them over the 20^3 lattice
// sites of the one-channel embedding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "BrickSource.h"
#include "GlProgram.h"

namespace fcc::render {

enum class BrickLayout { SsboVec4 = 0, SsboScalar = 1, TextureVec4 = 2, TextureScalar = 3 };

const std::vector<BrickLayout>& allBrickLayouts();
std::string brickLayoutName(BrickLayout layout);  // "ssbo-vec4", "ssbo-scalar", "texture-vec4", "texture-scalar"
// ValueError listing the valid names.
BrickLayout parseBrickLayout(const std::string& name);

class BrickPool {
 public:
  // GPU bytes of one slot's values in `layout`.
  static std::size_t slotBytes(BrickLayout layout);
  // The most slots this GL implementation can hold in `layout` (SSBO size or 3D texture limits).
  static std::size_t maxSlots(BrickLayout layout);

  // Slots filled from `block`s (BrickSource.h); SlotBlock::Sites and BccPacked need a scalar layout (ValueError
  // naming them otherwise). Needs a current OpenGL 4.5 context.
  BrickPool(BrickLayout layout, std::size_t slots, SlotBlock block = SlotBlock::FccPacked);
  ~BrickPool();
  BrickPool(const BrickPool&) = delete;
  BrickPool& operator=(const BrickPool&) = delete;

  BrickLayout layout() const { return layout_; }
  std::size_t slots() const { return slots_; }
  // "#define FCC_POOL_LAYOUT n" for shaders that include pool.glsl; then setUniforms() on each program
  // (the texture layouts' uPoolGrid).
  std::string glslDefines() const;
  void setUniforms(const GlProgram& program) const;
  // Fills slots[i] from blocks[i] for every i: halo blocks of io::kHaloBlockVoxels packed voxels (4
  // floats each, x fastest), or blocks of 20^3 floats (SlotBlock::Sites, BccPacked), copied as they are. The blocks are staged side by side in a mapped buffer by all cores (the
  // scalar layouts spread over their sites on the way), then copied into their slots on the GPU by one
  // compute dispatch a batch: no GL call a slot, no copy through the driver.
  void upload(const std::vector<uint32_t>& slots, const std::vector<const float*>& blocks);
  // Binds the pool where pool.glsl reads it (SSBO binding 0, or texture unit 3).
  void bind() const;

 private:
  BrickLayout layout_;
  std::size_t slots_;
  SlotBlock block_;
  glm::ivec3 grid_{1};                 // texture layouts: slots per axis
  std::unique_ptr<GlBuffer> buffer_;   // SSBO layouts
  GLuint texture_ = 0;                 // texture layouts
  std::unique_ptr<GlUploadBuffer> staging_;
  std::unique_ptr<GlBuffer> batchSlots_;  // the slots of a staged segment
  GlProgram scatter_;                     // shaders/pool_upload.comp: staged segment -> slots
  std::size_t stagingSlots_ = 0;       // slots one segment of staging_ holds
};

}  // namespace fcc::render
