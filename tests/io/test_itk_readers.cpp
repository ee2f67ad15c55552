// DICOM series and MetaImage, read through ITK (io/ItkReader.cpp). The test writes its own inputs with
// another library than the one that reads them: DICOM slices with GDCM's writer (CT images with
// rescale slope and intercept, an oblique orientation, file names in shuffled order), MetaImage by hand
// (it is a text header and raw bytes).
#include <gdcmAttribute.h>
#include <gdcmImageWriter.h>
#include <gdcmMediaStorage.h>
#include <gdcmUIDGenerator.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>

#include <zlib.h>

#include "io/ConversionCache.h"
#include "io/Convert.h"
#include "io/DenseSource.h"
#include "io/DenseVolume.h"
#include "io/PatientMetadata.h"
#include "SameVdbFiles.h"
#include "io/VdbFile.h"
#include "sparse/Error.h"
#include "tests/PrivateUserCache.h"
#include "tests/tools/RunCommand.h"

namespace fcc::io {
namespace {

using test::TempDir;

constexpr int kNx = 11, kNy = 9, kNz = 7;
const glm::dvec3 kSpacing(0.7, 0.8, 1.5);
const glm::dvec3 kOrigin(-12.5, 4.0, 30.25);
constexpr double kSlope = 2.0, kIntercept = -100.0;

// The stored (raw) value of voxel (i, j, k).
int16_t rawValue(int i, int j, int k) { return int16_t(3 * i + 17 * j + 101 * k - 50); }

// Row and column directions of the slices (DICOM's Image Orientation (Patient)), a rotation about z.
glm::dvec3 rowDirection() { return glm::dvec3(std::cos(0.3), std::sin(0.3), 0.0); }
glm::dvec3 columnDirection() { return glm::dvec3(-std::sin(0.3), std::cos(0.3), 0.0); }

// Slice k of the series as a CT image file.
void writeSlice(const std::string& path, int k, const std::string& studyUid, const std::string& seriesUid) {
  gdcm::ImageWriter writer;
  gdcm::Image& image = writer.GetImage();
  // Three dimensions (one slice): GDCM writes all three coordinates of the origin then.
  image.SetNumberOfDimensions(3);
  image.SetDimension(0, kNx);
  image.SetDimension(1, kNy);
  image.SetDimension(2, 1);
  image.SetPixelFormat(gdcm::PixelFormat::INT16);
  image.SetPhotometricInterpretation(gdcm::PhotometricInterpretation::MONOCHROME2);
  image.SetTransferSyntax(gdcm::TransferSyntax::ExplicitVRLittleEndian);
  const glm::dvec3 normal = glm::cross(rowDirection(), columnDirection());
  const glm::dvec3 position = kOrigin + normal * (kSpacing.z * k);
  const double origin[3] = {position.x, position.y, position.z};
  const double spacing[3] = {kSpacing.x, kSpacing.y, kSpacing.z};
  const double cosines[6] = {rowDirection().x, rowDirection().y, rowDirection().z,
                             columnDirection().x, columnDirection().y, columnDirection().z};
  image.SetOrigin(origin);
  image.SetSpacing(spacing);
  image.SetDirectionCosines(cosines);
  image.SetSlope(kSlope);
  image.SetIntercept(kIntercept);
  std::vector<int16_t> pixels;
  for (int j = 0; j < kNy; ++j)
    for (int i = 0; i < kNx; ++i) pixels.push_back(rawValue(i, j, k));
  gdcm::DataElement data(gdcm::Tag(0x7fe0, 0x0010));
  data.SetByteValue(reinterpret_cast<const char*>(pixels.data()), uint32_t(pixels.size() * sizeof(int16_t)));
  image.SetDataElement(data);

  gdcm::DataSet& ds = writer.GetFile().GetDataSet();
  const gdcm::MediaStorage ct(gdcm::MediaStorage::CTImageStorage);
  gdcm::Attribute<0x0008, 0x0016> sopClass{ct.GetString()};
  ds.Replace(sopClass.GetAsDataElement());
  gdcm::UIDGenerator uids;
  gdcm::Attribute<0x0008, 0x0018> sopInstance{uids.Generate()};
  ds.Replace(sopInstance.GetAsDataElement());
  gdcm::Attribute<0x0008, 0x0060> modality{"CT"};
  ds.Replace(modality.GetAsDataElement());
  gdcm::Attribute<0x0020, 0x000d> study{studyUid};
  ds.Replace(study.GetAsDataElement());
  gdcm::Attribute<0x0020, 0x000e> series{seriesUid};
  ds.Replace(series.GetAsDataElement());
  gdcm::Attribute<0x0020, 0x0013> instance{k + 1};
  ds.Replace(instance.GetAsDataElement());
  writer.SetFileName(path.c_str());
  ASSERT_TRUE(writer.Write()) << path;
}

// The series in `dir`, slice k in the file named by `order[k]` (names that sort unlike positions).
void writeSeries(const std::filesystem::path& dir, const std::vector<int>& order) {
  std::filesystem::create_directories(dir);
  gdcm::UIDGenerator uids;
  const std::string study = uids.Generate(), series = uids.Generate();
  for (int k = 0; k < kNz; ++k) writeSlice((dir / ("slice" + std::to_string(order[size_t(k)]))).string(), k, study, series);
}

void expectTheSeries(const DenseVolume& v) {
  ASSERT_EQ(v.dims, glm::ivec3(kNx, kNy, kNz));
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(v.spacing[a], kSpacing[a], 1e-6) << "axis " << a;
    EXPECT_NEAR(v.origin[a], kOrigin[a], 1e-4) << "axis " << a;
    EXPECT_NEAR(v.direction[0][a], rowDirection()[a], 1e-5);
    EXPECT_NEAR(v.direction[1][a], columnDirection()[a], 1e-5);
  }
  for (int k = 0; k < kNz; ++k)
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i)
        ASSERT_EQ(v.at(i, j, k), float(kSlope * rawValue(i, j, k) + kIntercept)) << i << "," << j << "," << k;
}

