// Synthetic test and benchmark fields, sampled on the FCC lattice of a Cartesian embedding of `dims`
// points, generated on demand per site (the builder streams them block by block).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "SampleField.h"

namespace fcc {

struct SynthSpec {
  std::string kind;       // "sphere", "marschner-lobb", "blobs"
  glm::ivec3 dims{64};    // Cartesian embedding points per axis
  uint64_t seed = 1;
};

struct SynthField {
  std::unique_ptr<SampleField> field;
  glm::dvec3 worldFromIndexScale{1.0};   // world = origin + scale * ijk
  glm::dvec3 worldFromIndexOrigin{0.0};
  bool levelSet = false;
  float suggestedIso = 0.5f;
};

// The valid kinds, for messages and --help.
const std::vector<std::string>& synthKinds();

// ValueError for an unknown kind (listing the valid ones) or dims below 2.
SynthField makeSynthField(const SynthSpec& spec);

}  // namespace fcc
