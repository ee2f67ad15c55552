// Which bricks the GPU pool holds, in which slots, and the page table the raycaster reads: for every
// brick of a dense box, kSkip (its bounds exclude the isovalue, or it is constant) or kMissing (needed,
// not resident) or its pool slot; and per node of 16^3 bricks whether any brick in it is needed.
// With a level-of-detail pyramid (docs/RENDERER.md, "Level of detail") there is one such box per
// level, their page and node entries concatenated (level 0 first): a brick is named by its index into
// the concatenated page table, and the pool's slots are shared by every level.
// Pure bookkeeping, no OpenGL: the raycaster uploads what this computes.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace fcc::render {

class Residency {
 public:
  static constexpr uint32_t kSkip = 0xFFFFFFFFu;
  static constexpr uint32_t kMissing = 0xFFFFFFFEu;
  static constexpr int kNodeBricks = 16;  // bricks per node side (an internal node of the FCC tree)

  // One level's box of bricks [brickMin, brickMin + brickDims), in that level's brick coordinates.
  struct LevelBox {
    glm::ivec3 brickMin{0}, brickDims{1};
  };
  // The box of bricks [brickMin, brickMin + brickDims) and the number of pool slots: one level.
  Residency(const glm::ivec3& brickMin, const glm::ivec3& brickDims, uint32_t slotCount);
  // One box per level, level 0 first.
  Residency(const std::vector<LevelBox>& levels, uint32_t slotCount);

  // Level 0's box.
  const glm::ivec3& brickMin() const { return levels_[0].box.brickMin; }
  const glm::ivec3& brickDims() const { return levels_[0].box.brickDims; }
  const glm::ivec3& nodeDims() const { return levels_[0].nodeDims; }
  int levelCount() const { return int(levels_.size()); }
  const LevelBox& levelBox(int level) const { return levels_[std::size_t(level)].box; }
  const glm::ivec3& levelNodeDims(int level) const { return levels_[std::size_t(level)].nodeDims; }
  uint32_t pageOffset(int level) const { return levels_[std::size_t(level)].pageOffset; }  // into pageEntries()
  uint32_t nodeOffset(int level) const { return levels_[std::size_t(level)].nodeOffset; }  // into nodeEntries()
  uint32_t slotCount() const { return uint32_t(slotBrick_.size()); }
  uint32_t brickIndex(const glm::ivec3& brick, int level = 0) const;  // into pageEntries()
  glm::ivec3 brickAt(uint32_t index) const;  // in its level's brick coordinates
  int levelOf(uint32_t index) const;

  // The bricks that need evaluation for the current isovalue (all inside the box). Resident bricks
  // stay resident whether needed or not (an isovalue change back costs nothing). The first form is
  // level 0's (other levels need none); the second one list per level.
  void setNeeded(const std::vector<glm::ivec3>& bricks);
  void setNeeded(const std::vector<std::vector<glm::ivec3>>& bricksPerLevel);
  std::size_t neededCount() const { return neededCount_; }
  std::size_t neededCount(int level) const { return levels_[std::size_t(level)].needed; }

  // Slots holding a brick of `level` or coarser are never evicted (-1: none). The raycaster pins the
  // coarsest level of a pyramid (at most 8 bricks), so that every ray always has a level to draw.
  void setPinnedLevel(int level) { pinnedLevel_ = level; }
  int pinnedLevel() const { return pinnedLevel_; }

  // Orders the slots for eviction once per pass: free slots first, then the least recently used
  // (slotLastUse, the pass that last read each slot). The order is fixed here and sorted in parts as
  // assigning reaches them (nextSlotInOrder): a pass takes a few thousand of 40 k slots.
  void startAssigning(const std::vector<uint32_t>& slotLastUse);
  // Assigns pool slots to `bricks` (not yet resident), in order, taking slots in the order
  // startAssigning made and never one assigned since then. Returns (brick, slot) pairs (fewer when
  // the order runs out); the page table already points to them. Level 0's bricks.
  std::vector<std::pair<glm::ivec3, uint32_t>> assign(const std::vector<glm::ivec3>& bricks);
  // The same for bricks of any level, named by index: (index, slot) pairs.
  std::vector<std::pair<uint32_t, uint32_t>> assignIndices(const std::vector<uint32_t>& indices);
  // Both at once: one call's worth of assignments.
  std::vector<std::pair<glm::ivec3, uint32_t>> assign(const std::vector<glm::ivec3>& bricks,
                                                      const std::vector<uint32_t>& slotLastUse) {
    startAssigning(slotLastUse);
    return assign(bricks);
  }
  // The page entries changed since the last call (indices into pageEntries(), each once; all of them
  // after setNeeded), cleared by the call: what an upload of the page table must write.
  std::vector<uint32_t> takeChangedEntries();
  bool allEntriesChanged() const { return allChanged_; }

  bool isResident(const glm::ivec3& brick, int level = 0) const;
  uint32_t residentCount() const { return uint32_t(brickSlot_.size()); }
  // The brick index a slot holds, or -1 for a free slot.
  int64_t slotBrick(uint32_t slot) const { return slotBrick_[slot]; }
  // Needed bricks not resident (what the current isovalue may still have to stream).
  std::size_t missingCount() const;
  std::size_t missingCount(int level) const;

  const std::vector<uint32_t>& pageEntries() const { return pageEntries_; }
  const std::vector<uint32_t>& nodeEntries() const { return nodeEntries_; }

 private:
  struct Level {
    LevelBox box;
    glm::ivec3 nodeDims{1};
    uint32_t pageOffset = 0, nodeOffset = 0;
    std::size_t needed = 0, residentNeeded = 0;
  };
  std::vector<Level> levels_;
  std::vector<uint32_t> pageEntries_;
  std::vector<uint32_t> nodeEntries_;
  std::vector<uint8_t> needed_;            // per brick index
  std::vector<int64_t> slotBrick_;         // per slot: brick index, or -1 when free
  std::unordered_map<uint32_t, uint32_t> brickSlot_;
  // startAssigning's order of the slots, sorted up to sortedEnd_ (nextSlotInOrder sorts more as
  // assigning reaches it): ((free 0, used 1) << 32 | the pass that last used it, slot).
  struct OrderedSlot {
    uint64_t used;
    uint32_t slot;
    bool operator<(const OrderedSlot& o) const { return used != o.used ? used < o.used : slot < o.slot; }
  };
  static constexpr std::size_t kFirstSortedSlots = 2048;
  bool nextSlotInOrder(uint32_t& slot);  // false when the order is used up
  std::vector<OrderedSlot> evictionOrder_;
  std::size_t sortedEnd_ = 0, nextInOrder_ = 0;
  std::vector<uint32_t> changed_;         // page entries changed since takeChangedEntries
  std::vector<uint8_t> changedMark_;      // per page entry: in changed_
  bool allChanged_ = true;
  int pinnedLevel_ = -1;
  void markChanged(uint32_t index);
  std::size_t neededCount_ = 0;
  std::size_t residentNeeded_ = 0;  // needed bricks that are resident (kept up to date: read every frame)
};

}  // namespace fcc::render
