// Which bricks the GPU pool holds, in which slots, and the page table the raycaster reads: for every
// brick of a dense box, kSkip (its bounds exclude the isovalue, or it is constant), kMissing (needed,
// not resident) or its pool slot; and per node of 16^3 bricks whether any brick in it is needed.
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

  // The box of bricks [brickMin, brickMin + brickDims) and the number of pool slots.
  Residency(const glm::ivec3& brickMin, const glm::ivec3& brickDims, uint32_t slotCount);

  const glm::ivec3& brickMin() const { return brickMin_; }
  const glm::ivec3& brickDims() const { return brickDims_; }
  const glm::ivec3& nodeDims() const { return nodeDims_; }
  uint32_t slotCount() const { return uint32_t(slotBrick_.size()); }
  uint32_t brickIndex(const glm::ivec3& brick) const;  // into pageEntries()
  glm::ivec3 brickAt(uint32_t index) const;

  // The bricks that need evaluation for the current isovalue (all inside the box). Resident bricks
  // stay resident whether needed or not (an isovalue change back costs nothing).
  void setNeeded(const std::vector<glm::ivec3>& bricks);
  std::size_t neededCount() const { return neededCount_; }

  // Orders the slots for eviction once per pass: free slots first, then the least recently used
  // (slotLastUse, the pass that last read each slot). Sorting the whole pool for every upload batch
  // took milliseconds a batch with 40 k slots.
  void startAssigning(const std::vector<uint32_t>& slotLastUse);
  // Assigns pool slots to `bricks` (not yet resident), in order, taking slots in the order
  // startAssigning made and never one assigned since then. Returns (brick, slot) pairs (fewer when
  // the order runs out); the page table already points to them.
  std::vector<std::pair<glm::ivec3, uint32_t>> assign(const std::vector<glm::ivec3>& bricks);
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

  bool isResident(const glm::ivec3& brick) const;
  uint32_t residentCount() const { return uint32_t(brickSlot_.size()); }
  // Needed bricks not resident (what the current isovalue may still have to stream).
  std::size_t missingCount() const;

  const std::vector<uint32_t>& pageEntries() const { return pageEntries_; }
  const std::vector<uint32_t>& nodeEntries() const { return nodeEntries_; }

 private:
  glm::ivec3 brickMin_, brickDims_, nodeDims_;
  std::vector<uint32_t> pageEntries_;
  std::vector<uint32_t> nodeEntries_;
  std::vector<uint8_t> needed_;            // per brick index
  std::vector<int64_t> slotBrick_;         // per slot: brick index, or -1 when free
  std::unordered_map<uint32_t, uint32_t> brickSlot_;
  std::vector<uint32_t> evictionOrder_;  // startAssigning's order of the slots
  std::size_t nextInOrder_ = 0;
  std::vector<uint32_t> changed_;         // page entries changed since takeChangedEntries
  std::vector<uint8_t> changedMark_;      // per page entry: in changed_
  bool allChanged_ = true;
  void markChanged(uint32_t index);
  std::size_t neededCount_ = 0;
  std::size_t residentNeeded_ = 0;  // needed bricks that are resident (kept up to date: read every frame)
};

}  // namespace fcc::render