TEST(ItkReaders, DicomSeriesInAnyFileOrderGivesTheVolumeWithRescaleAndGeometry) {
  TempDir dir;
  std::vector<int> order(kNz);
  std::iota(order.begin(), order.end(), 0);
  writeSeries(dir / "sorted", order);
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  writeSeries(dir / "shuffled", order);
  EXPECT_EQ(detectFormat(dir / "sorted"), Format::Dicom);
  EXPECT_EQ(detectFormat(dir / "sorted/slice3"), Format::Dicom) << "by the DICM marker";
  const DenseVolume sorted = readDicom(dir / "sorted");
  expectTheSeries(sorted);
  const DenseVolume shuffled = readDicom(dir / "shuffled");
  expectTheSeries(shuffled);
  EXPECT_EQ(sorted.values, shuffled.values);
  // One file of the series stands for the whole series.
  expectTheSeries(readDicom(dir / "shuffled/slice2"));

  // Converted: the FCC grid's transform is the series' geometry (world = origin + R * S * ijk).
  ConvertOptions o;
  o.prefilter = false;
  convertToFcc(dir / "shuffled", dir / "ct.vdb", o);
  const FccGrid::Ptr grid = readFccGrid(dir / "ct.vdb");
  const openvdb::Vec3d world = grid->transform().indexToWorld(openvdb::Vec3d(2.0, 3.0, 4.0));
  const glm::dvec3 expected = kOrigin + rowDirection() * (kSpacing.x * 2.0) + columnDirection() * (kSpacing.y * 3.0) +
                              glm::cross(rowDirection(), columnDirection()) * (kSpacing.z * 4.0);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(world[a], expected[a], 1e-6) << "axis " << a;
  // The world is the patient's LPS frame: superior +z, anterior -y, read and recorded for the camera.
  ASSERT_TRUE(sorted.patient.has_value());
  EXPECT_EQ(sorted.patient->superior, glm::dvec3(0, 0, 1));
  EXPECT_EQ(sorted.patient->anterior, glm::dvec3(0, -1, 0));
  const std::optional<PatientAxes> recorded = patientAxesOf(*grid, "ct.vdb");
  ASSERT_TRUE(recorded.has_value());
  EXPECT_EQ(recorded->superior, glm::dvec3(0, 0, 1));
  EXPECT_EQ(recorded->anterior, glm::dvec3(0, -1, 0));
}

