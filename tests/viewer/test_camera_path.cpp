// Camera paths (viewer/CameraPath.h, `view --record-path`): a written path comes back exactly, the
// camera between two frames is their blend, and each kind of bad file is one line naming it.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "sparse/Error.h"
#include "tests/tools/RunCommand.h"
#include "viewer/CameraPath.h"

namespace fcc::render {
namespace {

CameraPath twoFramePath() {
  CameraPath p;
  p.file = "data \"quoted\".vdb";
  Camera a;
  a.eye = glm::dvec3(0.1, -1.0 / 3.0, 10.0);
  a.lookat = glm::dvec3(2.0 / 7.0, 0.0, 0.0);
  a.fovYDegrees = 33.333333333333336;
  Camera b = a;
  b.eye = glm::dvec3(10.0, 1.0, 0.5);
  b.fovYDegrees = 50.0;
  p.points = {{0.0, a}, {0.25, b}};
  return p;
}

TEST(CameraPath, WrittenPathComesBackBitForBit) {
  test::TempDir dir;
  const CameraPath p = twoFramePath();
  const std::string file = dir / "p.json";
  writeCameraPathFile(file, p, false);
  const CameraPath back = readCameraPathFile(file);
  EXPECT_EQ(back.file, p.file);
  ASSERT_EQ(back.points.size(), p.points.size());
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    EXPECT_EQ(back.points[i].seconds, p.points[i].seconds);
    EXPECT_EQ(back.points[i].camera.eye, p.points[i].camera.eye);
    EXPECT_EQ(back.points[i].camera.lookat, p.points[i].camera.lookat);
    EXPECT_EQ(back.points[i].camera.up, p.points[i].camera.up);
    EXPECT_EQ(back.points[i].camera.fovYDegrees, p.points[i].camera.fovYDegrees);
  }
  EXPECT_THROW(writeCameraPathFile(file, p, false), Error) << "an existing file needs --force";
  EXPECT_NO_THROW(writeCameraPathFile(file, p, true));
}

TEST(CameraPath, CameraBetweenFramesIsTheirBlendAndEndsAreHeld) {
  const CameraPath p = twoFramePath();
  const Camera& a = p.points[0].camera;
  const Camera& b = p.points[1].camera;
  EXPECT_EQ(cameraAt(p, -1.0).eye, a.eye);
  EXPECT_EQ(cameraAt(p, 5.0).eye, b.eye);
  const Camera mid = cameraAt(p, 0.125);
  EXPECT_NEAR(glm::length(mid.eye - 0.5 * (a.eye + b.eye)), 0.0, 1e-12);
  EXPECT_NEAR(mid.fovYDegrees, 0.5 * (a.fovYDegrees + b.fovYDegrees), 1e-12);
}

TEST(CameraPath, RecorderTimesFramesFromTheFirst) {
  CameraPathRecorder recorder("f.vdb");
  Camera c;
  recorder.record(c);
  recorder.record(c);
  ASSERT_EQ(recorder.path().points.size(), 2u);
  EXPECT_EQ(recorder.path().points[0].seconds, 0.0);
  EXPECT_GE(recorder.path().points[1].seconds, 0.0);
  EXPECT_EQ(recorder.path().file, "f.vdb");
}

TEST(CameraPath, BadFilesAreOneLineNamingThem) {
  const std::string frame = "{\"t\": 0, \"eye\": [1, 2, 3], \"lookat\": [0, 0, 0]}";
  const std::string bad[] = {
      "not json",
      "[]",
      "{\"frames\": [" + frame + "]}",                              // no version
      "{\"fccvdb_camera_path\": 2, \"frames\": [" + frame + "]}",   // unknown version
      "{\"fccvdb_camera_path\": 1}",                                // no frames
      "{\"fccvdb_camera_path\": 1, \"frames\": []}",
      "{\"fccvdb_camera_path\": 1, \"frames\": [{\"eye\": [1, 2, 3], \"lookat\": [0, 0, 0]}]}",  // no t
      "{\"fccvdb_camera_path\": 1, \"frames\": [{\"t\": 0, \"eye\": [1, 2], \"lookat\": [0, 0, 0]}]}",
      "{\"fccvdb_camera_path\": 1, \"frames\": [{\"t\": 0, \"eye\": [0, 0, 0], \"lookat\": [0, 0, 0]}]}",
      "{\"fccvdb_camera_path\": 1, \"frames\": [{\"t\": 1, \"eye\": [1, 2, 3], \"lookat\": [0, 0, 0]}, " + frame + "]}",
      "{\"fccvdb_camera_path\": 1, \"frames\": [{\"t\": 0, \"eye\": [1, 2, 3], \"lookat\": [0, 0, 0], \"roll\": 1}]}",
      "{\"fccvdb_camera_path\": 1, \"frames\": [{\"t\": 1e999, \"eye\": [1, 2, 3], \"lookat\": [0, 0, 0]}]}",  // beyond a double
  };
  for (const std::string& text : bad) {
    try {
      parseCameraPathJson(text, "bad.json");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_NE(what.find("camera path bad.json: "), std::string::npos) << what;
      EXPECT_NE(what.find("valid is"), std::string::npos) << what;
    }
  }
  EXPECT_THROW(readCameraPathFile("/nonexistent/p.json"), InputError);
}

}  // namespace
}  // namespace fcc::render
