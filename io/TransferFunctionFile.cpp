#include "TransferFunctionFile.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <sys/stat.h>

#include "AtomicOutput.h"
#include "sparse/Error.h"

namespace fcc::io {
namespace {

using Json = nlohmann::json;

// A transfer function file is a few kilobytes; a file far beyond that is a wrong argument.
constexpr long long kMaxFileBytes = 64ll << 20;

const char* const kJsonValid =
    "valid: ParaView's colour-map JSON, a list of objects with \"Name\", \"RGBPoints\": [x, r, g, b, ...] and "
    "optionally \"Points\": [x, alpha, midpoint, sharpness, ...] (midpoint and sharpness in [0, 1])";
const char* const kTextValid =
    "valid: one control point a line, 'value r g b alpha' (colour and opacity in [0, 1], values non-decreasing), "
    "'#' comments";

// ParaView's colour spaces; every one is interpolated in RGB here (docs/DVR.md).
const char* const kColorSpaces[] = {"RGB", "HSV", "Lab", "Diverging", "Lab/CIEDE2000", "Step"};

[[noreturn]] void fail(const std::string& path, const std::string& what, const char* valid) {
  throw InputError("transfer function file " + path + ": " + what + "; " + valid);
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

bool endsWithJson(const std::string& path) {
  if (path.size() < 5) return false;
  std::string ext = path.substr(path.size() - 5);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".json";
}

std::string readWhole(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw InputError("transfer function file " + path + ": cannot be read (no such file)");
  if (S_ISDIR(st.st_mode)) throw InputError("transfer function file " + path + ": is a directory, not a file");
  if (st.st_size > kMaxFileBytes)
    throw InputError("transfer function file " + path + ": too large for a transfer function (" +
                     std::to_string(st.st_size) + " bytes; at most " + std::to_string(kMaxFileBytes) + ")");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("transfer function file " + path + ": cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError("transfer function file " + path + ": cannot be read");
  return text.str();
}

bool blank(const std::string& text) {
  return std::all_of(text.begin(), text.end(), [](unsigned char c) { return std::isspace(c); });
}

// The numbers of a flat array `key` of map `map`, a multiple of `group` (at least one group).
std::vector<double> numbers(const Json& object, const char* key, size_t group, const std::string& map,
                            const std::string& path) {
  const Json& array = object.at(key);
  if (!array.is_array())
    fail(path, "colour map " + map + ": \"" + key + "\" is not a list of numbers", kJsonValid);
  std::vector<double> out;
  out.reserve(array.size());
  for (size_t i = 0; i < array.size(); ++i) {
    if (!array[i].is_number())
      fail(path, "colour map " + map + ": \"" + key + "\" entry " + std::to_string(i + 1) + " is not a number",
           kJsonValid);
    const double v = array[i].get<double>();
    if (!std::isfinite(v))
      fail(path, "colour map " + map + ": \"" + key + "\" entry " + std::to_string(i + 1) + " is not finite", kJsonValid);
    out.push_back(v);
  }
  if (out.empty() || out.size() % group != 0)
    fail(path,
         "colour map " + map + ": \"" + key + "\" holds " + std::to_string(out.size()) + " numbers, not a positive multiple of " +
             std::to_string(group) + (group == 4 && std::string(key) == "RGBPoints" ? " (x, r, g, b per point)"
                                                                                   : " (x, alpha, midpoint, sharpness per point)"),
         kJsonValid);
  return out;
}

TransferFunction colorMapFromJson(const Json& object, size_t index, const std::string& path) {
  std::string name;
  if (object.contains("Name")) {
    if (!object["Name"].is_string()) fail(path, "colour map " + std::to_string(index + 1) + ": \"Name\" is not a string", kJsonValid);
    name = object["Name"].get<std::string>();
  }
  const std::string map = name.empty() ? std::to_string(index + 1) : "'" + name + "'";
  if (object.contains("ColorSpace")) {
    const Json& space = object["ColorSpace"];
    const bool known = space.is_string() && std::any_of(std::begin(kColorSpaces), std::end(kColorSpaces),
                                                       [&](const char* s) { return space.get<std::string>() == s; });
    if (!known) {
      std::string valid;
      for (const char* s : kColorSpaces) valid += (valid.empty() ? "" : ", ") + std::string(s);
      fail(path, "colour map " + map + ": unknown \"ColorSpace\" " + space.dump() + " (ParaView's are " + valid + ")",
           kJsonValid);
    }
  }
  if (!object.contains("RGBPoints"))
    fail(path, "colour map " + map + " has no \"RGBPoints\"", kJsonValid);
  const std::vector<double> rgb = numbers(object, "RGBPoints", 4, map, path);
  std::vector<ColorPoint> colors;
  for (size_t i = 0; i < rgb.size(); i += 4) colors.push_back({rgb[i], glm::dvec3(rgb[i + 1], rgb[i + 2], rgb[i + 3])});

  std::vector<OpacityPoint> opacities;
  if (object.contains("Points")) {
    const std::vector<double> points = numbers(object, "Points", 4, map, path);
    for (size_t i = 0; i < points.size(); i += 4) opacities.push_back({points[i], points[i + 1], points[i + 2], points[i + 3]});
  } else {
    // ParaView's default opacity: a ramp from 0 to 1 over the colour map's range.
    double lo = colors.front().x, hi = colors.front().x;
    for (const ColorPoint& p : colors) lo = std::min(lo, p.x), hi = std::max(hi, p.x);
    opacities = {{lo, 0.0}, {hi, 1.0}};
  }
  try {
    return TransferFunction(std::move(colors), std::move(opacities), name.empty() ? path : name);
  } catch (const ValueError& e) {
    fail(path, "colour map " + map + ": " + e.what(), kJsonValid);
  }
}

}  // namespace

TransferFunction parseParaViewColorMaps(const std::string& text, const std::string& path, const std::string& colorMapName) {
  if (blank(text)) fail(path, "is empty", kJsonValid);
  Json doc;
  try {
    doc = Json::parse(text);
  } catch (const Json::exception& e) {  // a parse error, or a number beyond a double (out_of_range)
    std::string what = e.what();
    const size_t bracket = what.find("] ");
    if (what.rfind("[json.exception", 0) == 0 && bracket != std::string::npos) what = what.substr(bracket + 2);
    fail(path, "not JSON (" + what + ")", kJsonValid);
  }
  if (doc.is_object()) doc = Json::array({doc});  // one map alone
  if (!doc.is_array()) fail(path, "holds a JSON " + std::string(doc.type_name()) + ", not a list of colour maps", kJsonValid);
  if (doc.empty()) fail(path, "holds no colour map (an empty list)", kJsonValid);
  std::string names;
  for (size_t i = 0; i < doc.size(); ++i) {
    const Json& object = doc[i];
    if (!object.is_object()) fail(path, "entry " + std::to_string(i + 1) + " is not an object", kJsonValid);
    const std::string name = object.contains("Name") && object["Name"].is_string() ? object["Name"].get<std::string>() : "";
    if (colorMapName.empty() || name == colorMapName) return colorMapFromJson(object, i, path);
    names += (names.empty() ? "'" : ", '") + name + "'";
  }
  throw InputError("transfer function file " + path + ": no colour map named '" + colorMapName + "' (the file has " + names +
                   ")");
}

TransferFunction parseTransferFunctionText(const std::string& text, const std::string& path) {
  std::vector<ColorPoint> colors;
  std::vector<OpacityPoint> opacities;
  std::istringstream lines(text);
  std::string line;
  int lineNumber = 0;
  while (std::getline(lines, line)) {
    ++lineNumber;
    const size_t hash = line.find('#');
    const std::string content = line.substr(0, hash);
    if (blank(content)) continue;
    std::istringstream fields(content);
    double v[5];
    int n = 0;
    std::string word;
    bool bad = false;
    while (fields >> word) {
      char* end = nullptr;
      const double x = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0' || !std::isfinite(x) || n == 5) {
        bad = true;
        break;
      }
      v[n++] = x;
    }
    if (bad || n != 5) {
      std::string shown = content;
      shown.erase(0, shown.find_first_not_of(" \t"));
      shown.erase(shown.find_last_not_of(" \t\r") + 1);
      fail(path, "line " + std::to_string(lineNumber) + ": expected five finite numbers 'value r g b alpha', found '" + shown + "'",
           kTextValid);
    }
    const std::string at = "line " + std::to_string(lineNumber) + ": ";
    if (!colors.empty() && v[0] < colors.back().x)
      fail(path, at + "value " + number(v[0]) + " is below the previous point's " + number(colors.back().x) +
                     " (values must not decrease)", kTextValid);
    for (int k = 1; k <= 4; ++k)
      if (v[k] < 0.0 || v[k] > 1.0)
        fail(path, at + (k < 4 ? "colour component " : "opacity ") + number(v[k]) + " is outside [0, 1]", kTextValid);
    colors.push_back({v[0], glm::dvec3(v[1], v[2], v[3])});
    opacities.push_back({v[0], v[4]});
  }
  if (colors.empty()) fail(path, blank(text) ? "is empty" : "holds no control point (only comments)", kTextValid);
  try {
    return TransferFunction(std::move(colors), std::move(opacities), path);
  } catch (const ValueError& e) {
    fail(path, e.what(), kTextValid);
  }
}

TransferFunction readTransferFunctionFile(const std::string& path, const std::string& colorMapName) {
  const std::string text = readWhole(path);
  if (endsWithJson(path)) return parseParaViewColorMaps(text, path, colorMapName);
  return parseTransferFunctionText(text, path);
}

std::vector<TransferFunction> readParaViewColorMaps(const std::string& path) {
  const std::string text = readWhole(path);
  // The first map checks the file as a whole (empty, not JSON, no maps) with the reader's messages.
  std::vector<TransferFunction> maps{parseParaViewColorMaps(text, path)};
  const Json doc = Json::parse(text);
  for (std::size_t i = 1; doc.is_array() && i < doc.size(); ++i) {
    if (!doc[i].is_object()) fail(path, "entry " + std::to_string(i + 1) + " is not an object", kJsonValid);
    maps.push_back(colorMapFromJson(doc[i], i, path));
  }
  return maps;
}

std::string paraViewColorMapJson(const TransferFunction& tf, const std::string& name) {
  Json rgb = Json::array(), points = Json::array();
  for (const ColorPoint& p : tf.colors()) {
    rgb.push_back(p.x);
    for (int c = 0; c < 3; ++c) rgb.push_back(p.rgb[c]);
  }
  for (const OpacityPoint& p : tf.opacities()) {
    points.push_back(p.x);
    points.push_back(p.alpha);
    points.push_back(p.midpoint);
    points.push_back(p.sharpness);
  }
  Json map = Json::object();
  map["Name"] = name;
  map["ColorSpace"] = "RGB";
  map["Creator"] = "fccvdb";
  map["RGBPoints"] = std::move(rgb);
  map["Points"] = std::move(points);
  // nlohmann-json writes a double in the fewest digits that read back to the same double.
  return Json::array({map}).dump(1) + "\n";
}

void writeParaViewColorMap(const std::string& path, const TransferFunction& tf, const std::string& name,
                           bool overwrite) {
  writeTextFile(path, paraViewColorMapJson(tf, name), overwrite);
}

TransferFunctionSpec splitTransferFunctionSpec(const std::string& spec) {
  struct stat st {};
  if (::stat(spec.c_str(), &st) == 0) return {spec, ""};  // a file whose name holds ".json:" itself
  std::string lower = spec;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  const std::size_t at = lower.rfind(".json:");
  if (at == std::string::npos) return {spec, ""};
  return {spec.substr(0, at + 5), spec.substr(at + 6)};
}

TransferFunction transferFunctionFromSpec(const std::string& spec) {
  if (isTransferFunctionPreset(spec)) return transferFunctionPreset(spec);
  struct stat st {};
  if (::stat(spec.c_str(), &st) == 0) return readTransferFunctionFile(spec);
  const TransferFunctionSpec named = splitTransferFunctionSpec(spec);
  if (!named.colorMapName.empty() && ::stat(named.path.c_str(), &st) == 0)
    return readTransferFunctionFile(named.path, named.colorMapName);
  std::string valid;
  for (const std::string& n : transferFunctionPresetNames()) valid += (valid.empty() ? "" : ", ") + n;
  // A spec that looks like a path (a folder or an extension) was meant as a file: say it is missing.
  const bool looksLikePath = named.path.find('/') != std::string::npos || named.path.find('.') != std::string::npos;
  throw ValueError("--tf '" + spec + "' is " + (looksLikePath ? "no such file, and not a preset" : "neither a preset") +
                   " (" + valid + ") " + (looksLikePath ? "either" : "nor a file") +
                   " (files: ParaView colour-map .json, FILE.json:NAME for its map NAME, or a text file of "
                   "'value r g b alpha' lines)");
}

}  // namespace fcc::io
