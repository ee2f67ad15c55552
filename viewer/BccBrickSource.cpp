#include "BccBrickSource.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <glm/gtc/matrix_transform.hpp>

#include "io/DenseVolume.h"
#include "io/VdbLeafReader.h"
#include "sparse/BccGrids.h"
#include "sparse/Error.h"

namespace fcc::render {
namespace {

constexpr int kDim = kBccSlotDim;                      // 12 coset voxels per side
constexpr std::size_t kCosetFloats = std::size_t(kDim) * kDim * kDim;

uint64_t brickKey(const glm::ivec3& b) {
  return (uint64_t(uint32_t(b.x) & 0x1FFFFF) << 42) | (uint64_t(uint32_t(b.y) & 0x1FFFFF) << 21) | (uint32_t(b.z) & 0x1FFFFF);
}

}  // namespace

bool holdsBccGrids(const std::string& path) {
  if (io::detectFormat(path) != io::Format::Vdb) return false;
  bool primary = false, secondary = false;
  for (const io::VdbGridEntry& g : io::VdbLeafReader::listGrids(path)) {
    primary = primary || g.name == kBccPrimaryGridName;
    secondary = secondary || g.name == kBccSecondaryGridName;
  }
  return primary && secondary;
}

BccBrickSource::BccBrickSource(const std::string& path, const ReconstructionInfo& reconstruction, bool cacheRanges)
    : path_(path), reconstruction_(reconstruction) {
  if (reconstruction.lattice != Lattice::Bcc) {
    const Lattice bcc = Lattice::Bcc;
    throw ValueError("reconstruction '" + std::string(reconstruction.name) + "' is not one of a BCC dataset's (valid: " +
                     reconstructionNames(&bcc) + ")");
  }
  if (!holdsBccGrids(path))
    throw InputError(path + ": not a BCC dataset (it needs the float grids '" + kBccPrimaryGridName + "' and '" +
                         kBccSecondaryGridName + "': docs/FORMAT.md)");
  primary_ = std::make_unique<io::CartesianBrickStore>(path, kBccPrimaryGridName, cacheRanges);
  secondary_ = std::make_unique<io::CartesianBrickStore>(path, kBccSecondaryGridName, cacheRanges);
  // Coset voxel m is BCC site 2m (primary) or 2m + 1 (secondary): the secondary's map is the primary's
  // moved by half a voxel.
  worldFromIndex_ = primary_->worldFromIndex() * glm::dmat4(glm::dmat3(0.5));
  const glm::dmat4 secondaryExpected = primary_->worldFromIndex() * glm::translate(glm::dmat4(1.0), glm::dvec3(0.5));
  const glm::dmat4& secondary = secondary_->worldFromIndex();
  double scale = 0.0, error = 0.0;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) {
      scale = std::max(scale, std::abs(secondaryExpected[c][r]));
      error = std::max(error, std::abs(secondary[c][r] - secondaryExpected[c][r]));
    }
  if (!(error <= 1e-6 * std::max(scale, 1.0)))
    throw InputError(path + ": the BCC cosets do not fit together: '" + kBccSecondaryGridName +
                         "' must lie half a voxel from '" + kBccPrimaryGridName + "' along every axis");
  if (!(primary_->background() == secondary_->background()))
    throw InputError(path + ": the BCC cosets have different backgrounds (" + std::to_string(primary_->background()) +
                         " and " + std::to_string(secondary_->background()) + ")");

  // BCC brick b's coset voxels [8b - 2, 8b + 10) lie in coset brick B = b >> 1's block [16B - 2, 16B + 18):
  // the hull of both cosets' ranges there (the background where a coset lists none) bounds it.
  struct Listed {
    glm::vec2 range{std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()};
    int cosets = 0;  // how many cosets list the brick: the background joins the hull below two
  };
  std::unordered_map<uint64_t, Listed> cosetRange;
  std::vector<glm::ivec3> cosetBricks;
  const float bg = background();
  for (const io::CartesianBrickStore* store : {primary_.get(), secondary_.get()})
    for (const auto& r : store->brickRanges()) {
      auto [it, added] = cosetRange.try_emplace(brickKey(r.brick));
      if (added) cosetBricks.push_back(r.brick);
      Listed& l = it->second;
      l.range = glm::vec2(std::min(l.range.x, r.lo), std::max(l.range.y, r.hi));
      ++l.cosets;
    }
  valueMin_ = valueMax_ = bg;
  for (const glm::ivec3& B : cosetBricks) {
    const Listed& l = cosetRange[brickKey(B)];
    const glm::vec2 range = l.cosets < 2 ? glm::vec2(std::min(l.range.x, bg), std::max(l.range.y, bg)) : l.range;
    valueMin_ = std::min(valueMin_, range.x);
    valueMax_ = std::max(valueMax_, range.y);
    for (int i = 0; i < 8; ++i) ranges_.push_back({2 * B + glm::ivec3(i & 1, (i >> 1) & 1, i >> 2), range.x, range.y});
  }
}

BccBrickSource::~BccBrickSource() = default;

void BccBrickSource::brickBox(glm::ivec3& lo, glm::ivec3& hi) const {
  lo = glm::ivec3(std::numeric_limits<int>::max());
  hi = glm::ivec3(std::numeric_limits<int>::min());
  for (const auto& r : ranges_) {
    lo = glm::min(lo, r.brick);
    hi = glm::max(hi, r.brick);
  }
}

void BccBrickSource::worldBounds(glm::dvec3& lo, glm::dvec3& hi) const {
  glm::dvec3 lo2, hi2;
  primary_->worldBounds(lo, hi);
  secondary_->worldBounds(lo2, hi2);
  lo = glm::min(lo, lo2);
  hi = glm::max(hi, hi2);
}

io::Damage BccBrickSource::damage() const {
  io::Damage d = primary_->damage();
  const io::Damage s = secondary_->damage();
  d.unit = "leaf";
  d.count += s.count;
  if (d.first.empty()) d.first = s.first;
  for (const std::string& m : s.messages)
    if (d.messages.size() < io::Damage::kMaxMessages) d.messages.push_back(m);
  return d;
}

void BccBrickSource::forEachVaryingBrick(const std::function<void(const glm::ivec3&, float, float)>& visit) const {
  for (const auto& r : ranges_) visit(r.brick, r.lo, r.hi);
}

void BccBrickSource::decode(std::vector<LoadedBrick>& chunk) const {
  for (LoadedBrick& b : chunk) {
    b.halo.assign(slotBlockFloats(SlotBlock::BccPacked), 0.0f);
    const glm::ivec3 voxelMin = 8 * b.brick - kBccSlotLo;
    primary_->readBox(voxelMin, glm::ivec3(kDim), b.halo.data());
    secondary_->readBox(voxelMin, glm::ivec3(kDim), b.halo.data() + kCosetFloats);
  }
}

}  // namespace fcc::render
