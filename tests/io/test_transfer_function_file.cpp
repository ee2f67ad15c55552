// Transfer functions from files (io/TransferFunctionFile.h): ParaView's colour-map JSON (written here
// in its exported shape) and the plain text format load; every bad file is one InputError line naming
// the file, what is wrong and what is valid; `--tf SPEC` resolves presets before files.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "io/TransferFunctionFile.h"
#include "sparse/Error.h"
#include "tests/tools/RunCommand.h"

namespace fcc {
namespace {

using test::TempDir;

std::string write(const TempDir& dir, const std::string& name, const std::string& text) {
  const std::string path = dir / name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// As ParaView's "Export" writes a colour map (a list, one object per map, keys it has besides ours).
const char* const kParaView = R"([
  {
    "ColorSpace" : "Diverging",
    "Creator" : "Test",
    "Name" : "Two Tone",
    "NanColor" : [ 1, 1, 0 ],
    "Points" : [ -1.0, 0.0, 0.5, 0.0, 0.5, 0.25, 0.5, 0.0, 2.0, 0.75, 0.5, 0.0 ],
    "RGBPoints" : [ -1.0, 0.0, 0.0, 1.0, 0.5, 1.0, 1.0, 1.0, 2.0, 1.0, 0.0, 0.0 ]
  },
  {
    "ColorSpace" : "RGB",
    "Name" : "No Opacity",
    "RGBPoints" : [ 10, 0, 0, 0, 20, 1, 1, 1 ]
  }
])";

TEST(TransferFunctionFile, ParaViewJsonLoadsTheFirstMapOrTheNamedOne) {
  TempDir dir;
  const std::string path = write(dir, "maps.json", kParaView);
  const TransferFunction first = io::readTransferFunctionFile(path);
  EXPECT_EQ(first.name(), "Two Tone");
  EXPECT_FALSE(first.normalized());  // data values as written
  ASSERT_EQ(first.colors().size(), 3u);
  ASSERT_EQ(first.opacities().size(), 3u);
  EXPECT_EQ(first.color(-1.0), glm::dvec3(0.0, 0.0, 1.0));
  EXPECT_EQ(first.color(2.0), glm::dvec3(1.0, 0.0, 0.0));
  EXPECT_NEAR(first.color(1.25).g, 0.5, 1e-12);  // interpolated in RGB
  EXPECT_DOUBLE_EQ(first.opacity(0.5), 0.25);
  EXPECT_DOUBLE_EQ(first.opacity(1.25), 0.5);
  EXPECT_EQ(first.domainMin(), -1.0);
  EXPECT_EQ(first.domainMax(), 2.0);

  // By name; without "Points", ParaView's default opacity: a ramp 0 to 1 over the colours' range.
  const TransferFunction second = io::readTransferFunctionFile(path, "No Opacity");
  EXPECT_EQ(second.name(), "No Opacity");
  EXPECT_DOUBLE_EQ(second.opacity(10.0), 0.0);
  EXPECT_DOUBLE_EQ(second.opacity(15.0), 0.5);
  EXPECT_DOUBLE_EQ(second.opacity(20.0), 1.0);
  try {
    io::readTransferFunctionFile(path, "Jet");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'Jet'"), std::string::npos) << what;
    EXPECT_NE(what.find("'Two Tone', 'No Opacity'"), std::string::npos) << what;
  }
  // One map alone (an object, not a list) is taken too.
  const TransferFunction alone =
      io::readTransferFunctionFile(write(dir, "one.JSON", R"({"Name": "x", "RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1]})"));
  EXPECT_EQ(alone.name(), "x");
}

