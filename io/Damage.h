// Damage met while reading a file's leaves out of core, one policy for every store (io/BrickStore.h's
// FCC bricks, io/CartesianBrickStore.h's Cartesian leaves): a leaf whose bytes fail our checks is never
// trusted — it reads as the grid's background, a hole in what is drawn — and is recorded once, so that
// `render`, the viewer's panel and `info --check` can say how many and which.
#pragma once

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

namespace fcc::io {

struct Damage {
  uint64_t count = 0;          // damaged units met so far, each counted once
  std::string unit = "brick";  // what one is: "brick" (an FCC brick, one leaf of its grid) or "leaf" (8^3 voxels)
  std::string first;           // the first one's message: "FILE: leaf at (x, y, z) is damaged: WHAT"
  std::vector<std::string> messages;  // the first kMaxMessages, one a unit
  static constexpr std::size_t kMaxMessages = 20;
};

// "1 damaged brick", "3 damaged leaves": a count of Damage's unit, for the lines that report it.
inline std::string damagedCountText(const Damage& d) {
  std::string unit = d.unit;
  if (d.count != 1) unit = unit == "leaf" ? "leaves" : unit + "s";
  return std::to_string(d.count) + " damaged " + unit;
}

// The damage a store met, from any thread: each leaf (by its index in the file) recorded once.
class DamageLog {
 public:
  explicit DamageLog(std::string unit) : unit_(std::move(unit)) {}
  // Records leaf `leafIndex` with its message; false if it was recorded already.
  bool record(uint64_t leafIndex, const std::string& message) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!leaves_.insert(leafIndex).second) return false;
    if (messages_.size() < Damage::kMaxMessages) messages_.push_back(message);
    return true;
  }
  Damage damage() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return {leaves_.size(), unit_, messages_.empty() ? std::string() : messages_.front(), messages_};
  }
  bool any() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return !leaves_.empty();
  }

 private:
  const std::string unit_;
  mutable std::mutex mutex_;
  std::unordered_set<uint64_t> leaves_;
  std::vector<std::string> messages_;
};

}  // namespace fcc::io
