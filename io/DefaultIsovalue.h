// The isovalue `render`, `view` and `bench render` use without --iso, and `info` suggests: one rule,
// from the file's topology and metadata alone (no brick is read).
#pragma once

#include <string>

#include "BrickStore.h"

namespace fcc::io {

struct IsoChoice {
  float value = 0.0f;
  std::string basis;  // why this value, for messages: "level set: its zero crossing", ...
};

// A level set: 0. A file that records its samples' histogram (convert, synth): Otsu's threshold on it,
// the background left out (sparse/SampleHistogram.h says why). Otherwise, and when the histogram has
// fewer than two occupied bins besides the background: the middle of the range the surface can take
// (BrickStore::valueMin/valueMax, the hull of the bounds).
IsoChoice defaultIsovalue(const BrickStore& store);

}  // namespace fcc::io
