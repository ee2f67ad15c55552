// How long a step() of a progressive frame may spend uploading bricks at a fixed frame budget, so that
// a frame whose pass is long does not also spend the whole upload time and go over its budget (issue
// 19's p99 frame time): what the budget leaves after the rest of the last frame — its pass, its
// requests and what the caller did around them; the camera moves a little a frame, so the next frame's
// rest costs about as much — within [least, most]. `most` is the caller's cap (the viewer's 4 ms);
// `least` keeps some bricks arriving every frame, so a view whose pass alone fills the budget still
// converges. Part of the budget (kUploadHeadroom) is left free for the pass growing from one frame to
// the next (the zoom's passes grow by about 0.5 ms a frame on the H200, docs/BENCHMARKS.md).
#pragma once

#include <algorithm>

namespace fcc::render {

constexpr double kUploadHeadroom = 0.15;        // of the frame budget
constexpr double kLeastUploadSeconds = 0.0005;  // 0.5 ms: about 100 bricks on the H200

// All in seconds. lastRest: the last frame's time besides its uploads (negative or NaN: unknown, `most`).
inline double uploadSecondsWithin(double frameBudget, double lastRest, double most) {
  if (!(lastRest >= 0.0)) return most;
  const double least = std::min(kLeastUploadSeconds, most);
  return std::clamp(frameBudget * (1.0 - kUploadHeadroom) - lastRest, least, most);
}

// The frame budget of a display refreshing refreshHz times a second (GLFW's video mode; 0 or less:
// unknown, taken as 60 Hz), within [1/500, 1/24] s: a reported rate outside that is taken at its bound.
constexpr int kDefaultRefreshHz = 60;
inline double frameBudgetForRefresh(int refreshHz) {
  if (refreshHz <= 0) refreshHz = kDefaultRefreshHz;
  return 1.0 / double(std::clamp(refreshHz, 24, 500));
}

}  // namespace fcc::render
