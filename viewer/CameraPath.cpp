#include "CameraPath.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "io/AtomicOutput.h"
#include "sparse/Error.h"

namespace fcc::render {
namespace {

constexpr const char* kValid =
    "valid is {\"fccvdb_camera_path\": 1, \"frames\": [{\"t\": SECONDS, \"eye\": [X, Y, Z], \"lookat\": [X, Y, Z], "
    "\"up\": [X, Y, Z], \"fov\": DEGREES}, ...]} (up and fov optional; view --record-path writes it)";

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

std::string triple(const glm::dvec3& v) { return "[" + number(v.x) + ", " + number(v.y) + ", " + number(v.z) + "]"; }

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw InputError("camera path " + name + ": " + what + "; " + kValid);
}

double finiteNumber(const nlohmann::json& value, const std::string& name, const std::string& where) {
  if (!value.is_number()) fail(name, where + " is not a number");
  const double v = value.get<double>();
  if (!std::isfinite(v)) fail(name, where + " is not finite");
  return v;
}

glm::dvec3 tripleOf(const nlohmann::json& value, const std::string& name, const std::string& where) {
  if (!value.is_array() || value.size() != 3) fail(name, where + " needs three numbers");
  return {finiteNumber(value[0], name, where), finiteNumber(value[1], name, where), finiteNumber(value[2], name, where)};
}

}  // namespace

std::string cameraPathJson(const CameraPath& path) {
  std::string out = "{\"fccvdb_camera_path\": 1, \"file\": " + nlohmann::json(path.file).dump() + ", \"frames\": [";
  for (std::size_t i = 0; i < path.points.size(); ++i) {
    const CameraPathPoint& p = path.points[i];
    out += std::string(i ? ",\n  " : "\n  ") + "{\"t\": " + number(p.seconds) + ", \"eye\": " + triple(p.camera.eye) +
           ", \"lookat\": " + triple(p.camera.lookat) + ", \"up\": " + triple(p.camera.up) +
           ", \"fov\": " + number(p.camera.fovYDegrees) + "}";
  }
  return out + "\n]}\n";
}

CameraPath parseCameraPathJson(const std::string& text, const std::string& name) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // a parse error, or a number beyond a double
    fail(name, std::string("not JSON (") + e.what() + ")");
  }
  if (!doc.is_object()) fail(name, "not a JSON object");
  if (!doc.contains("fccvdb_camera_path")) fail(name, "no \"fccvdb_camera_path\" version");
  if (doc["fccvdb_camera_path"] != 1) fail(name, "version " + doc["fccvdb_camera_path"].dump() + " is unknown");
  CameraPath path;
  if (doc.contains("file")) {
    if (!doc["file"].is_string()) fail(name, "\"file\" is not a string");
    path.file = doc["file"].get<std::string>();
  }
  if (!doc.contains("frames") || !doc["frames"].is_array()) fail(name, "no \"frames\" list");
  const nlohmann::json& frames = doc["frames"];
  if (frames.empty()) fail(name, "\"frames\" is empty");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const nlohmann::json& f = frames[i];
    const std::string where = "frame " + std::to_string(i);
    if (!f.is_object()) fail(name, where + " is not an object");
    CameraPathPoint p;
    for (const auto& [key, value] : f.items()) {
      if (key == "t") p.seconds = finiteNumber(value, name, where + "'s \"t\"");
      else if (key == "eye") p.camera.eye = tripleOf(value, name, where + "'s \"eye\"");
      else if (key == "lookat") p.camera.lookat = tripleOf(value, name, where + "'s \"lookat\"");
      else if (key == "up") p.camera.up = tripleOf(value, name, where + "'s \"up\"");
      else if (key == "fov") p.camera.fovYDegrees = finiteNumber(value, name, where + "'s \"fov\"");
      else fail(name, where + " has an unknown key \"" + key + "\"");
    }
    if (!f.contains("t")) fail(name, where + " has no \"t\"");
    if (!f.contains("eye") || !f.contains("lookat")) fail(name, where + " needs \"eye\" and \"lookat\"");
    if (!path.points.empty() && p.seconds < path.points.back().seconds) fail(name, where + "'s \"t\" goes back in time");
    try {
      cameraFrame(p.camera, 1.0);  // validates the camera
    } catch (const ValueError& e) {
      fail(name, where + ": " + e.what());
    }
    path.points.push_back(p);
  }
  return path;
}

CameraPath readCameraPathFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("camera path " + path + ": cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  return parseCameraPathJson(text.str(), path);
}

void writeCameraPathFile(const std::string& file, const CameraPath& path, bool overwrite) {
  io::writeTextFile(file, cameraPathJson(path), overwrite);
}

Camera cameraAt(const CameraPath& path, double seconds) {
  if (path.points.empty()) throw ValueError("camera path: no frames");
  const std::vector<CameraPathPoint>& p = path.points;
  if (seconds <= p.front().seconds) return p.front().camera;
  if (seconds >= p.back().seconds) return p.back().camera;
  std::size_t i = 1;
  while (p[i].seconds < seconds) ++i;  // p[i - 1].seconds < seconds <= p[i].seconds
  const double span = p[i].seconds - p[i - 1].seconds;
  const double f = span > 0.0 ? (seconds - p[i - 1].seconds) / span : 1.0;
  const Camera& a = p[i - 1].camera;
  const Camera& b = p[i].camera;
  Camera c;
  c.eye = glm::mix(a.eye, b.eye, f);
  c.lookat = glm::mix(a.lookat, b.lookat, f);
  c.up = glm::mix(a.up, b.up, f);
  c.fovYDegrees = a.fovYDegrees + f * (b.fovYDegrees - a.fovYDegrees);
  // Two valid cameras can blend into a degenerate one (opposite up vectors, the eye through the
  // look-at point): then the nearer frame's camera.
  try {
    cameraFrame(c, 1.0);
  } catch (const ValueError&) {
    return f < 0.5 ? a : b;
  }
  return c;
}

void CameraPathRecorder::record(const Camera& camera) {
  const auto now = std::chrono::steady_clock::now();
  if (!start_) start_ = now;
  record(camera, std::chrono::duration<double>(now - *start_).count());
}

void CameraPathRecorder::record(const Camera& camera, double seconds) { path_.points.push_back({seconds, camera}); }

}  // namespace fcc::render
