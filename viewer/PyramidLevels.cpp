#include "PyramidLevels.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "Raycaster.h"
#include "io/VdbLeafReader.h"
#include "sparse/Error.h"
#include "sparse/FccGrid.h"

namespace fcc::render {

PyramidLevels::PyramidLevels(const io::BrickStore& level0, std::size_t hostCacheBytes) : builtFor_(hostCacheBytes) {
  std::vector<std::string> names;
  for (const io::VdbGridEntry& g : io::VdbLeafReader::listGrids(level0.path())) names.push_back(g.name);
  const std::string base = level0.index().getName();
  for (int k = 1; k < kMaxLodLevels; ++k) {
    const std::string name = lodGridName(base, k);
    if (std::find(names.begin(), names.end(), name) == names.end()) break;
    auto store = std::make_unique<io::BrickStore>(level0.path(), name);
    // Level k's index point J lies at level 0's 2^k J: the raycaster marches level k with level 0's
    // ray scaled by 2^-k, so any other transform would draw it in the wrong place.
    const glm::dmat4 expected = level0.worldFromIndex() * glm::dmat4(glm::dmat3(std::ldexp(1.0, k)));
    double worst = 0.0, scale = 0.0;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 3; ++r) {
        worst = std::max(worst, std::abs(store->worldFromIndex()[c][r] - expected[c][r]));
        scale = std::max(scale, std::abs(expected[c][r]));
      }
    if (worst > 1e-9 * std::max(scale, 1.0))
      throw InputError(level0.path() + ": pyramid level " + name + "'s transform is not level 0's scaled by " +
                       std::to_string(1 << k) + " (rebuild it with `fccvdb pyramid`)");
    const std::size_t budget = hostCacheBytes >> (3 * k);
    hostCacheBytes_ += budget;
    sources_.push_back(std::make_unique<FccBrickSource>(*store, budget));
    stores_.push_back(std::move(store));
  }
}

PyramidLevels::~PyramidLevels() = default;

std::vector<const BrickSource*> PyramidLevels::sources() const {
  std::vector<const BrickSource*> out;
  for (const auto& s : sources_) out.push_back(s.get());
  return out;
}

}  // namespace fcc::render
