// The Cartesian volume readers: real scans from ../shared/data, exact round trips through files written
// here (raw of every type and byte order, NRRD attached/detached raw/gzip, hand-made NIfTI-1), and bad
// input of every kind — each must be one InputError/ValueError line naming the file, never a crash.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "io/DenseVolume.h"
#include "sparse/Error.h"

#ifndef FCC_SHARED_DATA_DIR
#define FCC_SHARED_DATA_DIR ""
#endif

namespace fcc::io {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<uint8_t>;
using ::testing::HasSubstr;

// --- writing test files --------------------------------------------------------------------------------

template <class T>
void store(Bytes& bytes, size_t offset, T value, bool bigEndian) {
  uint8_t raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  if (bigEndian) std::reverse(raw, raw + sizeof(T));  // the test machine is little-endian (x86, arm64)
  if (bytes.size() < offset + sizeof(T)) bytes.resize(offset + sizeof(T));
  std::memcpy(bytes.data() + offset, raw, sizeof(T));
}

template <class T>
Bytes encode(const std::vector<T>& values, bool bigEndian) {
  Bytes bytes;
  for (size_t i = 0; i < values.size(); ++i) store(bytes, i * sizeof(T), values[i], bigEndian);
  return bytes;
}

Bytes concat(Bytes a, const Bytes& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

Bytes textBytes(const std::string& text) { return Bytes(text.begin(), text.end()); }

void writeFile(const fs::path& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

Bytes gzipped(const Bytes& bytes) {
  uLongf size = compressBound(uLong(bytes.size())) + 32;
  Bytes out(size);
  z_stream stream{};
  deflateInit2(&stream, Z_DEFAULT_COMPRESSION, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY);  // +16: gzip wrapper
  stream.next_in = const_cast<uint8_t*>(bytes.data());
  stream.avail_in = uInt(bytes.size());
  stream.next_out = out.data();
  stream.avail_out = uInt(out.size());
  EXPECT_EQ(deflate(&stream, Z_FINISH), Z_STREAM_END);
  out.resize(stream.total_out);
  deflateEnd(&stream);
  return out;
}

// A NIfTI-1 single file as a writer would make it; fields default to a little-endian 3-D volume.
struct NiftiSpec {
  glm::ivec3 dims{2, 3, 4};
  int16_t datatype = 16;  // float32
  bool bigEndian = false;
  float slope = 0.0f, intercept = 0.0f;
  glm::vec3 pixdim{1.0f};
  int16_t qformCode = 0, sformCode = 0;
  glm::vec3 qoffset{0.0f}, sformTranslation{0.0f};
  glm::vec3 srow[3] = {{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}};  // the sform's rotation, by rows
  glm::vec3 quatern{0.0f};  // quatern_b, c, d
  float qfac = 1.0f;        // pixdim[0]
  int16_t rank = 3, dim4 = 1;
  float voxOffset = 352.0f;
  int32_t sizeofHdr = 348;
  std::string magic = std::string("n+1\0", 4);
};

Bytes niftiFile(const NiftiSpec& s, const Bytes& data) {
  Bytes h(352, 0);
  const bool be = s.bigEndian;
  store<int32_t>(h, 0, s.sizeofHdr, be);
  const int16_t dim[8] = {s.rank, int16_t(s.dims.x), int16_t(s.dims.y), int16_t(s.dims.z), s.dim4, 1, 1, 1};
  for (int i = 0; i < 8; ++i) store<int16_t>(h, 40 + 2 * i, dim[i], be);
  store<int16_t>(h, 70, s.datatype, be);
  store<int16_t>(h, 72, 32, be);  // bitpix: deliberately not trusted by the reader
  const float pixdim[4] = {s.qfac, s.pixdim.x, s.pixdim.y, s.pixdim.z};
  for (int i = 0; i < 4; ++i) store<float>(h, 76 + 4 * i, pixdim[i], be);
  store<float>(h, 108, s.voxOffset, be);
  store<float>(h, 112, s.slope, be);
  store<float>(h, 116, s.intercept, be);
  store<int16_t>(h, 252, s.qformCode, be);
  store<int16_t>(h, 254, s.sformCode, be);
  for (int i = 0; i < 3; ++i) store<float>(h, 256 + 4 * i, s.quatern[i], be);
  for (int i = 0; i < 3; ++i) store<float>(h, 268 + 4 * i, s.qoffset[i], be);
  for (int row = 0; row < 3; ++row) {
    for (int column = 0; column < 3; ++column) store<float>(h, 280 + 16 * row + 4 * column, s.srow[row][column], be);
    store<float>(h, 280 + 16 * row + 12, s.sformTranslation[row], be);
  }
  std::memcpy(h.data() + 344, s.magic.data(), 4);
  h.resize(size_t(s.voxOffset), 0);
  return concat(h, data);
}

// --- checking errors -----------------------------------------------------------------------------------

// The message of the E that `read` throws; fails the test if it throws nothing or something else, or if
// the message is not one line.
template <class E = InputError>
std::string errorOf(const std::function<void()>& read) {
  try {
    read();
  } catch (const E& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << "message is not one line: " << message;
    return message;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return {};
  }
  ADD_FAILURE() << "nothing was thrown";
  return {};
}

// Reading garbage may succeed (it happens to be valid) or throw fcc::Error; anything else (another
// exception type, a crash under the sanitizers) is a bug.
void expectSucceedsOrFcc(const std::function<void()>& read, const std::string& what) {
  try {
    read();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << what;
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": non-fcc exception " << e.what();
  }
}

fs::path sharedData(const std::string& name) { return fs::path(FCC_SHARED_DATA_DIR) / name; }

double fractionBelow(const DenseVolume& v, float threshold) {
  return double(std::count_if(v.values.begin(), v.values.end(), [&](float x) { return x < threshold; })) / double(v.values.size());
}

// A unit vector as expected, to rounding.
void expectNear(const glm::dvec3& got, const glm::dvec3& want, const char* what) {
  EXPECT_LT(glm::length(got - want), 1e-6) << what << ": (" << got.x << "," << got.y << "," << got.z << "), want ("
                                           << want.x << "," << want.y << "," << want.z << ")";
}

class ReaderFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("fcc_readers_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string file(const std::string& name, const Bytes& bytes) const {
    writeFile(dir_ / name, bytes);
    return (dir_ / name).string();
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

// --- real data -------------------------------------------------------------------------------------------

TEST(RealData, EngineCtGzip) {
  const fs::path path = sharedData("engine_256x256x128_uint8.raw.gz");
  if (!fs::exists(path)) GTEST_SKIP() << path << " is missing";
  RawLayout layout;
  layout.dims = {256, 256, 128};
  const DenseVolume v = readRaw(path.string(), layout);
  EXPECT_EQ(v.dims, glm::ivec3(256, 256, 128));
  ASSERT_EQ(v.values.size(), size_t(256) * 256 * 128);
  EXPECT_NEAR(fractionBelow(v, 16.0f), 0.83, 0.02);
  EXPECT_GT(*std::max_element(v.values.begin(), v.values.end()), 240.0f);
}

TEST(RealData, BrainsmallDenWithHeader) {
  const fs::path path = sharedData("brainsmall.den");
  if (!fs::exists(path)) GTEST_SKIP() << path << " is missing";
  RawLayout layout;
  layout.dims = {128, 128, 84};
  layout.headerBytes = 62;
  const DenseVolume v = readRaw(path.string(), layout);
  ASSERT_EQ(v.values.size(), size_t(128) * 128 * 84);
  EXPECT_NEAR(fractionBelow(v, 16.0f), 0.79, 0.02);
  EXPECT_EQ(v.spacing, glm::dvec3(1.0));
}

TEST(RealData, Ch2BetterNiftiGzip) {
  const fs::path path = sharedData("ch2better.nii.gz");
  if (!fs::exists(path)) GTEST_SKIP() << path << " is missing";
  const DenseVolume v = readNifti(path.string());
  EXPECT_EQ(v.dims, glm::ivec3(301, 370, 316));
  ASSERT_EQ(v.values.size(), size_t(301) * 370 * 316);
  EXPECT_EQ(v.spacing, glm::dvec3(0.5));
  EXPECT_EQ(v.origin, glm::dvec3(-75.0, -107.0, -69.5));  // sform translation
  // Stored RAS (the sform is 0.5 times the identity): the world's +z is superior, +y anterior.
  ASSERT_TRUE(v.patient.has_value());
  EXPECT_EQ(v.patient->superior, glm::dvec3(0.0, 0.0, 1.0));
  EXPECT_EQ(v.patient->anterior, glm::dvec3(0.0, 1.0, 0.0));
  EXPECT_GT(*std::max_element(v.values.begin(), v.values.end()), 100.0f);
}

// --- DenseVolume, types, formats -------------------------------------------------------------------------

TEST(DenseVolumeLayout, XFastestIndexing) {
  DenseVolume v;
  v.dims = {3, 4, 5};
  v.values.resize(60);
  for (size_t i = 0; i < v.values.size(); ++i) v.values[i] = float(i);
  EXPECT_EQ(v.index(1, 0, 0), 1u);
  EXPECT_EQ(v.index(0, 1, 0), 3u);
  EXPECT_EQ(v.index(0, 0, 1), 12u);
  EXPECT_EQ(v.at(2, 3, 4), 59.0f);
  EXPECT_TRUE(v.contains(2, 3, 4));
  EXPECT_FALSE(v.contains(3, 0, 0));
  EXPECT_FALSE(v.contains(0, -1, 0));
  EXPECT_FALSE(v.contains(0, 0, 5));
}

TEST(ScalarTypes, ParseNamesAndRejectOthers) {
  EXPECT_EQ(parseScalarType("u8"), ScalarType::U8);
  EXPECT_EQ(parseScalarType("i16"), ScalarType::I16);
  EXPECT_EQ(parseScalarType("f64"), ScalarType::F64);
  EXPECT_EQ(scalarTypeSize(ScalarType::U32), 4u);
  EXPECT_STREQ(scalarTypeName(ScalarType::I8), "i8");
  const std::string message = errorOf<ValueError>([] { parseScalarType("u12"); });
  EXPECT_THAT(message, HasSubstr("u12"));
  EXPECT_THAT(message, HasSubstr("u8, i8, u16, i16, u32, i32, f32, f64"));
}

TEST(Formats, ByExtension) {
  EXPECT_EQ(detectFormat("a/sphere.vdb"), Format::Vdb);
  EXPECT_EQ(detectFormat("x.nrrd"), Format::Nrrd);
  EXPECT_EQ(detectFormat("x.NHDR"), Format::Nrrd);
  EXPECT_EQ(detectFormat("brain.nii"), Format::Nifti);
  EXPECT_EQ(detectFormat("brain.nii.gz"), Format::Nifti);
  EXPECT_EQ(detectFormat("engine.raw.gz"), Format::Raw);
  EXPECT_EQ(detectFormat("brainsmall.den"), Format::Raw);
  EXPECT_EQ(detectFormat("noextension"), Format::Raw);
}

// --- raw round trips -------------------------------------------------------------------------------------

class RawRoundTrip : public ReaderFiles {
 protected:
  // Writes `values` as a 3x2x2 raw volume of `type` in both byte orders, plain and gzip, and reads them back.
  template <class T>
  void check(ScalarType type, const std::vector<T>& values) {
    ASSERT_EQ(values.size(), 12u);
    for (const bool bigEndian : {false, true}) {
      for (const bool gzip : {false, true}) {
        const Bytes header = textBytes("HDR");
        const Bytes bytes = concat(header, encode(values, bigEndian));
        const std::string name = std::string(scalarTypeName(type)) + (bigEndian ? "_be" : "_le") + (gzip ? ".raw.gz" : ".raw");
        RawLayout layout;
        layout.dims = {3, 2, 2};
        layout.type = type;
        layout.bigEndian = bigEndian;
        layout.spacing = {0.5, 1.0, 2.0};
        layout.headerBytes = header.size();
        const DenseVolume v = readRaw(file(name, gzip ? gzipped(bytes) : bytes), layout);
        ASSERT_EQ(v.values.size(), values.size()) << name;
        for (size_t i = 0; i < values.size(); ++i) EXPECT_EQ(v.values[i], static_cast<float>(values[i])) << name << " #" << i;
        EXPECT_EQ(v.at(2, 1, 1), static_cast<float>(values[11])) << name;
        EXPECT_EQ(v.spacing, layout.spacing);
        EXPECT_EQ(v.origin, glm::dvec3(0.0));
      }
    }
  }
};

TEST_F(RawRoundTrip, EveryTypeBothEndians) {
  check<uint8_t>(ScalarType::U8, {0, 1, 2, 127, 128, 200, 255, 3, 4, 5, 6, 7});
  check<int8_t>(ScalarType::I8, {-128, -1, 0, 1, 127, -50, 50, 2, 3, 4, 5, 6});
  check<uint16_t>(ScalarType::U16, {0, 1, 0x0102, 0x8000, 65535, 300, 4096, 7, 8, 9, 10, 11});
  check<int16_t>(ScalarType::I16, {-32768, -2, 0x1234, 32767, 0, -300, 1, 2, 3, 4, 5, 6});
  check<uint32_t>(ScalarType::U32, {0, 1, 0x01020304, 0xffffffffu, 16777216, 7, 8, 9, 10, 11, 12, 13});
  check<int32_t>(ScalarType::I32, {std::numeric_limits<int32_t>::min(), -1, 0x01020304, std::numeric_limits<int32_t>::max(),
                                   -16777216, 0, 1, 2, 3, 4, 5, 6});
  check<float>(ScalarType::F32, {0.0f, -0.0f, 1.5f, -2.25f, 1e-30f, 3.4e38f, std::numeric_limits<float>::infinity(), 7.0f,
                                 0.1f, 1e10f, -1e-5f, 42.0f});
  check<double>(ScalarType::F64, {0.0, -1.0, 0.125, 1e100, -1e-300, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 0.1});
}

TEST_F(ReaderFiles, RawGzipDetectedByMagicNotName) {
  const std::vector<uint16_t> values = {1, 2, 3, 4, 5, 6, 7, 8};
  RawLayout layout;
  layout.dims = {2, 2, 2};
  layout.type = ScalarType::U16;
  const DenseVolume v = readRaw(file("volume.bin", gzipped(encode(values, false))), layout);
  EXPECT_EQ(v.values, std::vector<float>({1, 2, 3, 4, 5, 6, 7, 8}));
}

TEST_F(ReaderFiles, RawOfExactSizeStartingWithGzipMagicIsRaw) {
  // 0x8b1f as little-endian u16 is the bytes 1f 8b; then 0x0008 gives the third magic byte 08.
  const std::vector<uint16_t> values = {0x8b1f, 0x0008, 3, 4, 5, 6, 7, 8};
  RawLayout layout;
  layout.dims = {2, 2, 2};
  layout.type = ScalarType::U16;
  const DenseVolume v = readRaw(file("magic.raw", encode(values, false)), layout);
  EXPECT_EQ(v.values[0], float(0x8b1f));
  EXPECT_EQ(v.values[1], 8.0f);
}

// --- NRRD round trips ------------------------------------------------------------------------------------

const std::vector<int16_t> kNrrdValues = {-300, 1, 2, 3, 400, 5, 6, 7, 8, 9, 10, -11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23};

std::string nrrdHeader(const std::string& encoding, const std::string& extra) {
  return "NRRD0004\n# written by test_readers\ntype: short\ndimension: 3\nsizes: 4 3 2\nendian: big\nencoding: " + encoding +
         "\nspacings: 0.5 0.25 2\nspace origin: (1.5,-2,3)\nunits:=mm\n" + extra;
}

void expectNrrdVolume(const DenseVolume& v, glm::dvec3 spacing = {0.5, 0.25, 2.0}) {
  EXPECT_EQ(v.dims, glm::ivec3(4, 3, 2));
  ASSERT_EQ(v.values.size(), kNrrdValues.size());
  for (size_t i = 0; i < kNrrdValues.size(); ++i) EXPECT_EQ(v.values[i], float(kNrrdValues[i]));
  EXPECT_EQ(v.spacing, spacing);
  EXPECT_EQ(v.origin, glm::dvec3(1.5, -2.0, 3.0));
}

TEST_F(ReaderFiles, NrrdAttachedRaw) {
  expectNrrdVolume(readNrrd(file("a.nrrd", concat(textBytes(nrrdHeader("raw", "\n")), encode(kNrrdValues, true)))));
}

TEST_F(ReaderFiles, NrrdAttachedGzip) {
  expectNrrdVolume(readNrrd(file("a.nrrd", concat(textBytes(nrrdHeader("gzip", "\n")), gzipped(encode(kNrrdValues, true))))));
}

TEST_F(ReaderFiles, NrrdDetachedRawAndGz) {
  file("data.raw", encode(kNrrdValues, true));
  expectNrrdVolume(readNrrd(file("d.nhdr", textBytes(nrrdHeader("raw", "data file: data.raw\n")))));
  fs::create_directories(dir_ / "sub");
  file("sub/data.raw.gz", gzipped(encode(kNrrdValues, true)));
  expectNrrdVolume(readNrrd(file("g.nhdr", textBytes(nrrdHeader("gz", "data file: ./sub/data.raw.gz\n")))));
}

TEST_F(ReaderFiles, NrrdSpaceDirectionsCrlfAndSkips) {
  // CRLF lines, axis-aligned directions (a negative one: its magnitude is the spacing), "line skip" and
  // "byte skip" before the data, and "byte skip: -1" (the data is the file's last bytes).
  const std::string header =
      "NRRD0005\r\ntype: int16\r\ndimension: 3\r\nspace: left-posterior-superior\r\nsizes: 4 3 2\r\n"
      "space directions: (-0.5,0,0) (0, 0.25, 0) (0,0,2)\r\nkinds: domain domain domain\r\nendian: big\r\n"
      "encoding: raw\r\nspace origin: (1.5,-2,3)\r\n";
  file("skipped.raw", concat(textBytes("line one\nline two\nXYZ"), encode(kNrrdValues, true)));
  expectNrrdVolume(readNrrd(file("s.nhdr", textBytes(header + "data file: skipped.raw\r\nline skip: 2\r\nbyte skip: 3\r\n"))));
  expectNrrdVolume(readNrrd(file("t.nhdr", textBytes(header + "data file: skipped.raw\r\nbyte skip: -1\r\n"))));
}

// An anatomical space gives the patient's axes, with the directions' signs (the world keeps every index
// axis running forward); other spaces and none give none.
TEST_F(ReaderFiles, NrrdPatientAxesFromAnatomicalSpace) {
  auto read = [&](const std::string& fields) {
    const std::string header = "NRRD0004\ntype: short\ndimension: 3\nsizes: 4 3 2\nendian: big\nencoding: raw\n" + fields + "\n";
    return readNrrd(file("p.nrrd", concat(textBytes(header), encode(kNrrdValues, true))));
  };
  EXPECT_FALSE(read("spacings: 1 1 1\n").patient.has_value());
  EXPECT_FALSE(read("space: scanner-xyz\nspace directions: (1,0,0) (0,1,0) (0,0,1)\n").patient.has_value());
  struct Case {
    std::string fields;
    glm::dvec3 superior, anterior;
  };
  const Case cases[] = {
      {"space: RAS\nspace directions: (1,0,0) (0,1,0) (0,0,1)\n", {0, 0, 1}, {0, 1, 0}},
      {"space: right-anterior-superior\nspace directions: (1,0,0) (0,-2,0) (0,0,-1)\n", {0, 0, -1}, {0, -1, 0}},
      {"space: Left-Anterior-Superior\nspace directions: (-1,0,0) (0,1,0) (0,0,1)\n", {0, 0, 1}, {0, 1, 0}},
      {"space: left-posterior-superior\nspace directions: (0.5,0,0) (0,0.5,0) (0,0,0.5)\n", {0, 0, 1}, {0, -1, 0}},
      {"space: LPS\nspace directions: (-0.5,0,0) (0,-0.5,0) (0,0,0.5)\n", {0, 0, 1}, {0, 1, 0}},
      {"space: lps\nspacings: 1 1 1\n", {0, 0, 1}, {0, -1, 0}},
  };
  for (const Case& c : cases) {
    const DenseVolume v = read(c.fields);
    ASSERT_TRUE(v.patient.has_value()) << c.fields;
    expectNear(v.patient->superior, c.superior, c.fields.c_str());
    expectNear(v.patient->anterior, c.anterior, c.fields.c_str());
  }
}

TEST_F(ReaderFiles, NrrdTypeSpellingsAndUnsigned) {
  const std::vector<uint8_t> values(24, 7);
  for (const char* type : {"uchar", "unsigned char", "uint8", "uint8_t"}) {
    const std::string header = std::string("NRRD0004\ntype: ") + type + "\ndimension: 3\nsizes: 4 3 2\nencoding: raw\n\n";
    const DenseVolume v = readNrrd(file("u.nrrd", concat(textBytes(header), values)));
    EXPECT_EQ(v.values, std::vector<float>(24, 7.0f)) << type;
    EXPECT_EQ(v.spacing, glm::dvec3(1.0)) << type;
  }
  const std::vector<float> floats = {0.5f, -1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f};
  const std::string header = "NRRD0004\ntype: float\ndimension: 3\nsizes: 2 2 2\nendian: little\nencoding: raw\nspacings: nan 3 4\n\n";
  const DenseVolume v = readNrrd(file("f.nrrd", concat(textBytes(header), encode(floats, false))));
  EXPECT_EQ(v.values[1], -1.0f);
  EXPECT_EQ(v.spacing, glm::dvec3(1.0, 3.0, 4.0));
}

// --- NIfTI round trips -----------------------------------------------------------------------------------

TEST_F(ReaderFiles, NiftiFloatWithSform) {
  NiftiSpec spec;
  spec.pixdim = {0.5f, -0.75f, 2.0f};
  spec.sformCode = 2;
  spec.sformTranslation = {-10.0f, 20.0f, 30.5f};
  spec.qformCode = 1;
  spec.qoffset = {1.0f, 2.0f, 3.0f};
  std::vector<float> values(24);
  for (size_t i = 0; i < values.size(); ++i) values[i] = float(i) * 0.5f - 3.0f;
  const DenseVolume v = readNifti(file("f.nii", niftiFile(spec, encode(values, false))));
  EXPECT_EQ(v.dims, glm::ivec3(2, 3, 4));
  EXPECT_EQ(v.values, values);
  EXPECT_EQ(v.spacing, glm::dvec3(0.5, 0.75, 2.0));
  EXPECT_EQ(v.origin, glm::dvec3(-10.0, 20.0, 30.5));  // sform wins over qform
}

// The patient's axes in the reader's world frame (the index axes, scaled): from the sform, else the
// qform, else none; the world frame itself stays as it was (origin, spacing).
TEST_F(ReaderFiles, NiftiPatientAxesFromSformElseQform) {
  const std::vector<float> values(24, 1.0f);
  auto read = [&](const NiftiSpec& spec) { return readNifti(file("p.nii", niftiFile(spec, encode(values, false)))); };
  NiftiSpec spec;
  EXPECT_FALSE(read(spec).patient.has_value()) << "both codes 0: no orientation";

  // Stored LPS-like (i runs right to left, j anterior to posterior), anisotropic voxels.
  spec.pixdim = {0.5f, 2.0f, 3.0f};
  spec.sformCode = 1;
  spec.srow[0] = {-0.5f, 0.0f, 0.0f};
  spec.srow[1] = {0.0f, -2.0f, 0.0f};
  spec.srow[2] = {0.0f, 0.0f, 3.0f};
  DenseVolume v = read(spec);
  ASSERT_TRUE(v.patient.has_value());
  expectNear(v.patient->superior, {0, 0, 1}, "superior");
  expectNear(v.patient->anterior, {0, -1, 0}, "anterior");
  EXPECT_EQ(v.spacing, glm::dvec3(0.5, 2.0, 3.0));

  // Axes permuted (sagittal storage: i posterior to anterior, j inferior to superior, k left to right).
  spec.srow[0] = {0.0f, 0.0f, 3.0f};
  spec.srow[1] = {0.5f, 0.0f, 0.0f};
  spec.srow[2] = {0.0f, 2.0f, 0.0f};
  v = read(spec);
  ASSERT_TRUE(v.patient.has_value());
  expectNear(v.patient->superior, {0, 1, 0}, "superior");
  expectNear(v.patient->anterior, {1, 0, 0}, "anterior");

  // A singular sform gives none rather than a guess.
  spec.srow[2] = {0.0f, 0.0f, 0.0f};
  EXPECT_FALSE(read(spec).patient.has_value());

  // The qform: 90 degrees about z (quaternion (cos 45, 0, 0, sin 45)): i runs anterior, j left; qfac -1
  // flips k (inferior).
  spec = NiftiSpec();
  spec.qformCode = 1;
  spec.quatern = {0.0f, 0.0f, float(std::sqrt(0.5))};
  spec.qfac = -1.0f;
  v = read(spec);
  ASSERT_TRUE(v.patient.has_value());
  expectNear(v.patient->superior, {0, 0, -1}, "superior");
  expectNear(v.patient->anterior, {1, 0, 0}, "anterior");
  // A zero sform code leaves the qform in charge, whatever the srows say.
  spec.srow[0] = {0.0f, 0.0f, 0.0f};
  EXPECT_TRUE(read(spec).patient.has_value());
}

TEST_F(ReaderFiles, NiftiScaledU8QformGzip) {
  NiftiSpec spec;
  spec.datatype = 2;
  spec.slope = 2.0f;
  spec.intercept = -1.0f;
  spec.qformCode = 1;
  spec.qoffset = {4.0f, 5.0f, 6.0f};
  spec.rank = 4;  // a 3-D volume stored as one time point
  std::vector<uint8_t> values(24);
  for (size_t i = 0; i < values.size(); ++i) values[i] = uint8_t(i * 10);
  const DenseVolume v = readNifti(file("s.nii.gz", gzipped(niftiFile(spec, values))));
  for (size_t i = 0; i < values.size(); ++i) EXPECT_EQ(v.values[i], float(values[i]) * 2.0f - 1.0f);
  EXPECT_EQ(v.origin, glm::dvec3(4.0, 5.0, 6.0));
}

TEST_F(ReaderFiles, NiftiSwappedHeaderAndExtensions) {
  NiftiSpec spec;
  spec.bigEndian = true;
  spec.datatype = 4;  // int16
  spec.pixdim = {1.5f, 1.5f, 3.0f};
  spec.voxOffset = 400.0f;  // room for an extension block, skipped
  std::vector<int16_t> values(24);
  for (size_t i = 0; i < values.size(); ++i) values[i] = int16_t(i * 1000 - 12000);
  const DenseVolume v = readNifti(file("b.nii", niftiFile(spec, encode(values, true))));
  for (size_t i = 0; i < values.size(); ++i) EXPECT_EQ(v.values[i], float(values[i]));
  EXPECT_EQ(v.spacing, glm::dvec3(1.5, 1.5, 3.0));
  EXPECT_EQ(v.origin, glm::dvec3(0.0));
}

TEST_F(ReaderFiles, NiftiEveryDatatype) {
  struct Case {
    int16_t code;
    Bytes data;
  };
  const std::vector<double> expected = {0, 1, 2, 3, 4, 5, 6, 7};
  std::vector<uint32_t> u(expected.begin(), expected.end());
  const Case cases[] = {
      {2, encode(std::vector<uint8_t>(u.begin(), u.end()), false)},  {256, encode(std::vector<int8_t>(u.begin(), u.end()), false)},
      {512, encode(std::vector<uint16_t>(u.begin(), u.end()), false)}, {4, encode(std::vector<int16_t>(u.begin(), u.end()), false)},
      {768, encode(u, false)},                                       {8, encode(std::vector<int32_t>(u.begin(), u.end()), false)},
      {16, encode(std::vector<float>(u.begin(), u.end()), false)},     {64, encode(expected, false)},
  };
  for (const Case& c : cases) {
    NiftiSpec spec;
    spec.dims = {2, 2, 2};
    spec.datatype = c.code;
    const DenseVolume v = readNifti(file("t.nii", niftiFile(spec, c.data)));
    EXPECT_EQ(v.values, std::vector<float>(expected.begin(), expected.end())) << "datatype " << c.code;
  }
}

// --- bad input -------------------------------------------------------------------------------------------

TEST_F(ReaderFiles, RawSizeMismatchNamesLayout) {
  RawLayout layout;
  layout.dims = {4, 4, 2};
  const std::string short_ = file("engine.raw", Bytes(30));
  EXPECT_THAT(errorOf([&] { readRaw(short_, layout); }),
              HasSubstr("engine.raw: file holds 30 bytes but --dims 4,4,2 --type u8 needs 32 (+0 header bytes)"));
  const std::string long_ = file("long.raw", Bytes(40));
  EXPECT_THAT(errorOf([&] { readRaw(long_, layout); }), HasSubstr("long.raw: file holds 40 bytes"));
  const std::string gz = file("short.raw.gz", gzipped(Bytes(31)));
  EXPECT_THAT(errorOf([&] { readRaw(gz, layout); }), HasSubstr("short.raw.gz: file holds 31 bytes once decompressed"));
  const std::string gzLong = file("long.raw.gz", gzipped(Bytes(100000)));
  EXPECT_THAT(errorOf([&] { readRaw(gzLong, layout); }), HasSubstr("holds 100000 bytes once decompressed"));
}

TEST_F(ReaderFiles, RawBadDimsAndHugeDims) {
  const std::string path = file("dims.raw", Bytes(8));
  RawLayout layout;
  layout.dims = {0, 2, 2};
  EXPECT_THAT(errorOf([&] { readRaw(path, layout); }), HasSubstr("dims.raw: dims 0,2,2 are invalid"));
  layout.dims = {2, -2, 2};
  EXPECT_THAT(errorOf([&] { readRaw(path, layout); }), HasSubstr("dims.raw"));
  layout.dims = {100000, 100000, 100000};
  EXPECT_THAT(errorOf([&] { readRaw(path, layout); }), HasSubstr("2^34"));
  // Under the voxel limit but far more than the file holds: refused by size before any allocation.
  layout.dims = {2048, 2048, 2048};
  layout.type = ScalarType::F64;
  EXPECT_THAT(errorOf([&] { readRaw(path, layout); }), HasSubstr("file holds 8 bytes"));
  const std::string gz = file("dims.raw.gz", gzipped(Bytes(8)));
  EXPECT_THAT(errorOf([&] { readRaw(gz, layout); }), HasSubstr("file holds 8 bytes once decompressed"));
  layout.dims = {2, 2, 2};
  layout.type = ScalarType::U8;
  layout.spacing = {1.0, 0.0, 1.0};
  EXPECT_THAT(errorOf<ValueError>([&] { readRaw(path, layout); }), HasSubstr("dims.raw"));
}

TEST_F(ReaderFiles, MissingUnreadableAndMisnamedFiles) {
  RawLayout layout;
  layout.dims = {2, 2, 2};
  EXPECT_THAT(errorOf([&] { readRaw(path("absent.raw"), layout); }), HasSubstr("absent.raw: cannot open: No such file or directory"));
  EXPECT_THAT(errorOf([&] { readNrrd(path("absent.nrrd")); }), HasSubstr("absent.nrrd: cannot open"));
  EXPECT_THAT(errorOf([&] { readNifti(path("absent.nii")); }), HasSubstr("absent.nii: cannot open"));
  fs::create_directories(dir_ / "folder.nii");
  EXPECT_THAT(errorOf([&] { readNifti(path("folder.nii")); }), HasSubstr("folder.nii: cannot open: Is a directory"));
  const std::string notGzip = file("plain.raw.gz", Bytes(8, 1));
  EXPECT_THAT(errorOf([&] { readRaw(notGzip, layout); }), HasSubstr("plain.raw.gz: expected gzip data"));
}

TEST_F(ReaderFiles, CorruptAndTruncatedGzip) {
  Bytes data(50000);
  std::mt19937 random(7);
  for (uint8_t& b : data) b = uint8_t(random() % 16);  // compressible, so the stream has real structure
  RawLayout layout;
  layout.dims = {50, 50, 20};
  const Bytes gz = gzipped(data);
  ASSERT_EQ(readRaw(file("ok.raw.gz", gz), layout).values.size(), data.size());

  const std::string truncated = file("cut.raw.gz", Bytes(gz.begin(), gz.begin() + gz.size() / 2));
  EXPECT_THAT(errorOf([&] { readRaw(truncated, layout); }), HasSubstr("cut.raw.gz: truncated gzip data"));
  const std::string noTrailer = file("trailer.raw.gz", Bytes(gz.begin(), gz.end() - 4));
  EXPECT_THAT(errorOf([&] { readRaw(noTrailer, layout); }), HasSubstr("trailer.raw.gz: truncated gzip data"));
  Bytes flipped = gz;
  for (size_t i = 40; i < 60; ++i) flipped[i] ^= 0x5a;
  const std::string corrupt = file("bad.raw.gz", flipped);
  EXPECT_THAT(errorOf([&] { readRaw(corrupt, layout); }), HasSubstr("bad.raw.gz: "));
  Bytes badCrc = gz;
  badCrc[badCrc.size() - 6] ^= 1;
  const std::string crc = file("crc.raw.gz", badCrc);
  EXPECT_THAT(errorOf([&] { readRaw(crc, layout); }), HasSubstr("crc.raw.gz: corrupt gzip data"));
}

TEST_F(ReaderFiles, NrrdBadHeaders) {
  const Bytes data = encode(kNrrdValues, true);
  auto nrrd = [&](const std::string& name, const std::string& header) { return file(name, concat(textBytes(header), data)); };
  const std::string magic = nrrd("magic.nrrd", "NRRX0004\ntype: short\n\n");
  EXPECT_THAT(errorOf([&] { readNrrd(magic); }), HasSubstr("magic.nrrd: not a NRRD file"));
  EXPECT_THAT(errorOf([&] { readNrrd(magic); }), HasSubstr("NRRD000"));
  const std::string encoding = nrrd("enc.nrrd", nrrdHeader("bzip2", "\n"));
  EXPECT_THAT(errorOf([&] { readNrrd(encoding); }), HasSubstr("enc.nrrd: line 7: encoding \"bzip2\" is not supported; valid: raw, gzip (gz)"));
  std::string twoD = nrrdHeader("raw", "\n");
  twoD.replace(twoD.find("dimension: 3"), 12, "dimension: 2");
  EXPECT_THAT(errorOf([&] { readNrrd(nrrd("dim.nrrd", twoD)); }), HasSubstr("dim.nrrd: line 4: dimension \"2\" is not supported"));
  std::string type = nrrdHeader("raw", "\n");
  type.replace(type.find("short"), 5, "int64");
  EXPECT_THAT(errorOf([&] { readNrrd(nrrd("type.nrrd", type)); }), HasSubstr("type.nrrd: line 3: type \"int64\" is not supported; valid:"));
  EXPECT_THAT(errorOf([&] { readNrrd(nrrd("missing.nrrd", "NRRD0004\ndimension: 3\nsizes: 4 3 2\n\n")); }),
              HasSubstr("missing.nrrd: missing required field \"type:\""));
  EXPECT_THAT(errorOf([&] { readNrrd(nrrd("endian.nrrd", "NRRD0004\ntype: short\ndimension: 3\nsizes: 4 3 2\nencoding: raw\n\n")); }),
              HasSubstr("endian.nrrd: missing required field \"endian:\""));
  EXPECT_THAT(errorOf([&] { readNrrd(nrrd("oblique.nrrd", nrrdHeader("raw", "space directions: (1,1,0) (0,1,0) (0,0,1)\n\n"))); }),
              HasSubstr("oblique.nrrd: line 11: space directions are not axis-aligned"));
  EXPECT_THAT(errorOf([&] { readNrrd(nrrd("sizes.nrrd", "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 4 0 2\nencoding: raw\n\n")); }),
              HasSubstr("sizes.nrrd: line 4: size \"0\""));
  EXPECT_THAT(errorOf([&] { readNrrd(nrrd("garbage.nrrd", "NRRD0004\ntype: uchar\nthis is no field\n\n")); }),
              HasSubstr("garbage.nrrd: line 3: expected \"field: value\""));
  EXPECT_THAT(errorOf([&] { readNrrd(file("list.nhdr", textBytes(nrrdHeader("raw", "data file: LIST\na.raw\n")))); }),
              HasSubstr("list.nhdr: line 11: data file \"LIST\" is not supported"));
  EXPECT_THAT(errorOf([&] { readNrrd(file("nodata.nhdr", textBytes(nrrdHeader("raw", "data file: absent.raw\n")))); }),
              HasSubstr("absent.raw: cannot open: No such file or directory"));
  // A device as the data file would be read up to the voxel limit (fuzzing review): refused in one line.
  EXPECT_THAT(errorOf([&] { readNrrd(file("device.nhdr", textBytes(nrrdHeader("raw", "data file: /dev/zero\n")))); }),
              HasSubstr("device.nhdr: line 11: data file \"/dev/zero\" is not a regular file"));
  EXPECT_THAT(errorOf([&] { readNrrd(file("noblank.nrrd", textBytes(nrrdHeader("raw", "")))); }),
              HasSubstr("noblank.nrrd: header has no \"data file:\" field and no blank line"));
  const std::string shortData = file("short.nrrd", concat(textBytes(nrrdHeader("raw", "\n")), Bytes(data.begin(), data.end() - 1)));
  EXPECT_THAT(errorOf([&] { readNrrd(shortData); }), HasSubstr("short.nrrd: data holds 47 bytes but sizes 4,3,2 of type i16 need 48"));
  const std::string shortGz =
      file("shortgz.nrrd", concat(textBytes(nrrdHeader("gzip", "\n")), gzipped(Bytes(data.begin(), data.end() - 2))));
  EXPECT_THAT(errorOf([&] { readNrrd(shortGz); }), HasSubstr("shortgz.nrrd: data holds 46 bytes once decompressed"));
}

TEST_F(ReaderFiles, NiftiBadHeaders) {
  const Bytes data(24 * 4, 0);
  NiftiSpec spec;
  spec.sizeofHdr = 1234;
  EXPECT_THAT(errorOf([&] { readNifti(file("size.nii", niftiFile(spec, data))); }),
              HasSubstr("size.nii: not a NIfTI-1 file: sizeof_hdr is 1234, must be 348"));
  spec = {};
  spec.magic = std::string("n+2\0", 4);
  EXPECT_THAT(errorOf([&] { readNifti(file("magic.nii", niftiFile(spec, data))); }), HasSubstr("magic.nii: bad NIfTI-1 magic"));
  spec.magic = std::string("ni1\0", 4);
  EXPECT_THAT(errorOf([&] { readNifti(file("pair.nii", niftiFile(spec, data))); }), HasSubstr("pair.nii: two-file NIfTI-1"));
  spec = {};
  spec.datatype = 128;
  EXPECT_THAT(errorOf([&] { readNifti(file("rgb.nii", niftiFile(spec, data))); }),
              HasSubstr("rgb.nii: datatype 128 (rgb24) is not supported; supported: 2 (uint8)"));
  spec = {};
  spec.rank = 2;
  EXPECT_THAT(errorOf([&] { readNifti(file("rank.nii", niftiFile(spec, data))); }), HasSubstr("rank.nii: dim[0] is 2"));
  spec = {};
  spec.rank = 4;
  spec.dim4 = 3;
  EXPECT_THAT(errorOf([&] { readNifti(file("time.nii", niftiFile(spec, data))); }), HasSubstr("time.nii: dim[4] is 3"));
  spec = {};
  spec.dims = {2, 0, 4};
  EXPECT_THAT(errorOf([&] { readNifti(file("zero.nii", niftiFile(spec, data))); }), HasSubstr("zero.nii: dims 2,0,4 are invalid"));
  Bytes lowOffset = niftiFile(NiftiSpec{}, data);
  store<float>(lowOffset, 108, 300.0f, false);
  EXPECT_THAT(errorOf([&] { readNifti(file("low.nii", lowOffset)); }), HasSubstr("low.nii: vox_offset 300 is invalid"));
  const Bytes whole = niftiFile(NiftiSpec{}, data);
  EXPECT_THAT(errorOf([&] { readNifti(file("short.nii", Bytes(whole.begin(), whole.end() - 1))); }),
              HasSubstr("short.nii: file holds 447 bytes but dims 2,3,4 of datatype f32 need 96 from vox_offset 352"));
  EXPECT_THAT(errorOf([&] { readNifti(file("head.nii", Bytes(whole.begin(), whole.begin() + 200))); }),
              HasSubstr("head.nii: truncated NIfTI-1 header"));
  EXPECT_THAT(errorOf([&] { readNifti(file("shortgz.nii.gz", gzipped(Bytes(whole.begin(), whole.end() - 5)))); }),
              HasSubstr("shortgz.nii.gz: file holds 443 bytes once decompressed"));
}

TEST_F(ReaderFiles, EmptyFiles) {
  const std::string empty = file("empty", {});
  RawLayout layout;
  layout.dims = {1, 1, 1};
  EXPECT_THAT(errorOf([&] { readRaw(empty, layout); }), HasSubstr("empty: file holds 0 bytes"));
  EXPECT_THAT(errorOf([&] { readNrrd(empty); }), HasSubstr("empty: not a NRRD file"));
  EXPECT_THAT(errorOf([&] { readNifti(empty); }), HasSubstr("empty: not a NIfTI-1 file"));
  const std::string emptyGz = file("empty.raw.gz", {});
  EXPECT_THAT(errorOf([&] { readRaw(emptyGz, layout); }), HasSubstr("empty.raw.gz: expected gzip data"));
}

// --- garbage never crashes -------------------------------------------------------------------------------

TEST_F(ReaderFiles, RandomBytesAreRefused) {
  std::mt19937 random(1);
  RawLayout layout;
  layout.dims = {32, 32, 32};  // more bytes than any trial's file, so raw reading can never succeed
  for (int trial = 0; trial < 20; ++trial) {
    Bytes bytes(1 + random() % 5000);
    for (uint8_t& b : bytes) b = uint8_t(random());
    if (trial % 4 == 0) bytes.insert(bytes.begin(), {0x1f, 0x8b, 0x08});  // gzip magic, garbage stream
    if (trial % 4 == 1) bytes.insert(bytes.begin(), {'N', 'R', 'R', 'D', '0', '0', '0', '4', '\n'});
    if (trial % 4 == 2) store<int32_t>(bytes, 0, 348, false);
    const std::string path = file("random", bytes);
    EXPECT_THAT(errorOf([&] { readRaw(path, layout); }), HasSubstr("random"));
    EXPECT_THAT(errorOf([&] { readNrrd(path); }), HasSubstr("random"));
    EXPECT_THAT(errorOf([&] { readNifti(path); }), HasSubstr("random"));
  }
}

TEST_F(ReaderFiles, TruncatedAnywhereIsRefused) {
  NiftiSpec spec;
  spec.datatype = 512;
  const Bytes nifti = niftiFile(spec, encode(std::vector<uint16_t>(24, 9), false));
  const Bytes niftiGz = gzipped(nifti);
  const Bytes nrrd = concat(textBytes(nrrdHeader("raw", "\n")), encode(kNrrdValues, true));
  const Bytes nrrdGz = concat(textBytes(nrrdHeader("gzip", "\n")), gzipped(encode(kNrrdValues, true)));
  for (size_t size = 0; size < nifti.size(); ++size)
    EXPECT_THAT(errorOf([&] { readNifti(file("cut.nii", Bytes(nifti.begin(), nifti.begin() + size))); }), HasSubstr("cut.nii")) << size;
  for (size_t size = 0; size < niftiGz.size(); ++size)
    EXPECT_THAT(errorOf([&] { readNifti(file("cut.nii.gz", Bytes(niftiGz.begin(), niftiGz.begin() + size))); }), HasSubstr("cut.nii.gz"))
        << size;
  for (size_t size = 0; size < nrrd.size(); ++size)
    EXPECT_THAT(errorOf([&] { readNrrd(file("cut.nrrd", Bytes(nrrd.begin(), nrrd.begin() + size))); }), HasSubstr("cut.nrrd")) << size;
  for (size_t size = 0; size < nrrdGz.size(); ++size)
    EXPECT_THAT(errorOf([&] { readNrrd(file("cutgz.nrrd", Bytes(nrrdGz.begin(), nrrdGz.begin() + size))); }), HasSubstr("cutgz.nrrd"))
        << size;
}

TEST_F(ReaderFiles, MutatedHeadersNeverCrash) {
  std::mt19937 random(3);
  const Bytes nifti = niftiFile(NiftiSpec{}, encode(std::vector<float>(24, 1.0f), false));
  const Bytes nrrd = concat(textBytes(nrrdHeader("raw", "\n")), encode(kNrrdValues, true));
  const size_t nrrdHeaderSize = nrrdHeader("raw", "\n").size();
  for (int trial = 0; trial < 300; ++trial) {
    Bytes a = nifti;
    for (int flips = 1 + random() % 4; flips > 0; --flips) a[random() % 352] = uint8_t(random());
    const std::string niftiPath = file("mutated.nii", a);
    expectSucceedsOrFcc([&] { readNifti(niftiPath); }, "nifti trial " + std::to_string(trial));
    Bytes b = nrrd;
    for (int flips = 1 + random() % 3; flips > 0; --flips) b[random() % nrrdHeaderSize] = uint8_t(random() % 128);
    const std::string nrrdPath = file("mutated.nrrd", b);
    expectSucceedsOrFcc([&] { readNrrd(nrrdPath); }, "nrrd trial " + std::to_string(trial));
  }
}

}  // namespace
}  // namespace fcc::io
