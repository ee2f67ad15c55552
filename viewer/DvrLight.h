// DVR's light for gradient shading (RenderOptions::dvrLight; shaders/dvr.glsl; docs/DVR.md, "The
// light"): the headlight, one directional light fixed to the camera, or VTK's and ParaView's light kit.
#pragma once

#include <array>
#include <string>

#include <glm/glm.hpp>

#include "GlProgram.h"

namespace fcc::render {

struct CameraFrame;

// The values of dvr.glsl's uDvrLight.
enum class DvrLight { Headlight = 0, Directional = 1, Kit = 2 };
// "headlight", "directional", "kit" (the bench's JSON, the viewer's list).
std::string dvrLightName(DvrLight light);

// VTK's default light kit (vtkLightKit, ParaView's "Light Kit"), fixed to the camera: a key light at
// elevation 50, azimuth 10 degrees (render::lightInCameraFromAngles' angles), a fill light at -75, -10,
// two back lights at 0, +110 and 0, -110, and the headlight, of intensities 0.75, 0.75 / 3, 0.75 / 3.5
// each and 0.75 / 3 (its key-to-fill, key-to-back and key-to-head ratios). Here the lights are white
// (the kit's warmth, a tint, is not taken) and weighted by those intensities over their sum, so that
// the weights add up to 1 as the one light's does and an image keeps the one light's brightness range.
struct LightKit {
  std::array<glm::vec3, 4> inCamera;  // key, fill, back, back: unit directions towards them, camera space
  std::array<float, 4> weight;        // theirs
  float headWeight = 0.0f;            // the headlight's (towards the eye along each ray)
};
const LightKit& defaultLightKit();

// dvr.glsl's light uniforms in `program` (a shaded DVR program; locations -1 elsewhere, ignored):
// uDvrLight and the kit's weights, and (setDvrLightFrameUniforms, every frame) the kit's world
// directions for `frame` (the directional light's, uLightDir, is the isosurface's uniform too: the
// callers set it).
void setDvrLightUniforms(GLuint program, DvrLight light);
void setDvrLightFrameUniforms(GLuint program, const CameraFrame& frame);

}  // namespace fcc::render
