// A camera path: the cameras of successive frames with their times, as `fccvdb view --record-path`
// records them and `fccvdb bench stream --path PATH.json` replays them (docs/VIEWER.md):
//   {"fccvdb_camera_path": 1, "file": "blobs.vdb",
//    "frames": [{"t": 0, "eye": [X, Y, Z], "lookat": [X, Y, Z], "up": [X, Y, Z], "fov": DEGREES}, ...]}
// "t" in seconds since the first frame, not decreasing; each frame otherwise a camera file's object
// (viewer/CameraFile.h, world space, every digit a double needs). "file" names the data the path was
// recorded over (informative: a path replays over any file).
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "Camera.h"

namespace fcc::render {

struct CameraPathPoint {
  double seconds = 0.0;  // since the path's first frame
  Camera camera;
};

struct CameraPath {
  std::string file;
  std::vector<CameraPathPoint> points;
  double duration() const { return points.empty() ? 0.0 : points.back().seconds - points.front().seconds; }
};

// The JSON text of `path` (one frame a line).
std::string cameraPathJson(const CameraPath& path);
// Parses cameraPathJson's format. InputError "camera path NAME: WHAT; valid is ..." for anything else:
// not JSON, no frames, a frame without eye or lookat, a time that is not finite or goes back, a
// degenerate camera.
CameraPath parseCameraPathJson(const std::string& text, const std::string& name);
// Reads and parses `path` (InputError naming it when it cannot be read).
CameraPath readCameraPathFile(const std::string& path);
// Writes cameraPathJson through a temporary file renamed into place (io::AtomicOutput's policy: an
// existing file only with `overwrite`).
void writeCameraPathFile(const std::string& file, const CameraPath& path, bool overwrite);

// The camera at `seconds` after the first frame: linear between the two frames around it (eye,
// look-at point, up, field of view), the first or last frame outside the path. A path must not be empty.
Camera cameraAt(const CameraPath& path, double seconds);

// Records one camera a frame, timed from the first (the viewer's frame loop calls record()).
class CameraPathRecorder {
 public:
  explicit CameraPathRecorder(std::string file) { path_.file = std::move(file); }
  void record(const Camera& camera);
  void record(const Camera& camera, double seconds);  // at a given time (tests)
  const CameraPath& path() const { return path_; }

 private:
  CameraPath path_;
  std::optional<std::chrono::steady_clock::time_point> start_;
};

}  // namespace fcc::render