// A DICOM folder renders through the conversion cache like any input; a changed slice is a changed
// source (the folder's own time does not change when a file in it is rewritten in place).
TEST(ItkReaders, DicomFolderIsCachedAndAChangedSliceConvertsAgain) {
  TempDir dir;
  std::vector<int> order(kNz);
  std::iota(order.begin(), order.end(), 0);
  writeSeries(dir / "ct", order);
  const test::ScopedEnv cache("FCCVDB_CACHE_DIR", (dir / "cache").c_str());
  ConvertOptions o;
  {
    const FccInput first(dir / "ct", o, true, nullptr);
    EXPECT_EQ(first.origin(), FccInput::Origin::Converted);
    EXPECT_TRUE(holdsFccGrid(first.path()));
  }
  EXPECT_EQ(FccInput(dir / "ct", o, true, nullptr).origin(), FccInput::Origin::CacheHit);
  // Slice 3 rewritten with other values, the same name and size.
  const auto slice = std::filesystem::path(dir / "ct") / "slice3";
  const auto before = std::filesystem::last_write_time(slice);
  writeSlice(slice.string(), 3, "1.2.3", "1.2.3.4");
  std::filesystem::last_write_time(slice, before + std::chrono::seconds(3));
  EXPECT_EQ(FccInput(dir / "ct", o, true, nullptr).origin(), FccInput::Origin::Converted);
}

TEST(ItkReaders, MetaImageWithDetachedAndLocalData) {
  TempDir dir;
  std::vector<int16_t> values;
  for (int k = 0; k < kNz; ++k)
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i) values.push_back(rawValue(i, j, k));
  const std::string header = "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
                             "TransformMatrix = 1 0 0 0 1 0 0 0 1\nOffset = -12.5 4 30.25\n"
                             "ElementSpacing = 0.7 0.8 1.5\nDimSize = 11 9 7\nElementType = MET_SHORT\n";
  {
    std::ofstream mha(dir / "v.mha", std::ios::binary);
    mha << header << "ElementDataFile = LOCAL\n";
    mha.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * 2));
  }
  {
    std::ofstream(dir / "v.mhd") << header << "ElementDataFile = v.raw\n";
    std::ofstream(dir / "v.raw", std::ios::binary).write(reinterpret_cast<const char*>(values.data()),
                                                         std::streamsize(values.size() * 2));
  }
  for (const char* name : {"v.mha", "v.mhd"}) {
    SCOPED_TRACE(name);
    EXPECT_EQ(detectFormat(dir / name), Format::MetaImage);
    const DenseVolume v = readMetaImage(dir / name);
    ASSERT_EQ(v.dims, glm::ivec3(kNx, kNy, kNz));
    EXPECT_NEAR(v.spacing.y, 0.8, 1e-9);
    EXPECT_NEAR(v.origin.z, 30.25, 1e-9);
    EXPECT_EQ(v.at(4, 5, 6), float(rawValue(4, 5, 6)));
  }
  // Damaged: the data is shorter than the header says.
  std::filesystem::resize_file(dir / "v.raw", 100);
  EXPECT_THROW(readMetaImage(dir / "v.mhd"), InputError);
  std::filesystem::resize_file(dir / "v.mha", std::filesystem::file_size(dir / "v.mha") - 50);
  EXPECT_THROW(readMetaImage(dir / "v.mha"), InputError);
  EXPECT_THROW(readDicom(dir / "v.raw"), InputError);
}

