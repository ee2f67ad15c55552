// Camera files (viewer/CameraFile.h): what is written comes back exactly, and each kind of bad file
// is one line naming the file, what is wrong and what is valid.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tests/tools/RunCommand.h"
#include "sparse/Error.h"
#include "viewer/CameraFile.h"

namespace fcc::render {
namespace {

TEST(CameraFile, WrittenCameraComesBackBitForBit) {
  test::TempDir dir;
  Camera c;
  c.eye = glm::dvec3(0.1, -1.0 / 3.0, 1e-17);
  c.lookat = glm::dvec3(12345.678901234567, 2.0 / 7.0, -5.5);
  c.up = glm::dvec3(0.2, 0.9, 0.1);
  c.fovYDegrees = 33.333333333333336;
  const std::string path = dir / "c.json";
  writeCameraFile(path, c);
  const Camera back = readCameraFile(path);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(back.eye[k], c.eye[k]);
    EXPECT_EQ(back.lookat[k], c.lookat[k]);
    EXPECT_EQ(back.up[k], c.up[k]);
  }
  EXPECT_EQ(back.fovYDegrees, c.fovYDegrees);
  EXPECT_EQ(test::readText(path), cameraJson(c));
}

TEST(CameraFile, UpAndFovMayBeLeftOutAndKeysComeInAnyOrder) {
  const Camera c = parseCameraJson(" {\n \"lookat\" : [0,0,0],\n \"eye\": [1, 2, 3.5e0] }\n", "x.json");
  EXPECT_EQ(c.eye, glm::dvec3(1.0, 2.0, 3.5));
  EXPECT_EQ(c.up, glm::dvec3(0.0, 1.0, 0.0));
  EXPECT_EQ(c.fovYDegrees, 40.0);
}

TEST(CameraFile, BadFilesAreOneLineNamingFileProblemAndTheValidForm) {
  const struct {
    const char* text;
    const char* problem;
  } cases[] = {
      {"", "expected '{'"},
      {"{\"eye\": [1,2,3]}", "no \"lookat\""},
      {"{\"lookat\": [1,2,3]}", "no \"eye\""},
      {"{\"eye\": [1,2], \"lookat\": [0,0,0]}", "\"eye\" needs three numbers, not 2"},
      {"{\"eye\": [1,2,3], \"lookat\": [0,0,0], \"fow\": 30}", "unknown key \"fow\""},
      {"{\"eye\": [1,2,\"a\"], \"lookat\": [0,0,0]}", "\"eye\" expects numbers"},
      {"{\"eye\": [1,2,3], \"lookat\": [0,0,0], \"fov\": 1e999}", "not finite"},
      {"{\"eye\": [1,2,3], \"lookat\": [1,2,3]}", "the eye and the look-at point coincide"},
      {"{\"eye\": [0,5,0], \"lookat\": [0,0,0], \"up\": [0,1,0]}", "up vector is parallel"},
      {"{\"eye\": [1,2,3], \"lookat\": [0,0,0], \"fov\": 180}", "field of view"},
      {"{\"eye\": [1,2,3], \"lookat\": [0,0,0]} x", "text after the object"},
  };
  for (const auto& c : cases) {
    try {
      parseCameraJson(c.text, "cam.json");
      ADD_FAILURE() << "accepted: " << c.text;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("camera file cam.json: ", 0), 0u) << what;
      EXPECT_NE(what.find(c.problem), std::string::npos) << what;
      EXPECT_NE(what.find("valid is {\"eye\": [X, Y, Z]"), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
  EXPECT_THROW(readCameraFile("/nonexistent/cam.json"), InputError);
}

// A view along the default up without "up" takes upAcross's: across the view, world +x to the right
// where the view allows (views along y), and for every view direction a valid frame.
TEST(CameraFile, AViewAlongTheDefaultUpWithoutUpTakesOneAcrossIt) {
  const Camera down = parseCameraJson("{\"eye\": [0,5,0], \"lookat\": [0,0,0]}", "cam.json");
  EXPECT_EQ(down.up, glm::dvec3(0, 0, -1));
  const Camera up = parseCameraJson("{\"eye\": [1,-5,2], \"lookat\": [1,0,2]}", "cam.json");
  EXPECT_EQ(up.up, glm::dvec3(0, 0, 1));
  for (const glm::dvec3& view : {glm::dvec3(0, -1, 0), glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0), glm::dvec3(-1, 0, 0),
                                 glm::dvec3(0, 0, 1), glm::dvec3(0.3, -2, 0.1), glm::dvec3(-3, 0.2, 0.5)}) {
    const glm::dvec3 u = upAcross(view);
    EXPECT_NEAR(glm::length(u), 1.0, 1e-12) << view.x << "," << view.y << "," << view.z;
    EXPECT_NEAR(glm::dot(u, glm::normalize(view)), 0.0, 1e-12) << view.x << "," << view.y << "," << view.z;
    const CameraFrame frame = cameraFrame(Camera{glm::dvec3(0.0), view, u, 40.0}, 1.0);
    if (std::abs(glm::normalize(view).x) < 0.9) {
      EXPECT_GT(frame.right.x, 0.0) << "world +x to the right, view " << view.x << "," << view.y << "," << view.z;
    } else {
      EXPECT_GT(frame.up.y, 0.0) << "+y up for a view along x";
    }
  }
}

}  // namespace
}  // namespace fcc::render
