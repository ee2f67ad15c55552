// Several isosurfaces from the command line (`render`, `view`, `bench render`): --iso as a comma list
// of 1 to 4 values, --surface-color (per surface #rrggbb or r,g,b in sRGB, separated by ';' or the flag
// repeated) and --surface-opacity (a comma list in [0, 1]). Each bad list is one ValueError line naming
// the flag and what is valid.
#pragma once

#include <glm/glm.hpp>

#include <string>
#include <vector>

#include "RenderJson.h"
#include "viewer/Raycaster.h"

namespace fcc::cli {

// --iso's values: 1 to render::kMaxIsosurfaces finite numbers separated by commas.
std::vector<float> parseIsoList(const std::string& text);
// --surface-color's colours (linear RGB), in order: each text holds one or more colours separated by ';'.
std::vector<glm::vec3> parseSurfaceColors(const std::vector<std::string>& texts);
// --surface-opacity's opacities: numbers in [0, 1] separated by commas.
std::vector<float> parseSurfaceOpacities(const std::string& text);

// The surfaces: `isos` (the first may come from the default isovalue), with the colours and opacities
// given, the rest render::defaultSurfaceColor and opaque. ValueError naming the flag when more colours
// or opacities than surfaces are given.
std::vector<render::Isosurface> surfacesFrom(const std::vector<float>& isos, const std::vector<std::string>& colorTexts,
                                             const std::string& opacityText);
// Sets options' surfaces (iso, surfaceColor, surfaceOpacity, moreSurfaces) to `surfaces`.
void setSurfaces(render::RenderOptions& options, const std::vector<render::Isosurface>& surfaces);
// What --json says the frame showed: the surfaces' isovalues (options as setSurfaces left them), or in
// DVR the transfer function `tf` (--tf's preset or file).
FrameLook frameLook(const render::RenderOptions& options, const std::string& tf);

}  // namespace fcc::cli
