// The camera paths `fccvdb bench stream` replays, one camera a frame (docs/BENCHMARKS.md, "bench
// stream"): an orbit, a zoom from the whole dataset to one brick, seeded random jumps, and a path
// recorded in the viewer (`view --record-path`, viewer/CameraPath.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "viewer/BrickSource.h"
#include "viewer/Camera.h"
#include "viewer/CameraPath.h"

namespace fcc::cli {

// A full turn about the look-at point (the viewer's turntable orbit) in `frames` frames.
std::vector<render::Camera> orbitPath(const render::Camera& start, int frames);

// From `start` (which frames the whole dataset) in a straight line to a view one brick high around
// `target` (world space; the view's height at the look-at point is one brick's world size at the
// end): the eye and the look-at point move on straight lines, the distance shrinking geometrically,
// so the scale changes by the same factor every frame.
std::vector<render::Camera> zoomPath(const render::Camera& start, const glm::dvec3& target, double brickWorldSize,
                                     int frames);
// The brick the zoom ends at: the centre (world space) of the brick nearest `near` among those whose
// value range holds `iso` (any varying brick when none does, or `near` itself without any), and one
// brick's world size (16 index units through worldFromIndex's scale).
glm::dvec3 zoomTarget(const render::BrickSource& source, const glm::dvec3& near, float iso, double& brickWorldSize);

// A new random camera every `holdFrames` frames (held meanwhile, so that each jump's convergence is
// seen), `frames` in all: the look-at point uniform in the middle half of the world box [lo, hi], the
// eye in a uniform direction at 0.25 to 1 times the start's distance, the start's up and field of
// view. The same seed gives the same path.
std::vector<render::Camera> jumpsPath(const render::Camera& start, const glm::dvec3& lo, const glm::dvec3& hi,
                                      int frames, int holdFrames, uint64_t seed);

// A recorded path replayed at `frameSeconds` a frame: the camera at times 0, frameSeconds, ... after
// its first frame (viewer/CameraPath.h's cameraAt), `frames` of them; frames <= 0 replays it in real
// time (its duration / frameSeconds + 1 frames). With `frames` given the frames span the recording
// evenly instead. A recording of no duration replays its cameras in order.
std::vector<render::Camera> recordedPath(const render::CameraPath& path, double frameSeconds, int frames);

}  // namespace fcc::cli
