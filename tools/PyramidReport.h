// The line `pyramid`, `convert --pyramid` and `synth --pyramid` print about the levels they wrote.
#pragma once

#include <cstdio>
#include <string>

#include "io/FccPyramid.h"

namespace fcc::cli {

inline void printPyramidSummary(const std::string& file, const io::PyramidSummary& s) {
  std::string levels;
  for (const io::PyramidLevel& l : s.levels) {
    char item[160];
    std::snprintf(item, sizeof item, "%s%d: spacing %g, %llu bricks", levels.empty() ? "" : "; ", l.level, l.spacing,
                  (unsigned long long)l.bricks);
    levels += item;
  }
  const double overhead = s.inputBytes ? 100.0 * (double(s.outputBytes) - double(s.inputBytes)) / double(s.inputBytes) : 0.0;
  std::fprintf(stderr, "pyramid of %s: %zu levels (%s); file %llu -> %llu bytes (%+.1f%%)\n", file.c_str(),
               s.levels.size(), levels.c_str(), (unsigned long long)s.inputBytes, (unsigned long long)s.outputBytes,
               overhead);
}

}  // namespace fcc::cli
