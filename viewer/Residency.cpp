#include "Residency.h"

#include <algorithm>
#include <numeric>

#include "sparse/Error.h"

namespace fcc::render {

Residency::Residency(const glm::ivec3& brickMin, const glm::ivec3& brickDims, uint32_t slotCount)
    : brickMin_(brickMin), brickDims_(glm::max(brickDims, glm::ivec3(1))) {
  if (slotCount == 0) throw ValueError("the GPU brick pool needs at least one slot");
  nodeDims_ = (brickDims_ + kNodeBricks - 1) / kNodeBricks;
  const std::size_t bricks = std::size_t(brickDims_.x) * brickDims_.y * brickDims_.z;
  if (bricks >= kMissing) throw ValueError("the data spans too many bricks for one page table");
  pageEntries_.assign(bricks, kSkip);
  needed_.assign(bricks, 0);
  changedMark_.assign(bricks, 0);
  nodeEntries_.assign(std::size_t(nodeDims_.x) * nodeDims_.y * nodeDims_.z, 0);
  slotBrick_.assign(slotCount, -1);
}

uint32_t Residency::brickIndex(const glm::ivec3& brick) const {
  const glm::ivec3 r = brick - brickMin_;
  return uint32_t((std::size_t(r.z) * brickDims_.y + r.y) * brickDims_.x + r.x);
}

glm::ivec3 Residency::brickAt(uint32_t index) const {
  const int x = int(index % uint32_t(brickDims_.x));
  const int y = int((index / uint32_t(brickDims_.x)) % uint32_t(brickDims_.y));
  const int z = int(index / (uint32_t(brickDims_.x) * uint32_t(brickDims_.y)));
  return brickMin_ + glm::ivec3(x, y, z);
}

void Residency::setNeeded(const std::vector<glm::ivec3>& bricks) {
  std::fill(needed_.begin(), needed_.end(), 0);
  std::fill(nodeEntries_.begin(), nodeEntries_.end(), 0);
  for (const glm::ivec3& b : bricks) {
    needed_[brickIndex(b)] = 1;
    const glm::ivec3 node = (b - brickMin_) / kNodeBricks;
    nodeEntries_[(std::size_t(node.z) * nodeDims_.y + node.y) * nodeDims_.x + node.x] = 1;
  }
  neededCount_ = bricks.size();
  allChanged_ = true;
  residentNeeded_ = 0;
  for (const auto& [index, slot] : brickSlot_) residentNeeded_ += needed_[index];
  for (std::size_t i = 0; i < pageEntries_.size(); ++i) {
    if (!needed_[i]) {
      pageEntries_[i] = kSkip;
      continue;
    }
    const auto it = brickSlot_.find(uint32_t(i));
    pageEntries_[i] = it == brickSlot_.end() ? kMissing : it->second;
  }
}

std::size_t Residency::missingCount() const { return neededCount_ - residentNeeded_; }

bool Residency::isResident(const glm::ivec3& brick) const { return brickSlot_.count(brickIndex(brick)) != 0; }

void Residency::startAssigning(const std::vector<uint32_t>& slotLastUse) {
  evictionOrder_.resize(slotBrick_.size());
  std::iota(evictionOrder_.begin(), evictionOrder_.end(), 0u);
  std::stable_sort(evictionOrder_.begin(), evictionOrder_.end(), [&](uint32_t a, uint32_t b) {
    const bool freeA = slotBrick_[a] < 0, freeB = slotBrick_[b] < 0;
    if (freeA != freeB) return freeA;
    const uint32_t useA = a < slotLastUse.size() ? slotLastUse[a] : 0;
    const uint32_t useB = b < slotLastUse.size() ? slotLastUse[b] : 0;
    return useA < useB;
  });
  nextInOrder_ = 0;
}

void Residency::markChanged(uint32_t index) {
  if (allChanged_ || changedMark_[index]) return;
  changedMark_[index] = 1;
  changed_.push_back(index);
}

std::vector<uint32_t> Residency::takeChangedEntries() {
  std::vector<uint32_t> out;
  out.swap(changed_);
  for (uint32_t index : out) changedMark_[index] = 0;
  allChanged_ = false;
  return out;
}

std::vector<std::pair<glm::ivec3, uint32_t>> Residency::assign(const std::vector<glm::ivec3>& bricks) {
  std::vector<std::pair<glm::ivec3, uint32_t>> out;
  for (const glm::ivec3& brick : bricks) {
    if (nextInOrder_ == evictionOrder_.size()) break;
    const uint32_t index = brickIndex(brick);
    if (brickSlot_.count(index)) continue;
    const uint32_t slot = evictionOrder_[nextInOrder_++];
    if (slotBrick_[slot] >= 0) {  // evict
      const uint32_t old = uint32_t(slotBrick_[slot]);
      brickSlot_.erase(old);
      residentNeeded_ -= needed_[old];
      pageEntries_[old] = needed_[old] ? kMissing : kSkip;
      markChanged(old);
    }
    slotBrick_[slot] = index;
    brickSlot_[index] = slot;
    residentNeeded_ += needed_[index];
    pageEntries_[index] = needed_[index] ? slot : kSkip;
    markChanged(index);
    out.emplace_back(brick, slot);
  }
  return out;
}

}  // namespace fcc::render
