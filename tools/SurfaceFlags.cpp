#include "SurfaceFlags.h"

#include <cmath>
#include <cstdlib>

#include "sparse/Error.h"
#include "viewer/Srgb.h"

namespace fcc::cli {
namespace {

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    const std::size_t at = text.find(separator, start);
    parts.push_back(text.substr(start, at == std::string::npos ? std::string::npos : at - start));
    if (at == std::string::npos) return parts;
    start = at + 1;
  }
}

std::string trimmed(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

// A finite float, the whole text; false for anything else.
bool parseNumber(const std::string& text, float& out) {
  const std::string t = trimmed(text);
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size() || !std::isfinite(v) || !std::isfinite(float(v))) return false;
  out = float(v);
  return true;
}

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// "#rrggbb" or "r,g,b" (0..1), both sRGB; false for anything else.
bool parseColor(const std::string& text, glm::vec3& srgb) {
  const std::string t = trimmed(text);
  if (!t.empty() && t[0] == '#') {
    if (t.size() != 7) return false;
    for (int c = 0; c < 3; ++c) {
      const int hi = hexDigit(t[1 + 2 * c]), lo = hexDigit(t[2 + 2 * c]);
      if (hi < 0 || lo < 0) return false;
      srgb[c] = float(hi * 16 + lo) / 255.0f;
    }
    return true;
  }
  const std::vector<std::string> parts = split(t, ',');
  if (parts.size() != 3) return false;
  for (int c = 0; c < 3; ++c)
    if (!parseNumber(parts[std::size_t(c)], srgb[c]) || srgb[c] < 0.0f || srgb[c] > 1.0f) return false;
  return true;
}

const std::string kMax = std::to_string(render::kMaxIsosurfaces);

}  // namespace

std::vector<float> parseIsoList(const std::string& text) {
  const std::vector<std::string> parts = split(text, ',');
  std::vector<float> isos;
  for (const std::string& part : parts) {
    float v = 0.0f;
    if (!parseNumber(part, v)) {
      if (parts.size() == 1)  // one value: today's message
        throw ValueError("--iso '" + text + "': the isovalue must be a finite number");
      throw ValueError("--iso '" + text + "': expected 1 to " + kMax +
                       " finite isovalues separated by commas, e.g. 0.2,0.5");
    }
    isos.push_back(v);
  }
  if (isos.size() > std::size_t(render::kMaxIsosurfaces))
    throw ValueError("--iso '" + text + "': " + std::to_string(isos.size()) + " isovalues; valid are 1 to " + kMax +
                     " separated by commas, e.g. 0.2,0.5");
  return isos;
}

std::vector<glm::vec3> parseSurfaceColors(const std::vector<std::string>& texts) {
  std::vector<glm::vec3> colors;
  for (const std::string& text : texts)
    for (const std::string& part : split(text, ';')) {
      glm::vec3 srgb(0.0f);
      if (!parseColor(part, srgb))
        throw ValueError("--surface-color '" + text + "': expected a colour per surface, #rrggbb or r,g,b (sRGB, 0 to 1), " +
                         "separated by ';' or the flag repeated, e.g. '#d9b88f;0.3,0.5,0.9'");
      colors.push_back(render::linearFromSrgb(srgb));
    }
  return colors;
}

std::vector<float> parseSurfaceOpacities(const std::string& text) {
  std::vector<float> opacities;
  for (const std::string& part : split(text, ',')) {
    float v = 0.0f;
    if (!parseNumber(part, v) || v < 0.0f || v > 1.0f)
      throw ValueError("--surface-opacity '" + text + "': expected an opacity per surface, 0 to 1, separated by commas, e.g. 1,0.4");
    opacities.push_back(v);
  }
  return opacities;
}

std::vector<render::Isosurface> surfacesFrom(const std::vector<float>& isos, const std::vector<std::string>& colorTexts,
                                             const std::string& opacityText) {
  const std::vector<glm::vec3> colors = parseSurfaceColors(colorTexts);
  const std::vector<float> opacities = opacityText.empty() ? std::vector<float>{} : parseSurfaceOpacities(opacityText);
  const std::string surfaces = std::to_string(isos.size()) + (isos.size() == 1 ? " surface" : " surfaces");
  if (colors.size() > isos.size())
    throw ValueError("--surface-color: " + std::to_string(colors.size()) + " colours for " + surfaces +
                     " (--iso's values); valid is at most one colour per surface");
  if (opacities.size() > isos.size())
    throw ValueError("--surface-opacity '" + opacityText + "': " + std::to_string(opacities.size()) + " opacities for " +
                     surfaces + " (--iso's values); valid is at most one opacity per surface");
  std::vector<render::Isosurface> out;
  for (std::size_t k = 0; k < isos.size(); ++k)
    out.push_back(render::Isosurface{isos[k], k < colors.size() ? colors[k] : render::defaultSurfaceColor(int(k)),
                                     k < opacities.size() ? opacities[k] : 1.0f});
  return out;
}

void setSurfaces(render::RenderOptions& options, const std::vector<render::Isosurface>& surfaces) {
  options.iso = surfaces.at(0).iso;
  options.surfaceColor = surfaces[0].color;
  options.surfaceOpacity = surfaces[0].opacity;
  options.moreSurfaces.assign(surfaces.begin() + 1, surfaces.end());
}

FrameLook frameLook(const render::RenderOptions& options, const std::string& tf) {
  FrameLook look;
  if (options.mode == render::RenderMode::Dvr) {
    look.transferFunction = tf;
  } else {
    look.isovalues.push_back(options.iso);
    for (const render::Isosurface& s : options.moreSurfaces) look.isovalues.push_back(s.iso);
  }
  return look;
}

}  // namespace fcc::cli
