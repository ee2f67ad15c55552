#include "DvrLight.h"

#include "Camera.h"
#include "sparse/Error.h"

namespace fcc::render {

std::string dvrLightName(DvrLight light) {
  switch (light) {
    case DvrLight::Headlight: return "headlight";
    case DvrLight::Directional: return "directional";
    case DvrLight::Kit: return "kit";
  }
  return "headlight";
}

void checkDvrShading(const DvrShading& shading) {
  if (!(shading.specular >= 0.0f && shading.specular <= 1.0f))
    throw ValueError("specular strength " + std::to_string(shading.specular) + ": valid are 0 (none) to 1");
  if (!(shading.specularPower > 0.0f && shading.specularPower <= 1000.0f))
    throw ValueError("specular power " + std::to_string(shading.specularPower) + ": valid are (0, 1000]");
}

const LightKit& defaultLightKit() {
  static const LightKit kit = [] {
    const float key = 0.75f, fill = key / 3.0f, back = key / 3.5f, head = key / 3.0f;
    const float sum = key + fill + 2.0f * back + head;
    LightKit k;
    k.inCamera = {lightInCameraFromAngles(10.0f, 50.0f), lightInCameraFromAngles(-10.0f, -75.0f),
                  lightInCameraFromAngles(110.0f, 0.0f), lightInCameraFromAngles(-110.0f, 0.0f)};
    k.weight = {key / sum, fill / sum, back / sum, back / sum};
    k.headWeight = head / sum;
    return k;
  }();
  return kit;
}

void setDvrLightUniforms(GLuint program, DvrLight light) {
  const LightKit& kit = defaultLightKit();
  glProgramUniform1i(program, glGetUniformLocation(program, "uDvrLight"), int(light));
  glProgramUniform4fv(program, glGetUniformLocation(program, "uDvrKitWeights"), 1, &kit.weight[0]);
  glProgramUniform1f(program, glGetUniformLocation(program, "uDvrKitHeadWeight"), kit.headWeight);
}

void setDvrLightFrameUniforms(GLuint program, const CameraFrame& frame) {
  std::array<glm::vec3, 4> world;
  for (std::size_t i = 0; i < world.size(); ++i) world[i] = lightTowardsWorld(frame, defaultLightKit().inCamera[i]);
  glProgramUniform3fv(program, glGetUniformLocation(program, "uDvrKitLights"), GLsizei(world.size()), &world[0].x);
}

}  // namespace fcc::render
