#include "Residency.h"

#include <algorithm>
#include <numeric>

#include "sparse/Error.h"

namespace fcc::render {

Residency::Residency(const glm::ivec3& brickMin, const glm::ivec3& brickDims, uint32_t slotCount)
    : Residency(std::vector<LevelBox>{LevelBox{brickMin, brickDims}}, slotCount) {}

Residency::Residency(const std::vector<LevelBox>& levels, uint32_t slotCount) {
  if (slotCount == 0) throw ValueError("the GPU brick pool needs at least one slot");
  if (levels.empty()) throw ValueError("a brick residency needs at least one level");
  std::size_t bricks = 0, nodes = 0;
  for (const LevelBox& box : levels) {
    Level l;
    l.box = LevelBox{box.brickMin, glm::max(box.brickDims, glm::ivec3(1))};
    l.nodeDims = (l.box.brickDims + kNodeBricks - 1) / kNodeBricks;
    l.pageOffset = uint32_t(bricks);
    l.nodeOffset = uint32_t(nodes);
    bricks += std::size_t(l.box.brickDims.x) * l.box.brickDims.y * l.box.brickDims.z;
    nodes += std::size_t(l.nodeDims.x) * l.nodeDims.y * l.nodeDims.z;
    if (bricks >= kMissing) throw ValueError("the data spans too many bricks for one page table");
    levels_.push_back(l);
  }
  pageEntries_.assign(bricks, kSkip);
  needed_.assign(bricks, 0);
  changedMark_.assign(bricks, 0);
  nodeEntries_.assign(nodes, 0);
  slotBrick_.assign(slotCount, -1);
}

uint32_t Residency::brickIndex(const glm::ivec3& brick, int level) const {
  const Level& l = levels_[std::size_t(level)];
  const glm::ivec3 r = brick - l.box.brickMin;
  return l.pageOffset + uint32_t((std::size_t(r.z) * l.box.brickDims.y + r.y) * l.box.brickDims.x + r.x);
}

int Residency::levelOf(uint32_t index) const {
  int level = 0;
  while (level + 1 < int(levels_.size()) && levels_[std::size_t(level) + 1].pageOffset <= index) ++level;
  return level;
}

glm::ivec3 Residency::brickAt(uint32_t index) const {
  const Level& l = levels_[std::size_t(levelOf(index))];
  const uint32_t local = index - l.pageOffset;
  const glm::ivec3& dims = l.box.brickDims;
  const int x = int(local % uint32_t(dims.x));
  const int y = int((local / uint32_t(dims.x)) % uint32_t(dims.y));
  const int z = int(local / (uint32_t(dims.x) * uint32_t(dims.y)));
  return l.box.brickMin + glm::ivec3(x, y, z);
}

void Residency::setNeeded(const std::vector<glm::ivec3>& bricks) {
  std::vector<std::vector<glm::ivec3>> perLevel(levels_.size());
  perLevel[0] = bricks;
  setNeeded(perLevel);
}

void Residency::setNeeded(const std::vector<std::vector<glm::ivec3>>& bricksPerLevel) {
  std::fill(needed_.begin(), needed_.end(), 0);
  std::fill(nodeEntries_.begin(), nodeEntries_.end(), 0);
  neededCount_ = 0;
  for (std::size_t k = 0; k < levels_.size(); ++k) {
    Level& l = levels_[k];
    l.needed = l.residentNeeded = 0;
    if (k >= bricksPerLevel.size()) continue;
    for (const glm::ivec3& b : bricksPerLevel[k]) {
      needed_[brickIndex(b, int(k))] = 1;
      const glm::ivec3 node = (b - l.box.brickMin) / kNodeBricks;
      nodeEntries_[l.nodeOffset + (std::size_t(node.z) * l.nodeDims.y + node.y) * l.nodeDims.x + node.x] = 1;
    }
    l.needed = bricksPerLevel[k].size();
    neededCount_ += l.needed;
  }
  allChanged_ = true;
  residentNeeded_ = 0;
  for (const auto& [index, slot] : brickSlot_)
    if (needed_[index]) {
      ++residentNeeded_;
      ++levels_[std::size_t(levelOf(index))].residentNeeded;
    }
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

std::size_t Residency::missingCount(int level) const {
  const Level& l = levels_[std::size_t(level)];
  return l.needed - l.residentNeeded;
}

bool Residency::isResident(const glm::ivec3& brick, int level) const {
  return brickSlot_.count(brickIndex(brick, level)) != 0;
}

void Residency::startAssigning(const std::vector<uint32_t>& slotLastUse) {
  // Each eligible slot's place in the order, fixed now (assigning changes which slots are free):
  // free slots first, then by the pass that last used them, then by slot (the order a stable sort
  // of the slots gave).
  evictionOrder_.clear();
  for (uint32_t s = 0; s < uint32_t(slotBrick_.size()); ++s)
    if (pinnedLevel_ < 0 || slotBrick_[s] < 0 || levelOf(uint32_t(slotBrick_[s])) < pinnedLevel_) {
      const uint64_t used = (uint64_t(slotBrick_[s] < 0 ? 0 : 1) << 32) | (s < slotLastUse.size() ? slotLastUse[s] : 0u);
      evictionOrder_.push_back(OrderedSlot{used, s});
    }
  sortedEnd_ = 0;
  nextInOrder_ = 0;
}

bool Residency::nextSlotInOrder(uint32_t& slot) {
  if (nextInOrder_ == sortedEnd_) {
    // Sorted a part at a time: a pass takes a few thousand slots of 40 k, and sorting all of them
    // took 2.8 ms a pass. Partitioning first keeps the parts in the order a sort of all would give.
    if (sortedEnd_ == evictionOrder_.size()) return false;
    const std::size_t end = std::min(evictionOrder_.size(), sortedEnd_ + std::max<std::size_t>(kFirstSortedSlots, sortedEnd_));
    const auto first = evictionOrder_.begin() + std::ptrdiff_t(sortedEnd_), last = evictionOrder_.begin() + std::ptrdiff_t(end);
    if (last != evictionOrder_.end()) std::nth_element(first, last, evictionOrder_.end());
    std::sort(first, last);
    sortedEnd_ = end;
  }
  slot = evictionOrder_[nextInOrder_++].slot;
  return true;
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
  std::vector<uint32_t> indices;
  indices.reserve(bricks.size());
  for (const glm::ivec3& brick : bricks) indices.push_back(brickIndex(brick));
  std::vector<std::pair<glm::ivec3, uint32_t>> out;
  for (const auto& [index, slot] : assignIndices(indices)) out.emplace_back(brickAt(index), slot);
  return out;
}

std::vector<std::pair<uint32_t, uint32_t>> Residency::assignIndices(const std::vector<uint32_t>& indices) {
  std::vector<std::pair<uint32_t, uint32_t>> out;
  for (const uint32_t index : indices) {
    if (brickSlot_.count(index)) continue;
    uint32_t slot = 0;
    if (!nextSlotInOrder(slot)) break;
    if (slotBrick_[slot] >= 0) {  // evict
      const uint32_t old = uint32_t(slotBrick_[slot]);
      brickSlot_.erase(old);
      if (needed_[old]) {
        --residentNeeded_;
        --levels_[std::size_t(levelOf(old))].residentNeeded;
      }
      pageEntries_[old] = needed_[old] ? kMissing : kSkip;
      markChanged(old);
    }
    slotBrick_[slot] = index;
    brickSlot_[index] = slot;
    if (needed_[index]) {
      ++residentNeeded_;
      ++levels_[std::size_t(levelOf(index))].residentNeeded;
    }
    pageEntries_[index] = needed_[index] ? slot : kSkip;
    markChanged(index);
    out.emplace_back(index, slot);
  }
  return out;
}

}  // namespace fcc::render