// A MetaImage's AnatomicalOrientation makes it a patient's: ITK's world is the LPS frame, so codes that
// agree with the TransformMatrix (ITK writes identity as "RAI": each letter the side an axis runs from)
// give superior +z, anterior -y, as DICOM; codes that disagree with an identity matrix say where the index
// axes point; none, "???" or a body axis named twice give no axes. Read whole and streamed alike, and
// recorded by convert for the default camera.
TEST(ItkReaders, MetaImageAnatomicalOrientationGivesThePatientAxes) {
  TempDir dir;
  const std::vector<int16_t> values(size_t(kNx) * kNy * kNz, 7);
  const auto write = [&](const std::string& name, const std::string& extra) {
    std::ofstream out(dir / name, std::ios::binary);
    out << "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
           "TransformMatrix = 1 0 0 0 1 0 0 0 1\nOffset = 0 0 0\nElementSpacing = 0.7 0.8 1.5\n"
        << extra << "DimSize = 11 9 7\nElementType = MET_SHORT\nElementDataFile = LOCAL\n";
    out.write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * 2));
    return dir / name;
  };
  struct Case {
    const char* codes;
    std::optional<PatientAxes> expected;
  };
  const Case cases[] = {
      {"RAI", PatientAxes{{0, 0, 1}, {0, -1, 0}}},  // ITK's identity: the world is LPS
      {"LPS", PatientAxes{{0, 0, -1}, {0, 1, 0}}},  // every axis reversed
      {"RSA", PatientAxes{{0, -1, 0}, {0, 0, -1}}},  // coronal slices: y runs down from the top, z back from the face
      {"???", std::nullopt},
      {"RRI", std::nullopt},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.codes);
    const std::string path = write(std::string(c.codes[0] == '?' ? "unknown" : c.codes) + ".mha",
                                   std::string("AnatomicalOrientation = ") + c.codes + "\n");
    const DenseVolume whole = readMetaImage(path);
    const auto streamed = openMetaImage(path);
    for (const std::optional<PatientAxes>& got : {whole.patient, streamed->geometry().patient}) {
      ASSERT_EQ(got.has_value(), c.expected.has_value());
      if (!got) continue;
      for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(got->superior[a], c.expected->superior[a], 1e-12) << "superior " << a;
        EXPECT_NEAR(got->anterior[a], c.expected->anterior[a], 1e-12) << "anterior " << a;
      }
    }
  }
  EXPECT_FALSE(readMetaImage(write("none.mha", "")).patient.has_value()) << "no AnatomicalOrientation: not a patient's";

  // Recorded by convert, so render and view show it upright.
  ConvertOptions o;
  o.prefilter = false;
  convertToFcc(dir / "RSA.mha", dir / "rsa.vdb", o);
  const std::optional<PatientAxes> recorded = patientAxesOf(*readFccGrid(dir / "rsa.vdb"), "rsa.vdb");
  ASSERT_TRUE(recorded.has_value());
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(recorded->superior[a], glm::dvec3(0, -1, 0)[a], 1e-6) << "superior " << a;
    EXPECT_NEAR(recorded->anterior[a], glm::dvec3(0, 0, -1)[a], 1e-6) << "anterior " << a;
  }
}

// `source` read in runs that start and end inside slices, backwards too, gives the whole read's values.
void expectRunsGiveTheVolume(DenseSource& source, const DenseVolume& whole) {
  ASSERT_EQ(source.geometry().dims, whole.dims);
  ASSERT_EQ(source.voxelCount(), whole.values.size());
  for (const uint64_t run : {uint64_t(1), uint64_t(37), uint64_t(kNx * kNy), uint64_t(250)}) {
    std::vector<float> got(whole.values.size());
    for (uint64_t first = 0; first < got.size(); first += run)
      source.read(first, std::min<uint64_t>(run, got.size() - first), got.data() + first);
    EXPECT_EQ(got, whole.values) << "runs of " << run;
  }
  std::vector<float> last(5);
  source.read(whole.values.size() - 5, 5, last.data());
  source.read(3, 5, last.data());
  EXPECT_EQ(last, std::vector<float>(whole.values.begin() + 3, whole.values.begin() + 8)) << "back to the start";
}

