// The default camera of medical data (issue 16): NIfTI, NRRD with an anatomical space, MetaImage with an
// AnatomicalOrientation (and DICOM, tests/io/test_itk_readers.cpp) are shown upright, the anterior side towards the viewer, whatever the
// file's storage order; data without patient axes keeps the old default; --up/--eye still win.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "ExrRead.h"
#include "RunCommand.h"
#include "io/PatientMetadata.h"
#include "sparse/FccGrid.h"

namespace fcc::test {
namespace {

// The camera `render` printed ("camera: --eye X,Y,Z --lookat X,Y,Z --up X,Y,Z --fov F").
struct PrintedCamera {
  glm::dvec3 eye{0.0}, lookat{0.0}, up{0.0};
  std::string flags;
};

bool parsePrintedCamera(const std::string& err, PrintedCamera& c) {
  const std::size_t at = err.find("camera: ");
  if (at == std::string::npos) return false;
  c.flags = err.substr(at + 8, err.find('\n', at) - at - 8);
  double fov = 0.0;
  return std::sscanf(c.flags.c_str(), "--eye %lf,%lf,%lf --lookat %lf,%lf,%lf --up %lf,%lf,%lf --fov %lf", &c.eye.x, &c.eye.y,
                     &c.eye.z, &c.lookat.x, &c.lookat.y, &c.lookat.z, &c.up.x, &c.up.y, &c.up.z, &fov) == 10;
}

// The printed camera carries no rounding noise: each coordinate is 0 or not tiny against the scene
// (the framing once printed 1e-16 where 0 was meant).
void expectNoRoundingNoise(const PrintedCamera& c) {
  const double scale = std::max({1.0, glm::length(c.eye), glm::length(c.lookat)});
  for (const glm::dvec3& v : {c.eye, c.lookat, c.up})
    for (int a = 0; a < 3; ++a)
      EXPECT_TRUE(v[a] == 0.0 || std::abs(v[a]) > 1e-9 * scale) << "coordinate " << v[a] << " in " << c.flags;
}

std::string triple(const glm::dvec3& v) {
  char text[100];
  std::snprintf(text, sizeof text, "%.17g,%.17g,%.17g", v.x, v.y, v.z);
  return text;
}

// A small head phantom in the patient's RAS coordinates (mm): an ellipsoid with a nose (anterior), an
// ear on the left and a knob on top, right and back; 100 inside, 0 far outside.
float phantom(const glm::dvec3& pRas) {
  struct Blob {
    glm::dvec3 centre, radii;
  };
  const Blob blobs[] = {{{0, 0, 0}, {13, 15, 17}}, {{0, 15, 0}, {4, 4, 4}}, {{-13, 0, 2}, {3.5, 3.5, 3.5}}, {{5, -5, 16}, {5, 5, 5}}};
  double v = 0.0;
  for (const Blob& b : blobs) {
    const glm::dvec3 q = (pRas - b.centre) / b.radii;
    v = std::max(v, 1.0 - glm::dot(q, q));
  }
  return float(100.0 * std::max(v, 0.0));
}

// The phantom's samples stored with index (i, j, k) at RAS position rasOf(i, j, k), x fastest.
std::vector<float> phantomSamples(const glm::ivec3& dims, const std::function<glm::dvec3(int, int, int)>& rasOf) {
  std::vector<float> values;
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) values.push_back(phantom(rasOf(i, j, k)));
  return values;
}

// A little-endian float32 NIfTI-1 (.nii) with the given sform (rows: 3x3 and translation) or qform.
struct NiftiOrientation {
  int16_t sformCode = 0, qformCode = 0;
  float srow[3][4] = {};
  float quatern[3] = {}, qoffset[3] = {};
};

void writeNifti(const std::string& path, const glm::ivec3& dims, const std::vector<float>& values, const NiftiOrientation& o) {
  std::vector<char> h(352, 0);
  auto put = [&](std::size_t offset, auto value) { std::memcpy(h.data() + offset, &value, sizeof value); };
  put(0, int32_t(348));
  const int16_t dim[8] = {3, int16_t(dims.x), int16_t(dims.y), int16_t(dims.z), 1, 1, 1, 1};
  for (int i = 0; i < 8; ++i) put(40 + 2 * i, dim[i]);
  put(70, int16_t(16));  // float32
  put(72, int16_t(32));
  for (int i = 0; i < 4; ++i) put(76 + 4 * i, 1.0f);  // qfac and 1 mm voxels
  put(108, 352.0f);
  put(252, o.qformCode);
  put(254, o.sformCode);
  for (int i = 0; i < 3; ++i) put(256 + 4 * i, o.quatern[i]);
  for (int i = 0; i < 3; ++i) put(268 + 4 * i, o.qoffset[i]);
  for (int row = 0; row < 3; ++row)
    for (int c = 0; c < 4; ++c) put(280 + 16 * row + 4 * c, o.srow[row][c]);
  std::memcpy(h.data() + 344, "n+1\0", 4);
  std::ofstream out(path, std::ios::binary);
  out.write(h.data(), std::streamsize(h.size()));
  out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
}

// How far two renders of the same surface differ: the pixels covered by one only, over those covered
// by either; the mean difference of R where both are covered.
struct ImageDifference {
  double coverage = 1.0, shading = 1.0;
};

ImageDifference differenceOf(const std::string& a, const std::string& b) {
  int w = 0, h = 0, w2 = 0, h2 = 0;
  const std::vector<float> alphaA = readExrChannel(a, "A", w, h), alphaB = readExrChannel(b, "A", w2, h2);
  const std::vector<float> redA = readExrChannel(a, "R", w, h), redB = readExrChannel(b, "R", w2, h2);
  ImageDifference d;
  if (w != w2 || h != h2) return d;
  int either = 0, one = 0, both = 0;
  double shading = 0.0;
  for (std::size_t p = 0; p < alphaA.size(); ++p) {
    const bool inA = alphaA[p] > 0.5f, inB = alphaB[p] > 0.5f;
    either += inA || inB;
    one += inA != inB;
    if (inA && inB) {
      ++both;
      shading += std::abs(double(redA[p]) - double(redB[p]));
    }
  }
  if (either == 0 || both == 0) return d;
  d.coverage = double(one) / either;
  d.shading = shading / both;
  return d;
}

class CliCamera : public ::testing::Test {
 protected:
  // `render FILE -o NAME.exr` at 96x96, iso 50 unless `extra` says, through a cache in the test's folder.
  CommandResult render(const std::string& input, const std::string& name, const std::string& extra = " --iso 50") {
    return runShell("FCCVDB_CACHE_DIR=" + (dir_ / "cache") + " " + FCC_FCCVDB_EXE + " render " + input + " -o " +
                    (dir_ / name) + " --res 96x96 --force" + extra);
  }
  TempDir dir_;
};

// The phantom stored five ways: RAS order (NIfTI sform), reversed along x and y (NIfTI sform; NRRD in
// LPS space and MetaImage "RAI", which store exactly that), and turned 90 degrees about z (NIfTI qform). Each file's world
// frame differs, yet each default view shows the same picture: the head upright, nose towards the
// viewer, the ear on the image's right (the patient's left). The same data without orientation (raw)
// keeps the old default, +y up.
TEST_F(CliCamera, MedicalDataIsUprightFromTheFrontWhateverTheStorageOrder) {
  const glm::ivec3 dims(41, 45, 49);  // odd: reversing an axis maps the FCC sites onto themselves
  NiftiOrientation ras;
  ras.sformCode = 1;
  const float rasRows[3][4] = {{1, 0, 0, -20}, {0, 1, 0, -22}, {0, 0, 1, -24}};
  std::memcpy(ras.srow, rasRows, sizeof rasRows);
  const std::vector<float> rasValues = phantomSamples(dims, [](int i, int j, int k) { return glm::dvec3(i - 20, j - 22, k - 24); });
  writeNifti(dir_ / "ras.nii", dims, rasValues, ras);

  NiftiOrientation reversed;
  reversed.sformCode = 2;
  const float reversedRows[3][4] = {{-1, 0, 0, 20}, {0, -1, 0, 22}, {0, 0, 1, -24}};
  std::memcpy(reversed.srow, reversedRows, sizeof reversedRows);
  const std::vector<float> reversedValues =
      phantomSamples(dims, [](int i, int j, int k) { return glm::dvec3(20 - i, 22 - j, k - 24); });
  writeNifti(dir_ / "reversed.nii", dims, reversedValues, reversed);
  {
    std::ofstream nrrd(dir_ / "lps.nrrd", std::ios::binary);
    nrrd << "NRRD0004\ntype: float\ndimension: 3\nsizes: 41 45 49\nendian: little\nencoding: raw\n"
            "space: left-posterior-superior\nspace directions: (1,0,0) (0,1,0) (0,0,1)\nspace origin: (-20,-22,-24)\n\n";
    nrrd.write(reinterpret_cast<const char*>(reversedValues.data()), std::streamsize(reversedValues.size() * sizeof(float)));
  }
  {
    // The same LPS storage as a MetaImage: ITK's identity orientation, written as "RAI" (each letter
    // the side an axis runs from).
    std::ofstream mha(dir_ / "lps.mha", std::ios::binary);
    mha << "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
           "TransformMatrix = 1 0 0 0 1 0 0 0 1\nOffset = -20 -22 -24\nAnatomicalOrientation = RAI\n"
           "ElementSpacing = 1 1 1\nDimSize = 41 45 49\nElementType = MET_FLOAT\nElementDataFile = LOCAL\n";
    mha.write(reinterpret_cast<const char*>(reversedValues.data()), std::streamsize(reversedValues.size() * sizeof(float)));
  }

  NiftiOrientation turned;  // index i runs anterior (+y), j to the patient's left (-x)
  turned.qformCode = 1;
  turned.quatern[2] = float(std::sqrt(0.5));  // 90 degrees about z
  turned.qoffset[0] = 20;
  turned.qoffset[1] = -22;
  turned.qoffset[2] = -24;
  const glm::ivec3 turnedDims(45, 41, 49);
  writeNifti(dir_ / "turned.nii", turnedDims,
             phantomSamples(turnedDims, [](int i, int j, int k) { return glm::dvec3(20 - j, i - 22, k - 24); }), turned);

  {
    std::ofstream raw(dir_ / "ras.raw", std::ios::binary);
    raw.write(reinterpret_cast<const char*>(rasValues.data()), std::streamsize(rasValues.size() * sizeof(float)));
  }

  const CommandResult reference = render(dir_ / "ras.nii", "ras.exr");
  if (failedForLackOfGl(reference)) GTEST_SKIP() << reference.err;
  ASSERT_EQ(reference.status, 0) << reference.err;
  PrintedCamera camera;
  ASSERT_TRUE(parsePrintedCamera(reference.err, camera)) << reference.err;
  // Stored RAS: the world is RAS, superior +z is up and the eye lies anterior (+y) of the centre.
  EXPECT_EQ(camera.up, glm::dvec3(0, 0, 1)) << camera.flags;
  const glm::dvec3 view = camera.eye - camera.lookat;
  EXPECT_GT(view.y, 0.0) << camera.flags;
  EXPECT_LT(std::abs(view.x) + std::abs(view.z), 1e-9 * view.y) << camera.flags;
  expectNoRoundingNoise(camera);

  // That camera given explicitly (the direction and up by hand, the framing distance printed) is the
  // same image.
  const CommandResult explicitCamera = render(dir_ / "ras.nii", "explicit.exr",
                                              " --iso 50 --lookat " + triple(camera.lookat) + " --eye " +
                                                  triple(camera.lookat + glm::dvec3(0, glm::length(view), 0)) + " --up 0,0,1");
  ASSERT_EQ(explicitCamera.status, 0) << explicitCamera.err;
  EXPECT_EQ(readText(dir_ / "ras.exr"), readText(dir_ / "explicit.exr"));

  // Each file's world is the patient's RAS moved about; its default camera is the upright one in that
  // world. Its framing (the data's box, in packed voxels) moves with the storage order by a voxel, so
  // the picture is compared under the reference's framing, mapped into that world, with the default up.
  struct Variant {
    const char* name;
    std::function<glm::dvec3(const glm::dvec3&)> worldOf;  // of a RAS position
    glm::dvec3 superior, anterior;                         // in that world
  };
  const Variant variants[] = {
      {"reversed.nii", [](const glm::dvec3& p) { return glm::dvec3(40 - p.x, 44 - p.y, p.z); }, {0, 0, 1}, {0, -1, 0}},
      {"lps.nrrd", [](const glm::dvec3& p) { return glm::dvec3(-p.x, -p.y, p.z); }, {0, 0, 1}, {0, -1, 0}},
      {"lps.mha", [](const glm::dvec3& p) { return glm::dvec3(-p.x, -p.y, p.z); }, {0, 0, 1}, {0, -1, 0}},
      {"turned.nii", [](const glm::dvec3& p) { return glm::dvec3(p.y + 42, -2 - p.x, p.z); }, {0, 0, 1}, {1, 0, 0}},
  };
  for (const Variant& v : variants) {
    SCOPED_TRACE(v.name);
    const CommandResult r = render(dir_ / v.name, std::string(v.name) + ".exr");
    ASSERT_EQ(r.status, 0) << r.err;
    PrintedCamera c;
    ASSERT_TRUE(parsePrintedCamera(r.err, c)) << r.err;
    EXPECT_EQ(c.up, v.superior) << c.flags;
    EXPECT_LT(glm::length(glm::normalize(c.eye - c.lookat) - v.anterior), 1e-6) << c.flags;  // the qform is in floats

    const std::string framed = std::string(v.name) + ".framed.exr";
    const CommandResult same = render(dir_ / v.name, framed,
                                      " --iso 50 --lookat " + triple(v.worldOf(camera.lookat)) + " --eye " + triple(v.worldOf(camera.eye)));
    ASSERT_EQ(same.status, 0) << same.err;
    const ImageDifference d = differenceOf(dir_ / "ras.exr", dir_ / framed);
    EXPECT_LT(d.coverage, 0.005) << same.err;  // measured: 0
    EXPECT_LT(d.shading, 1e-3) << same.err;    // measured: below 2e-7
  }

  // The phantom is asymmetric enough for these checks to fail: upside down, or from behind, it differs.
  for (const std::string& wrong : {std::string(" --up 0,0,-1"), " --eye " + triple(camera.lookat - view)}) {
    SCOPED_TRACE(wrong);
    const CommandResult r = render(dir_ / "ras.nii", "wrong.exr", " --iso 50" + wrong);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_GT(differenceOf(dir_ / "ras.exr", dir_ / "wrong.exr").coverage, 0.2);  // measured: over 0.5
  }

  // The same samples as raw data: no patient axes, the old default (oblique, +y up).
  const CommandResult raw = render(dir_ / "ras.raw", "raw.exr", " --iso 50 --dims 41,45,49 --type f32");
  ASSERT_EQ(raw.status, 0) << raw.err;
  PrintedCamera rawCamera;
  ASSERT_TRUE(parsePrintedCamera(raw.err, rawCamera)) << raw.err;
  EXPECT_EQ(rawCamera.up, glm::dvec3(0, 1, 0)) << rawCamera.flags;
  expectNoRoundingNoise(rawCamera);
}

// The flags still win: --up alone keeps the upright eye and takes the user's up; an --eye above the
// head (along superior) gets anterior as up; --eye with --up takes both.
TEST_F(CliCamera, FlagsWinOverTheUprightDefault) {
  const glm::ivec3 dims(21, 23, 25);
  NiftiOrientation ras;
  ras.sformCode = 1;
  const float rows[3][4] = {{1, 0, 0, -10}, {0, 1, 0, -11}, {0, 0, 1, -12}};
  std::memcpy(ras.srow, rows, sizeof rows);
  writeNifti(dir_ / "h.nii", dims, phantomSamples(dims, [](int i, int j, int k) { return 2.0 * glm::dvec3(i - 10, j - 11, k - 12); }), ras);

  const CommandResult upright = render(dir_ / "h.nii", "a.exr");
  if (failedForLackOfGl(upright)) GTEST_SKIP() << upright.err;
  ASSERT_EQ(upright.status, 0) << upright.err;
  PrintedCamera base;
  ASSERT_TRUE(parsePrintedCamera(upright.err, base)) << upright.err;

  const CommandResult upOnly = render(dir_ / "h.nii", "b.exr", " --iso 50 --up 1,0,0");
  ASSERT_EQ(upOnly.status, 0) << upOnly.err;
  PrintedCamera c;
  ASSERT_TRUE(parsePrintedCamera(upOnly.err, c)) << upOnly.err;
  EXPECT_EQ(c.up, glm::dvec3(1, 0, 0));
  EXPECT_EQ(c.eye, base.eye);

  const glm::dvec3 above = base.lookat + glm::dvec3(0, 0, 100);
  const CommandResult fromAbove = render(dir_ / "h.nii", "c.exr", " --iso 50 --eye " + triple(above));
  ASSERT_EQ(fromAbove.status, 0) << fromAbove.err;
  ASSERT_TRUE(parsePrintedCamera(fromAbove.err, c)) << fromAbove.err;
  EXPECT_EQ(c.up, glm::dvec3(0, 1, 0)) << "anterior up for a view from above";
  EXPECT_EQ(c.eye, above);

  const CommandResult both = render(dir_ / "h.nii", "d.exr", " --iso 50 --eye 100,0,0 --up 0,1,0");
  ASSERT_EQ(both.status, 0) << both.err;
  ASSERT_TRUE(parsePrintedCamera(both.err, c)) << both.err;
  EXPECT_EQ(c.up, glm::dvec3(0, 1, 0));
  EXPECT_EQ(c.eye, glm::dvec3(100, 0, 0));
}

// Without patient axes, an --eye straight above or below the look-at point (along the default up)
// renders: the up becomes the one that keeps world +x to the right (-z looking down, +z looking up).
// An --up along the view is still the user's and is refused in one line.
TEST_F(CliCamera, AViewAlongTheDefaultUpChoosesAnotherUp) {
  const std::string synth = dir_ / "s.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + synth + " --dims 16,16,16 --quiet").status, 0);
  const CommandResult framed = render(synth, "a.exr");
  if (failedForLackOfGl(framed)) GTEST_SKIP() << framed.err;
  ASSERT_EQ(framed.status, 0) << framed.err;
  PrintedCamera base;
  ASSERT_TRUE(parsePrintedCamera(framed.err, base)) << framed.err;
  ASSERT_EQ(base.up, glm::dvec3(0, 1, 0)) << base.flags;
  for (const double side : {1.0, -1.0}) {
    const glm::dvec3 eye = base.lookat + glm::dvec3(0, 40.0 * side, 0);
    const CommandResult along = render(synth, "b.exr", " --iso 0.5 --eye " + triple(eye));
    ASSERT_EQ(along.status, 0) << "eye " << triple(eye) << ": " << along.err;
    PrintedCamera c;
    ASSERT_TRUE(parsePrintedCamera(along.err, c)) << along.err;
    EXPECT_EQ(c.up, glm::dvec3(0, 0, -side)) << c.flags;
    EXPECT_EQ(c.eye, eye) << c.flags;
  }
  const CommandResult refused = render(synth, "c.exr", " --iso 0.5 --eye " + triple(base.lookat + glm::dvec3(0, 40, 0)) + " --up 0,1,0");
  EXPECT_EQ(refused.status, 1) << refused.err;
  EXPECT_NE(refused.err.find("the up vector is parallel to the view direction"), std::string::npos) << refused.err;
}

// A file whose patient axes are damaged (one without the other, parallel ones) is one line, exit 1, no image.
TEST_F(CliCamera, DamagedPatientAxesAreOneLine) {
  const std::string synth = dir_ / "s.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + synth + " --dims 16,16,16 --quiet").status, 0);
  initializeVdb();
  auto rewrite = [&](const std::string& out, const std::function<void(openvdb::GridBase&)>& edit) {
    openvdb::io::File in(synth);
    in.open();
    openvdb::GridPtrVecPtr grids = in.getGrids();
    in.close();
    for (const openvdb::GridBase::Ptr& g : *grids)
      if (isFccGrid(*g)) edit(*g);
    openvdb::io::File(out).write(*grids);
  };
  rewrite(dir_ / "one.vdb", [](openvdb::GridBase& g) { g.insertMeta(meta::kPatientSuperior, openvdb::Vec3DMetadata({0, 0, 1})); });
  rewrite(dir_ / "parallel.vdb", [](openvdb::GridBase& g) { io::recordPatientAxes(g, io::PatientAxes{{0, 0, 1}, {0, 0, 2}}); });
  rewrite(dir_ / "fine.vdb", [](openvdb::GridBase& g) { io::recordPatientAxes(g, io::PatientAxes{{0, 1, 0}, {0, 0, 1}}); });
  const CommandResult fine = render(dir_ / "fine.vdb", "fine.png", " --iso 0.25");
  if (failedForLackOfGl(fine)) GTEST_SKIP() << fine.err;
  ASSERT_EQ(fine.status, 0) << fine.err;
  PrintedCamera c;
  ASSERT_TRUE(parsePrintedCamera(fine.err, c)) << fine.err;
  EXPECT_EQ(c.up, glm::dvec3(0, 1, 0)) << "the recorded superior, whatever the data";
  EXPECT_GT((c.eye - c.lookat).z, 0.0) << c.flags;
  for (const char* name : {"one", "parallel"}) {
    SCOPED_TRACE(name);
    const CommandResult r = render(dir_ / (std::string(name) + ".vdb"), std::string(name) + ".png", " --iso 0.25");
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_THAT(r.err, ::testing::HasSubstr(name == std::string("one") ? "fcc_patient_superior without fcc_patient_anterior"
                                                                        : "must be finite, nonzero and not parallel"));
    EXPECT_FALSE(std::filesystem::exists(dir_ / (std::string(name) + ".png")));
  }
}

// The shared Colin27 head (NIfTI, stored RAS), rendered directly: the default camera looks at its face
// with superior up, where it used to look from above.
TEST_F(CliCamera, Ch2betterDefaultIsUpright) {
  const std::string ch2 = std::string(FCC_SHARED_DATA_DIR) + "/ch2better.nii.gz";
  if (!std::filesystem::exists(ch2)) GTEST_SKIP() << ch2 << " is missing";
  const CommandResult r = render(ch2, "ch2.exr", "");
  if (failedForLackOfGl(r)) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.status, 0) << r.err;
  PrintedCamera c;
  ASSERT_TRUE(parsePrintedCamera(r.err, c)) << r.err;
  EXPECT_EQ(c.up, glm::dvec3(0, 0, 1)) << c.flags;
  const glm::dvec3 view = c.eye - c.lookat;
  EXPECT_GT(view.y, 0.0) << c.flags;
  EXPECT_LT(std::abs(view.x) + std::abs(view.z), 1e-9 * view.y) << c.flags;
}

}  // namespace
}  // namespace fcc::test
