// `render --json`: one JSON object on stdout describing the frame and, per process (MPI rank; one
// without MPI), where its time went. The same fields for one process and for N (docs/MPI.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "JsonText.h"

namespace fcc::cli {

struct RankReport {
  int rank = 0;
  double renderSeconds = 0.0;     // its frame (raycasting passes, uploads) and reading the image back
  double waitSeconds = 0.0;       // waiting for the slowest rank before compositing
  double compositeSeconds = 0.0;  // radix-k exchange and compositing, then the gather of the pieces
  uint64_t bytesSent = 0, bytesReceived = 0;  // image pieces exchanged while compositing and gathered
  uint64_t bricksRead = 0;        // bricks decoded from the file (through its host cache)
  uint64_t bricksOwned = 0;       // bricks of its partition whose bounds hold the isovalue / an opacity
  uint64_t bricksUploaded = 0;    // bricks uploaded to its GPU pool
  int passes = 0;
  std::string device;             // GL_RENDERER (EGL platform)
};

// The pyramid levels one process drew (docs/RENDERER.md, "Level of detail"): bricks per level, level 0
// first, and the share of hit pixels drawn from level 0. Empty: not reported (distributed frames).
struct LevelReport {
  std::vector<uint64_t> bricksPerLevel;
  double fullResolutionFraction = 1.0;
  double lodBias = 0.0;
};

// What the frame showed, beside its mode: the isovalues of its surfaces (the first is --iso's or the
// default's) or the transfer function --tf named. Empty fields are left out.
struct FrameLook {
  std::vector<float> isovalues;
  std::string transferFunction;
};

inline std::string frameLookJson(const FrameLook& look) {
  std::string s;
  if (!look.isovalues.empty()) {
    s += ", \"isovalues\": [";
    for (std::size_t i = 0; i < look.isovalues.size(); ++i) s += (i ? ", " : "") + jsonNumber(look.isovalues[i]);
    s += "]";
  }
  if (!look.transferFunction.empty()) s += ", \"tf\": " + jsonString(look.transferFunction);
  return s;
}

inline std::string renderJson(const std::string& file, const std::string& output, const std::string& mode, int width,
                              int height, const std::vector<int>& radices, double frameSeconds,
                              const std::vector<RankReport>& ranks, const LevelReport& levels = {},
                              const FrameLook& look = {}) {
  std::string radixList;
  for (std::size_t i = 0; i < radices.size(); ++i) radixList += (i ? ", " : "") + std::to_string(radices[i]);
  std::string s = "{\"file\": " + jsonString(file) + ", \"output\": " + jsonString(output) + ", \"mode\": " + jsonString(mode) +
                  frameLookJson(look) + ", \"res\": [" + std::to_string(width) + ", " + std::to_string(height) + "], \"ranks\": " +
                  std::to_string(ranks.size()) + ", \"radices\": [" + radixList + "], \"frame_seconds\": " +
                  jsonNumber(frameSeconds);
  if (!levels.bricksPerLevel.empty()) {
    std::string mix;
    for (std::size_t k = 0; k < levels.bricksPerLevel.size(); ++k) mix += (k ? ", " : "") + std::to_string(levels.bricksPerLevel[k]);
    s += ", \"level_mix\": [" + mix + "], \"full_resolution_fraction\": " + jsonNumber(levels.fullResolutionFraction) +
         ", \"lod_bias\": " + jsonNumber(levels.lodBias);
  }
  s += ", \"per_rank\": [";
  for (std::size_t i = 0; i < ranks.size(); ++i) {
    const RankReport& r = ranks[i];
    s += std::string(i ? "," : "") + "\n {\"rank\": " + std::to_string(r.rank) + ", \"render_seconds\": " + jsonNumber(r.renderSeconds) +
         ", \"wait_seconds\": " + jsonNumber(r.waitSeconds) + ", \"composite_seconds\": " + jsonNumber(r.compositeSeconds) +
         ", \"bytes_sent\": " + std::to_string(r.bytesSent) + ", \"bytes_received\": " + std::to_string(r.bytesReceived) +
         ", \"bricks_read\": " + std::to_string(r.bricksRead) + ", \"bricks_owned\": " + std::to_string(r.bricksOwned) +
         ", \"bricks_uploaded\": " + std::to_string(r.bricksUploaded) + ", \"passes\": " + std::to_string(r.passes) +
         ", \"device\": " + jsonString(r.device) + "}";
  }
  return s + "\n]}\n";
}

}  // namespace fcc::cli
