#include "CameraFile.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "io/AtomicOutput.h"
#include "sparse/Error.h"

namespace fcc::render {
namespace {

constexpr const char* kValid =
    "valid is {\"eye\": [X, Y, Z], \"lookat\": [X, Y, Z], \"up\": [X, Y, Z], \"fov\": DEGREES} (up and fov optional)";

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

std::string triple(const glm::dvec3& v) { return "[" + number(v.x) + ", " + number(v.y) + ", " + number(v.z) + "]"; }

// A reader of the one JSON shape above: an object whose values are numbers or arrays of numbers.
class Reader {
 public:
  Reader(const std::string& text, const std::string& name) : text_(text), name_(name) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError("camera file " + name_ + ": " + what + "; " + kValid);
  }
  void skipSpace() {
    while (at_ < text_.size() && std::isspace((unsigned char)text_[at_])) ++at_;
  }
  bool take(char c) {
    skipSpace();
    if (at_ < text_.size() && text_[at_] == c) {
      ++at_;
      return true;
    }
    return false;
  }
  void expect(char c, const char* where) {
    if (!take(c)) fail(std::string("expected '") + c + "' " + where + " at byte " + std::to_string(at_));
  }
  bool atEnd() {
    skipSpace();
    return at_ == text_.size();
  }
  std::string key() {
    expect('"', "to start a key");
    const std::size_t end = text_.find('"', at_);
    if (end == std::string::npos) fail("a key's string does not end");
    std::string k = text_.substr(at_, end - at_);
    at_ = end + 1;
    return k;
  }
  double value(const std::string& key) {
    skipSpace();
    const char* begin = text_.c_str() + at_;
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end == begin) fail("\"" + key + "\" expects numbers");
    if (!std::isfinite(v)) fail("\"" + key + "\" holds a number that is not finite");
    at_ += std::size_t(end - begin);
    return v;
  }
  std::vector<double> values(const std::string& key) {
    std::vector<double> out;
    if (!take('[')) {
      out.push_back(value(key));
      return out;
    }
    if (take(']')) return out;
    do out.push_back(value(key));
    while (take(','));
    expect(']', ("to end \"" + key + "\"").c_str());
    return out;
  }

 private:
  const std::string& text_;
  const std::string& name_;
  std::size_t at_ = 0;
};

}  // namespace

std::string cameraJson(const Camera& camera) {
  return "{\"eye\": " + triple(camera.eye) + ", \"lookat\": " + triple(camera.lookat) + ", \"up\": " +
         triple(camera.up) + ", \"fov\": " + number(camera.fovYDegrees) + "}\n";
}

Camera parseCameraJson(const std::string& text, const std::string& name) {
  Reader r(text, name);
  Camera camera;
  bool haveEye = false, haveLookat = false, haveUp = false;
  r.expect('{', "to start the object");
  if (!r.take('}')) {
    do {
      const std::string key = r.key();
      r.expect(':', ("after \"" + key + "\"").c_str());
      const std::vector<double> v = r.values(key);
      const bool isTriple = key == "eye" || key == "lookat" || key == "up";
      if (isTriple && v.size() != 3) r.fail("\"" + key + "\" needs three numbers, not " + std::to_string(v.size()));
      if (key == "fov" && v.size() != 1) r.fail("\"fov\" is one number of degrees");
      if (key == "eye") camera.eye = {v[0], v[1], v[2]}, haveEye = true;
      else if (key == "lookat") camera.lookat = {v[0], v[1], v[2]}, haveLookat = true;
      else if (key == "up") camera.up = {v[0], v[1], v[2]}, haveUp = true;
      else if (key == "fov") camera.fovYDegrees = v[0];
      else r.fail("unknown key \"" + key + "\"");
    } while (r.take(','));
    r.expect('}', "to end the object");
  }
  if (!r.atEnd()) r.fail("text after the object");
  if (!haveEye) r.fail("no \"eye\"");
  if (!haveLookat) r.fail("no \"lookat\"");
  // Without "up", a view straight along the default up takes the one across it (render's rule).
  if (!haveUp && viewRunsAlongUp(camera)) camera.up = upAcross(camera.lookat - camera.eye);
  try {
    cameraFrame(camera, 1.0);  // validates the camera
  } catch (const ValueError& e) {
    r.fail(e.what());
  }
  return camera;
}

Camera readCameraFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::error_code error;
    const bool exists = std::filesystem::exists(path, error);
    throw InputError("camera file " + path + (exists ? ": cannot be read" : ": no such file"));
  }
  std::stringstream text;
  text << in.rdbuf();
  return parseCameraJson(text.str(), path);
}

void writeCameraFile(const std::string& path, const Camera& camera) {
  io::writeTextFile(path, cameraJson(camera), /*overwrite=*/true);
}

}  // namespace fcc::render