// Each bad file: an InputError of one line that names the file, says what is wrong (`expected`) and
// what is valid.
void expectBadFile(const std::string& path, const std::string& expected) {
  try {
    io::readTransferFunctionFile(path);
    FAIL() << path << ": no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    std::printf("[   INFO   ] %s\n", what.c_str());
    EXPECT_EQ(what.rfind("transfer function file " + path + ": ", 0), 0u) << what;
    EXPECT_NE(what.find(expected), std::string::npos) << "expected '" << expected << "' in: " << what;
    EXPECT_NE(what.find("valid:"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(TransferFunctionFile, BadJsonFilesAreOneClearLine) {
  TempDir dir;
  const auto map = [](const std::string& body) { return "[{\"Name\": \"m\", " + body + "}]"; };
  expectBadFile(write(dir, "empty.json", ""), "is empty");
  expectBadFile(write(dir, "blank.json", "  \n\t\n"), "is empty");
  expectBadFile(write(dir, "text.json", "value r g b alpha\n"), "not JSON");
  expectBadFile(write(dir, "cut.json", "[{\"Name\": \"m\", \"RGBPoints\": [0, 0, 0"), "not JSON");
  // A number beyond a double: nlohmann-json's out_of_range, not a parse_error (found by fuzz_transfer_function).
  expectBadFile(write(dir, "overflow.json", "[{\"Name\": \"m\", \"RGBPoints\": [0, 0, 0, 2E222222]}]"), "not JSON");
  expectBadFile(write(dir, "list.json", "[]"), "no colour map");
  expectBadFile(write(dir, "number.json", "42"), "not a list of colour maps");
  expectBadFile(write(dir, "entry.json", "[3]"), "entry 1 is not an object");
  expectBadFile(write(dir, "nopoints.json", map("\"ColorSpace\": \"RGB\"")), "has no \"RGBPoints\"");
  expectBadFile(write(dir, "odd.json", map("\"RGBPoints\": [0, 0, 0, 0, 1, 1, 1]")),
                "holds 7 numbers, not a positive multiple of 4");
  expectBadFile(write(dir, "oddopacity.json", map("\"RGBPoints\": [0, 0, 0, 0], \"Points\": [0, 1, 0.5]")),
                "\"Points\" holds 3 numbers");
  expectBadFile(write(dir, "order.json", map("\"RGBPoints\": [0, 0, 0, 0, 2, 1, 1, 1, 1, 0, 0, 0]")), "sorted by value");
  expectBadFile(write(dir, "orderopacity.json", map("\"RGBPoints\": [0, 0, 0, 0], \"Points\": [1, 0, 0.5, 0, 0, 1, 0.5, 0]")),
                "sorted by value");
  expectBadFile(write(dir, "string.json", map("\"RGBPoints\": [0, \"red\", 0, 0]")), "entry 2 is not a number");
  expectBadFile(write(dir, "range.json", map("\"RGBPoints\": [0, 0, 0, 255]")), "outside [0, 1]");
  expectBadFile(write(dir, "alpha.json", map("\"RGBPoints\": [0, 0, 0, 0], \"Points\": [0, 2, 0.5, 0]")), "outside [0, 1]");
  expectBadFile(write(dir, "midpoint.json", map("\"RGBPoints\": [0, 0, 0, 0], \"Points\": [0, 1, 1.5, 0]")),
                "opacity point 1 (x = 0) has midpoint 1.5 and sharpness 0; each must lie in [0, 1]");
  expectBadFile(write(dir, "sharpness.json", map("\"RGBPoints\": [0, 0, 0, 0], \"Points\": [0, 1, 0.5, 0, 1, 0, 0.5, -2]")),
                "opacity point 2 (x = 1) has midpoint 0.5 and sharpness -2; each must lie in [0, 1]");
  expectBadFile(write(dir, "space.json", map("\"ColorSpace\": \"CMYK\", \"RGBPoints\": [0, 0, 0, 0]")),
                "unknown \"ColorSpace\" \"CMYK\"");
  expectBadFile(write(dir, "notlist.json", map("\"RGBPoints\": 3")), "\"RGBPoints\" is not a list of numbers");
}

TEST(TransferFunctionFile, TextFormatLoads) {
  TempDir dir;
  const std::string path = write(dir, "ramp.txt",
                                 "# value r g b alpha\n"
                                 "\n"
                                 "0    0 0 0   0\n"
                                 "100  1 0.5 0 0.2   # warm\n"
                                 "100  1 1 1 0.0\n"  // a step
                                 "250  1 1 1 1\n");
  const TransferFunction tf = io::readTransferFunctionFile(path);
  EXPECT_FALSE(tf.normalized());
  EXPECT_EQ(tf.colors().size(), 4u);
  EXPECT_DOUBLE_EQ(tf.opacity(50.0), 0.1);
  EXPECT_DOUBLE_EQ(tf.opacity(100.0), 0.0);  // the step's last point
  EXPECT_DOUBLE_EQ(tf.opacity(175.0), 0.5);
  EXPECT_NEAR(tf.color(50.0).g, 0.25, 1e-12);
  EXPECT_FALSE(tf.zeroOpacityOn(90.0, 100.0));
  EXPECT_TRUE(tf.zeroOpacityOn(-5.0, 0.0));
}

TEST(TransferFunctionFile, BadTextFilesAreOneClearLine) {
  TempDir dir;
  expectBadFile(write(dir, "empty.txt", ""), "is empty");
  expectBadFile(write(dir, "comments.txt", "# nothing\n\n"), "holds no control point");
  expectBadFile(write(dir, "four.txt", "0 0 0 0 0\n1 1 1 1\n"), "line 2: expected five finite numbers 'value r g b alpha', found '1 1 1 1'");
  expectBadFile(write(dir, "six.txt", "0 0 0 0 0 0\n"), "line 1: expected five");
  expectBadFile(write(dir, "word.txt", "0 0 0 0 0\n1 red 0 0 1\n"), "line 2");
  expectBadFile(write(dir, "nan.txt", "nan 0 0 0 0\n"), "line 1");
  expectBadFile(write(dir, "order.txt", "# a comment\n1 0 0 0 0\n0 1 1 1 1\n"),
                "line 3: value 0 is below the previous point's 1 (values must not decrease)");
  expectBadFile(write(dir, "range.txt", "0 0 0 0 1.5\n"), "line 1: opacity 1.5 is outside [0, 1]");
  expectBadFile(write(dir, "colour.txt", "\n0 0 -1 0 1\n"), "line 2: colour component -1 is outside [0, 1]");
  expectBadFile(write(dir, "json.txt", "[{\"RGBPoints\": [0, 0, 0, 0]}]\n"), "line 1");
}

TEST(TransferFunctionFile, UnreadableFilesAreInputErrors) {
  TempDir dir;
  EXPECT_THROW(io::readTransferFunctionFile(dir / "missing.json"), InputError);
  try {
    io::readTransferFunctionFile(dir.path.string());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("directory"), std::string::npos) << e.what();
  }
}

TEST(TransferFunctionFile, SpecsArePresetsThenFiles) {
  TempDir dir;
  const TransferFunction preset = io::transferFunctionFromSpec("inferno");
  EXPECT_EQ(preset.name(), "inferno");
  EXPECT_TRUE(preset.normalized());
  const TransferFunction file = io::transferFunctionFromSpec(write(dir, "maps.json", kParaView));
  EXPECT_EQ(file.name(), "Two Tone");
  try {
    io::transferFunctionFromSpec("infern");
    FAIL() << "no error";
  } catch (const ValueError& e) {
    const std::string what = e.what();
    for (const std::string& name : transferFunctionPresetNames()) EXPECT_NE(what.find(name), std::string::npos) << what;
    EXPECT_NE(what.find(".json"), std::string::npos) << what;
  }
}

// `--tf FILE.json:NAME` takes the map NAME of a file of several; a NAME the file lacks is one line
// listing the names it has. A file whose own name holds ".json:" is still the file.
TEST(TransferFunctionFile, SpecNamesAParaViewMap) {
  TempDir dir;
  const std::string path = write(dir, "maps.json", kParaView);
  EXPECT_EQ(io::transferFunctionFromSpec(path + ":No Opacity").name(), "No Opacity");
  EXPECT_EQ(io::transferFunctionFromSpec(path + ":Two Tone").name(), "Two Tone");
  const io::TransferFunctionSpec split = io::splitTransferFunctionSpec(path + ":No Opacity");
  EXPECT_EQ(split.path, path);
  EXPECT_EQ(split.colorMapName, "No Opacity");
  EXPECT_EQ(io::splitTransferFunctionSpec(path).colorMapName, "");
  try {
    io::transferFunctionFromSpec(path + ":Three Tone");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    std::printf("%s\n", what.c_str());
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line";
    for (const char* part : {"Three Tone", "'Two Tone'", "'No Opacity'", "maps.json"})
      EXPECT_NE(what.find(part), std::string::npos) << part << " in: " << what;
  }
  // A text file (its name does not end in .json) that exists under that name is read as it is.
  const std::string odd = write(dir, "odd.json:x", "0 0 0 0 0\n1 1 1 1 1\n");
  EXPECT_EQ(io::splitTransferFunctionSpec(odd).path, odd);
  EXPECT_EQ(io::transferFunctionFromSpec(odd).opacities().size(), 2u);
}

// Every map of a file, in order, for the viewer's colour-map choice.
TEST(TransferFunctionFile, AllMapsOfAFileLoad) {
  TempDir dir;
  const std::vector<TransferFunction> maps = io::readParaViewColorMaps(write(dir, "maps.json", kParaView));
  ASSERT_EQ(maps.size(), 2u);
  EXPECT_EQ(maps[0].name(), "Two Tone");
  EXPECT_EQ(maps[1].name(), "No Opacity");
  EXPECT_THROW(io::readParaViewColorMaps(write(dir, "bad.json", "[{\"Name\": \"a\"}]")), InputError);
}

// What the viewer saves reads back as the same function, bit for bit (values a short decimal format
// would round), through the same reader as --tf; ParaView's shape: RGBPoints and Points.
// ParaView's midpoint and sharpness shape the opacity between points (vtkPiecewiseFunction's curve).
TEST(TransferFunctionFile, ParaViewMidpointAndSharpnessShapeTheOpacity) {
  TempDir dir;
  const std::string path = write(
      dir, "shaped.json",
      R"([{"Name": "m", "RGBPoints": [0, 0, 0, 0, 4, 1, 1, 1], "Points": [0, 0, 0.25, 0.6, 4, 1, 0.5, 0]}])");
  const TransferFunction tf = io::readTransferFunctionFile(path);
  ASSERT_EQ(tf.opacities().size(), 2u);
  EXPECT_EQ(tf.opacities()[0].midpoint, 0.25);
  EXPECT_EQ(tf.opacities()[0].sharpness, 0.6);
  EXPECT_NEAR(tf.opacity(1.0), 0.5, 1e-12);  // a half at the midpoint, a quarter of the way
  EXPECT_EQ(tf.opacity(2.0), paraViewSegmentShape(0.5, 0.25, 0.6));
  EXPECT_LT(tf.opacity(0.2), 0.05) << "sharpness flattens the start";
}

TEST(TransferFunctionFile, SavedParaViewJsonReadsBackBitForBit) {
  TempDir dir;
  const TransferFunction tf({{-1.0 / 3.0, {0.1, 0.2 / 3.0, 1.0}}, {0.7071067811865476, {1.0 / 7.0, 0.5, 0.0}}},
                            {{-1.0 / 3.0, 0.0, 0.3 / 7.0, 2.0 / 3.0}, {0.1234567890123456789, 0.3 / 7.0}, {0.7071067811865476, 1.0}});
  const std::string path = dir / "saved.json";
  io::writeParaViewColorMap(path, tf, "my map", /*overwrite=*/false);
  const TransferFunction back = io::transferFunctionFromSpec(path);
  EXPECT_EQ(back.name(), "my map");
  ASSERT_EQ(back.colors().size(), tf.colors().size());
  ASSERT_EQ(back.opacities().size(), tf.opacities().size());
  for (std::size_t i = 0; i < tf.colors().size(); ++i) {
    EXPECT_EQ(back.colors()[i].x, tf.colors()[i].x);
    EXPECT_EQ(back.colors()[i].rgb, tf.colors()[i].rgb);
  }
  for (std::size_t i = 0; i < tf.opacities().size(); ++i) {
    EXPECT_EQ(back.opacities()[i].x, tf.opacities()[i].x);
    EXPECT_EQ(back.opacities()[i].alpha, tf.opacities()[i].alpha);
    EXPECT_EQ(back.opacities()[i].midpoint, tf.opacities()[i].midpoint);
    EXPECT_EQ(back.opacities()[i].sharpness, tf.opacities()[i].sharpness);
  }
  const std::string text = io::paraViewColorMapJson(tf, "my map");
  EXPECT_NE(text.find("\"RGBPoints\""), std::string::npos);
  EXPECT_NE(text.find("\"Points\""), std::string::npos);
  EXPECT_THROW(io::writeParaViewColorMap(path, tf, "again", /*overwrite=*/false), OutputError) << "exists";
}

}  // namespace
}  // namespace fcc
