#include "Compositor.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

namespace fcc::dist {

void compositeLayers(CompositeMode mode, const std::vector<const float*>& layers, std::size_t pixels, float* out) {
  if (layers.empty()) throw std::invalid_argument("compositing no layers");
  for (std::size_t p = 0; p < pixels; ++p) {
    const std::size_t at = p * kPixelFloats;
    float px[kPixelFloats];
    std::memcpy(px, layers[0] + at, sizeof px);
    for (std::size_t l = 1; l < layers.size(); ++l) {
      const float* back = layers[l] + at;
      if (mode == CompositeMode::NearestDepth) {
        // Strictly nearer only: at equal depths the front slab's hit is the one a single ray meets first.
        if (back[7] < px[7]) std::memcpy(px, back, sizeof px);
      } else {
        const float transmittance = 1.0f - px[3];
        for (int c = 0; c < 4; ++c) px[c] += transmittance * back[c];
        if (!std::isfinite(px[7])) px[7] = back[7];
      }
    }
    std::memcpy(out + at, px, sizeof px);
  }
}

PixelRange splitRange(const PixelRange& range, int k, int j) {
  const std::size_t n = range.size(), base = n / std::size_t(k), extra = n % std::size_t(k);
  const std::size_t begin = range.begin + std::size_t(j) * base + std::min<std::size_t>(std::size_t(j), extra);
  return {begin, begin + base + (std::size_t(j) < extra ? 1 : 0)};
}

PixelRange finalRange(const KdPartition& partition, int rank, std::size_t pixels) {
  PixelRange range{0, pixels};
  for (int r = 0; r < int(partition.radices().size()); ++r)
    range = splitRange(range, partition.radices()[std::size_t(r)], partition.digit(rank, r));
  return range;
}

std::vector<float> compositeRadixK(const KdPartition& partition, int rank, const glm::dvec3& eyeXyz, CompositeMode mode,
                                   const std::vector<float>& image, Transport& transport, CompositeStats& stats) {
  const std::size_t pixels = image.size() / kPixelFloats;
  PixelRange range{0, pixels};
  std::vector<float> held = image;  // the pixels of `range`
  for (int r = 0; r < int(partition.radices().size()); ++r) {
    const int k = partition.radices()[std::size_t(r)], mine = partition.digit(rank, r), stride = partition.stride(r);
    std::vector<int> peers;
    std::vector<std::vector<float>> sends;
    std::vector<std::size_t> recvCounts;
    const PixelRange kept = splitRange(range, k, mine);
    for (int j = 0; j < k; ++j) {
      if (j == mine) continue;
      const PixelRange piece = splitRange(range, k, j);
      peers.push_back(rank + (j - mine) * stride);
      const float* from = held.data() + (piece.begin - range.begin) * kPixelFloats;
      sends.emplace_back(from, from + piece.size() * kPixelFloats);
      recvCounts.push_back(kept.size() * kPixelFloats);
      stats.bytesSent += piece.size() * kPixelFloats * sizeof(float);
      stats.bytesReceived += kept.size() * kPixelFloats * sizeof(float);
    }
    std::vector<std::vector<float>> received = transport.exchange(peers, sends, recvCounts);
    // The k versions of the kept piece, by digit, then in the slabs' front-to-back order.
    std::vector<const float*> byDigit(static_cast<std::size_t>(k));
    for (int j = 0, i = 0; j < k; ++j) {
      if (j == mine) {
        byDigit[std::size_t(j)] = held.data() + (kept.begin - range.begin) * kPixelFloats;
      } else {
        if (received[std::size_t(i)].size() != kept.size() * kPixelFloats)
          throw std::runtime_error("compositing: rank " + std::to_string(peers[std::size_t(i)]) + " sent " +
                                   std::to_string(received[std::size_t(i)].size()) + " floats, expected " +
                                   std::to_string(kept.size() * kPixelFloats));
        byDigit[std::size_t(j)] = received[std::size_t(i++)].data();
      }
    }
    std::vector<const float*> layers;
    for (int j : partition.frontToBack(r, rank, eyeXyz)) layers.push_back(byDigit[std::size_t(j)]);
    std::vector<float> next(kept.size() * kPixelFloats);
    compositeLayers(mode, layers, kept.size(), next.data());
    held = std::move(next);
    range = kept;
    ++stats.rounds;
  }
  return held;
}

}  // namespace fcc::dist
