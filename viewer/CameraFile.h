// A camera as a JSON file, the same for `fccvdb view --camera`, `fccvdb render --camera` and the
// viewer's C key (docs/VIEWER.md):
//   {"eye": [X, Y, Z], "lookat": [X, Y, Z], "up": [X, Y, Z], "fov": DEGREES}
// world space; "fov" the vertical field of view in degrees. "up" (default 0,1,0) and "fov" (default
// 40) may be left out. Numbers are written with all the digits a double needs, so a saved camera
// renders the same image bit for bit.
#pragma once

#include <string>

#include "Camera.h"

namespace fcc::render {

// The JSON text of `camera` (one object, one line, a newline at the end).
std::string cameraJson(const Camera& camera);

// Parses cameraJson's format. InputError "camera file NAME: WHAT; valid is ..." naming `name` (the
// file) for anything else: not JSON of that shape, an unknown or missing key, a number that is not
// finite, a degenerate camera (the eye on the look-at point, up along the view, fov outside (0, 180)).
Camera parseCameraJson(const std::string& text, const std::string& name);

// Reads and parses `path` (InputError naming it when it cannot be read).
Camera readCameraFile(const std::string& path);

// Writes cameraJson(camera) to `path` through a temporary file (io::AtomicOutput), replacing it.
void writeCameraFile(const std::string& path, const Camera& camera);

}  // namespace fcc::render
