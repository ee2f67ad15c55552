// Sort-last compositing (docs/MPI.md): each process rendered the whole image from its own bricks; the
// images are merged by radix-k (binary swap when every radix is 2, direct send when there is one
// round): in round r the processes of a group of k_r split the image piece they hold into k_r pieces,
// each keeps one and receives that piece from the others, and composites the k_r versions in the
// visibility order of their k-d slabs (KdPartition::frontToBack). After the last round every process
// holds 1/N of the final image (finalRange), gathered once. Plain C++: the exchange is a Transport
// (MPI in MpiTransport.h; threads in the tests).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "KdPartition.h"

namespace fcc::dist {

// A pixel as the raycaster writes it (viewer/Raycaster.h FrameImages): premultiplied RGBA, then the
// normal and depth (+inf: no surface; DVR: the depth at opacity 0.5).
constexpr int kPixelFloats = 8;

enum class CompositeMode {
  NearestDepth,  // isosurfaces: per pixel the smaller depth wins, all eight floats together (ties: the front slab)
  FrontToBack,   // DVR: premultiplied "over", front first; the depth is the front-most finite one
};

// Composites `layers` (each `pixels` pixels, front first) into `out`; `out` may be layers[0].
void compositeLayers(CompositeMode mode, const std::vector<const float*>& layers, std::size_t pixels, float* out);

struct PixelRange {
  std::size_t begin = 0, end = 0;  // pixels [begin, end)
  std::size_t size() const { return end - begin; }
};

// Piece j of k of `range` (contiguous, sizes differing by at most one).
PixelRange splitRange(const PixelRange& range, int k, int j);

// The exchange of one round: send sends[i] to peers[i], receive recvCounts[i] floats from peers[i].
class Transport {
 public:
  virtual ~Transport() = default;
  virtual std::vector<std::vector<float>> exchange(const std::vector<int>& peers, const std::vector<std::vector<float>>& sends,
                                                   const std::vector<std::size_t>& recvCounts) = 0;
};

struct CompositeStats {
  uint64_t bytesSent = 0, bytesReceived = 0;
  int rounds = 0;
};

// The pixels `rank` holds once compositing `pixels` pixels is over.
PixelRange finalRange(const KdPartition& partition, int rank, std::size_t pixels);

// Radix-k over `partition`'s rounds. `image`: this rank's whole image, kPixelFloats a pixel; returns
// its final piece (finalRange) of the composite. `eyeXyz`: the camera in lattice index space.
std::vector<float> compositeRadixK(const KdPartition& partition, int rank, const glm::dvec3& eyeXyz, CompositeMode mode,
                                   const std::vector<float>& image, Transport& transport, CompositeStats& stats);

}  // namespace fcc::dist