// DICOM (one slice file at a time) and MetaImage (ITK's streaming, or whole where it is compressed):
// read by ranges of slices, and converted streamed, they give what the whole read gives.
TEST(ItkReaders, SourcesReadBySlicesEqualTheWholeReadAndConvertTheSame) {
  TempDir dir;
  std::vector<int> order(kNz);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(3));
  writeSeries(dir / "ct", order);
  std::vector<int16_t> values;
  for (int k = 0; k < kNz; ++k)
    for (int j = 0; j < kNy; ++j)
      for (int i = 0; i < kNx; ++i) values.push_back(rawValue(i, j, k));
  const std::string header = "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
                             "TransformMatrix = 0 1 0 -1 0 0 0 0 1\nOffset = -12.5 4 30.25\n"
                             "ElementSpacing = 0.7 0.8 1.5\nDimSize = 11 9 7\nElementType = MET_SHORT\n";
  const char* bytes = reinterpret_cast<const char*>(values.data());
  std::ofstream(dir / "v.mha", std::ios::binary) << header << "ElementDataFile = LOCAL\n" << std::string(bytes, values.size() * 2);
  std::vector<Bytef> packed(compressBound(uLong(values.size() * 2)));
  uLongf packedSize = uLongf(packed.size());
  ASSERT_EQ(compress2(packed.data(), &packedSize, reinterpret_cast<const Bytef*>(bytes), uLong(values.size() * 2), 6), Z_OK);
  std::ofstream(dir / "z.mha", std::ios::binary)
      << header << "CompressedData = True\nCompressedDataSize = " << packedSize << "\nElementDataFile = LOCAL\n"
      << std::string(reinterpret_cast<const char*>(packed.data()), packedSize);

  {
    SCOPED_TRACE("dicom");
    const auto source = openDicom(dir / "ct");
    const DenseVolume whole = readDicom(dir / "ct");
    expectTheSeries(whole);
    EXPECT_EQ(source->geometry().direction, whole.direction);
    EXPECT_EQ(source->geometry().spacing, whole.spacing);
    EXPECT_EQ(source->geometry().origin, whole.origin);
    ASSERT_TRUE(source->geometry().patient.has_value());
    EXPECT_EQ(source->geometry().patient->anterior, glm::dvec3(0, -1, 0));
    expectRunsGiveTheVolume(*source, whole);
  }
  for (const char* name : {"v.mha", "z.mha"}) {
    SCOPED_TRACE(name);
    const auto source = openMetaImage(dir / name);
    const DenseVolume whole = readMetaImage(dir / name);
    EXPECT_EQ(source->geometry().direction, whole.direction);
    EXPECT_FALSE(whole.patient.has_value()) << "a MetaImage need not be a patient's";
    EXPECT_EQ(whole.at(4, 5, 6), float(rawValue(4, 5, 6)));
    expectRunsGiveTheVolume(*source, whole);
  }

  for (const char* name : {"ct", "v.mha", "z.mha"})
    for (const bool resample : {false, true}) {
      SCOPED_TRACE(std::string(name) + (resample ? " resample" : " subsample"));
      ConvertOptions o;
      o.overwrite = true;
      if (resample) {
        o.mode = "resample";
        o.scale = 0.6;
      }
      const ConvertSummary streamed = convertToFcc(dir / name, dir / "streamed.vdb", o);
      EXPECT_NE(streamed.timings.find("read into slabs"), std::string::npos) << streamed.timings;
      o.inMemory = true;
      convertToFcc(dir / name, dir / "memory.vdb", o);
      test::expectSameFccFiles(dir / "memory.vdb", dir / "streamed.vdb");
    }
}

}  // namespace
}  // namespace fcc::io
