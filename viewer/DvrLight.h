// DVR's gradient shading as a user sets it (DvrShading: RenderOptions, ViewerSettings and
// ProjectedTetrahedra::Options hold one each; shaders/dvr.glsl; docs/DVR.md, "Gradient shading") and
// its light ("The light"): the headlight, one directional light fixed to the camera, or VTK's and
// ParaView's light kit.
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

// Gradient shading's settings. `on` is a program's define (FCC_DVR_SHADING: the unshaded programs stay
// as fast as without it), the others its uniforms, which show while it is on.
struct DvrShading {
  bool on = false;
  // The white specular term: strength in [0, 1] (0: none) and power in (0, 1000] (checkDvrShading).
  float specular = 0.0f;
  float specularPower = 20.0f;
  // The light: a headlight at the eye (the direction towards it is each ray's own), the directional
  // light RenderOptions::lightInCamera (the isosurface's), or the light kit below.
  DvrLight light = DvrLight::Headlight;
  bool operator==(const DvrShading& o) const {
    return on == o.on && specular == o.specular && specularPower == o.specularPower && light == o.light;
  }
  bool operator!=(const DvrShading& o) const { return !(*this == o); }
};
// ValueError naming the valid range of a specular strength or power outside it.
void checkDvrShading(const DvrShading& shading);

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
