// DICOM series and MetaImage through ITK's ImageIO layer (Debian's libinsighttoolkit5-dev; GDCM under
// DICOM), rather than readers of our own: these formats have many encodings (compressed transfer
// syntaxes, enhanced multi-frame objects, detached MetaImage data) that the field's libraries already
// handle. The only translation unit that includes ITK's headers: they are heavy.
#include <itkGDCMImageIO.h>
#include <itkGDCMSeriesFileNames.h>
#include <itkImage.h>
#include <itkImageFileReader.h>
#include <itkImageSeriesReader.h>
#include <itkMetaImageIO.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "DenseSource.h"
#include "sparse/Error.h"

namespace fcc::io {
namespace {

namespace fs = std::filesystem;
using Image = itk::Image<float, 3>;

// The image's geometry (values empty); InputError if it is larger than any reader accepts.
DenseVolume geometryOf(const Image& image, const std::string& path) {
  const Image::SizeType size = image.GetLargestPossibleRegion().GetSize();
  DenseVolume v;
  for (int a = 0; a < 3; ++a) {
    if (size[a] > uint64_t(1) << 30) throw InputError(path + ": " + std::to_string(size[a]) + " voxels along an axis is too many");
    v.dims[a] = int(size[a]);
  }
  checkedVoxelCount(v.dims, path);
  const Image::SpacingType spacing = image.GetSpacing();
  const Image::PointType origin = image.GetOrigin();
  const Image::DirectionType direction = image.GetDirection();
  for (int a = 0; a < 3; ++a) {
    v.spacing[a] = spacing[a];
    v.origin[a] = origin[a];
    for (int r = 0; r < 3; ++r) v.direction[a][r] = direction(r, a);  // glm: [column][row]
    if (!(std::isfinite(v.spacing[a]) && v.spacing[a] > 0.0))
      throw InputError(path + ": spacing " + std::to_string(v.spacing[a]) + " along axis " + std::to_string(a) +
                       " is not a positive number");
  }
  return v;
}

// A DICOM series' world (and a MetaImage's with an AnatomicalOrientation) is the patient's LPS frame (ITK's physical space: the slices' positions and
// orientation as DICOM gives them).
PatientAxes lpsPatientAxes() { return {kSuperiorInPatient, kAnteriorInLps}; }

// The image's samples and geometry.
DenseVolume toDense(const Image& image, const std::string& path, std::optional<PatientAxes> patient = std::nullopt) {
  DenseVolume v = geometryOf(image, path);
  v.patient = patient;
  const float* data = image.GetBufferPointer();
  v.values.assign(data, data + checkedVoxelCount(v.dims, path));  // ITK's buffer is x fastest, as ours
  return v;
}

// The DICOM files of the series `path` names: a folder (its one series, or the largest, by slices) or
// one of its files (that file's series).
std::vector<std::string> seriesFiles(const std::string& path) {
  // ITK writes its warnings ("WARNING: In .../itkGDCMSeriesFileNames.cxx ... No Series were found") as
  // blocks on stderr; what they say reaches the user as our one line (the InputErrors below).
  itk::Object::GlobalWarningDisplayOff();
  const bool folder = fs::is_directory(path);
  const std::string dir = folder ? path : fs::path(path).parent_path().string();
  auto names = itk::GDCMSeriesFileNames::New();
  names->SetUseSeriesDetails(true);
  names->SetDirectory(dir.empty() ? "." : dir);
  const std::vector<std::string>& uids = names->GetSeriesUIDs();
  if (uids.empty()) throw InputError(path + ": no DICOM series found" + (folder ? " in this folder" : " beside this file"));
  std::vector<std::string> best;
  for (const std::string& uid : uids) {
    std::vector<std::string> files = names->GetFileNames(uid);  // sorted by position along the slice normal
    if (!folder) {
      const fs::path wanted = fs::weakly_canonical(path);
      const bool holds = std::any_of(files.begin(), files.end(),
                                     [&](const std::string& f) { return fs::weakly_canonical(f) == wanted; });
      if (holds) return files;
    } else if (files.size() > best.size()) {
      best = std::move(files);
    }
  }
  if (best.empty()) throw InputError(path + ": this file belongs to no DICOM series GDCM can read");
  return best;
}

// ITK's MetaImage reader reports data shorter than its header promises only on std::cerr and hands
// back the image anyway; so uncompressed data is sized here first (one file, LOCAL or detached).
void checkMetaImageDataSize(itk::MetaImageIO& io, const std::string& path) {
  MetaImage* meta = io.GetMetaImagePointer();
  if (!meta || meta->CompressedData()) return;  // zlib itself fails on short compressed data
  uint64_t expected = uint64_t(io.GetComponentSize()) * io.GetNumberOfComponents();
  for (unsigned a = 0; a < io.GetNumberOfDimensions(); ++a) expected *= io.GetDimensions(a);
  const std::string dataFile = meta->ElementDataFileName();
  std::error_code ec;
  if (dataFile == "LOCAL") {
    // The data follows the header's last line, "ElementDataFile = LOCAL".
    std::ifstream in(path, std::ios::binary);
    std::string head(1 << 16, '\0');
    in.read(head.data(), std::streamsize(head.size()));
    head.resize(size_t(in.gcount()));
    const size_t field = head.find("ElementDataFile");
    const size_t lineEnd = field == std::string::npos ? std::string::npos : head.find('\n', field);
    if (lineEnd == std::string::npos) return;
    const uint64_t available = fs::file_size(path, ec) - (lineEnd + 1);
    if (!ec && available < expected)
      throw InputError(path + ": holds " + std::to_string(available) + " bytes of voxel data but its header needs " +
                       std::to_string(expected) + "; the file is truncated");
  } else if (dataFile.find_first_of("%") == std::string::npos && dataFile != "LIST") {
    const fs::path data = fs::path(dataFile).is_absolute() ? fs::path(dataFile) : fs::path(path).parent_path() / dataFile;
    const uint64_t available = fs::file_size(data, ec);
    if (ec) throw InputError(path + ": its data file " + data.string() + " cannot be opened");
    if (available < expected)
      throw InputError(data.string() + ": holds " + std::to_string(available) + " bytes but " + path +
                       " says its voxels take " + std::to_string(expected) + "; the file is truncated");
  }
}


// A reader's output read a range of slices at a time (an IORegion): ITK's MetaImageIO reads only
// those bytes of uncompressed data, ImageSeriesReader only those slice files. `what` words errors.
template <class Reader>
class ItkSource final : public DenseSource {
 public:
  // `whole`: the reader cannot read part of the file (compressed MetaImage data is inflated whole for
  // any region), so the first read takes every slice, once, rather than inflating it again per range.
  // `patient`: where the patient's axes lie in the image's world (DICOM's LPS), if it is a patient's.
  ItkSource(typename Reader::Pointer reader, std::string path, std::string what, bool whole = false,
            std::optional<PatientAxes> patient = std::nullopt)
      : reader_(reader), path_(std::move(path)), what_(std::move(what)), whole_(whole) {
    guarded([&] { reader_->UpdateOutputInformation(); });
    geometry_ = geometryOf(*reader_->GetOutput(), path_);
    geometry_.patient = patient;
  }

  void read(uint64_t first, uint64_t count, float* out) override {
    if (count == 0) return;
    const uint64_t sliceVoxels = uint64_t(geometry_.dims.x) * uint64_t(geometry_.dims.y);
    const int z0 = int(first / sliceVoxels), z1 = int((first + count - 1) / sliceVoxels);
    if (z0 < slicesFrom_ || z1 >= slicesFrom_ + slicesRead_) {
      if (whole_) readSlices(0, geometry_.dims.z);
      else readSlices(z0, z1 - z0 + 1);
    }
    std::copy_n(slices_.data() + (first - uint64_t(slicesFrom_) * sliceVoxels), count, out);
  }

 private:
  template <class F>
  void guarded(F&& f) {
    try {
      f();
    } catch (const itk::ExceptionObject& e) {
      throw InputError(path_ + ": " + what_ + ": " + e.GetDescription());
    }
  }

  // Slices [z0, z0 + n) into slices_ (the last ones read are kept: a run may end mid-slice).
  void readSlices(int z0, int n) {
    Image::RegionType region;
    region.SetIndex({0, 0, z0});
    region.SetSize({size_t(geometry_.dims.x), size_t(geometry_.dims.y), size_t(n)});
    Image* image = reader_->GetOutput();
    guarded([&] {
      image->SetRequestedRegion(region);
      reader_->Update();
    });
    // The buffer holds at least the region (all of the image where ITK cannot stream: compressed data).
    const Image::RegionType buffered = image->GetBufferedRegion();
    if (!buffered.IsInside(region)) throw InputError(path_ + ": " + what_ + ": ITK read less than the slices asked for");
    slices_.resize(size_t(region.GetNumberOfPixels()));
    float* dst = slices_.data();
    for (int z = z0; z < z0 + n; ++z)
      for (int y = 0; y < geometry_.dims.y; ++y) {
        const float* row = image->GetBufferPointer() + image->ComputeOffset({0, y, z});
        dst = std::copy_n(row, geometry_.dims.x, dst);
      }
    slicesFrom_ = z0;
    slicesRead_ = n;
  }

  typename Reader::Pointer reader_;
  std::string path_, what_;
  bool whole_;
  std::vector<float> slices_;
  int slicesFrom_ = 0, slicesRead_ = 0;
};

}  // namespace

DenseVolume readDicom(const std::string& path) {
  try {
    const std::vector<std::string> files = seriesFiles(path);
    auto reader = itk::ImageSeriesReader<Image>::New();
    reader->SetImageIO(itk::GDCMImageIO::New());  // applies Rescale Slope/Intercept into float
    reader->SetFileNames(files);
    reader->Update();
    return toDense(*reader->GetOutput(), path, lpsPatientAxes());
  } catch (const itk::ExceptionObject& e) {
    throw InputError(path + ": not a DICOM series ITK/GDCM can read: " + e.GetDescription());
  }
}

namespace {

// A MetaImage's ImageIO with its header read and checked: a 3-D scalar image whose data is the size the
// header says (one place for the whole read and the streamed source).
itk::MetaImageIO::Pointer openMetaImageIO(const std::string& path) {
  itk::Object::GlobalWarningDisplayOff();  // as for DICOM: the InputErrors say it in one line
  auto io = itk::MetaImageIO::New();
  if (!io->CanReadFile(path.c_str())) throw InputError(path + ": not a MetaImage (.mha/.mhd) file ITK can read");
  io->SetFileName(path);
  io->ReadImageInformation();
  if (io->GetNumberOfDimensions() != 3 || io->GetNumberOfComponents() != 1)
    throw InputError(path + ": a MetaImage of " + std::to_string(io->GetNumberOfDimensions()) + " dimensions and " +
                     std::to_string(io->GetNumberOfComponents()) + " components per voxel; valid: 3-D scalar images");
  checkMetaImageDataSize(*io, path);
  return io;
}

// MetaImage's AnatomicalOrientation: one code per index axis, each naming the side the axis runs *from*
// (MetaIO's MET_ORIENTATION_RL is "R", right to left; ITK writes an identity direction, LPS, as "RAI").
// The index axis's direction in ITK's LPS patient frame, or zero for an unknown code.
glm::dvec3 lpsDirectionOf(MET_OrientationEnumType code) {
  switch (code) {
    case MET_ORIENTATION_RL: return {1, 0, 0};
    case MET_ORIENTATION_LR: return {-1, 0, 0};
    case MET_ORIENTATION_AP: return {0, 1, 0};
    case MET_ORIENTATION_PA: return {0, -1, 0};
    case MET_ORIENTATION_IS: return {0, 0, 1};
    case MET_ORIENTATION_SI: return {0, 0, -1};
    default: return glm::dvec3(0.0);
  }
}

// The patient's axes of a MetaImage in ITK's world (origin + direction * spacing * ijk), or none where the
// header has no AnatomicalOrientation (data that need not be a patient's). ITK's world is the patient's
// LPS frame, and the TransformMatrix the index axes' directions in it: where the orientation codes agree
// with the matrix (ITK writes them from it), the matrix gives the exact axes, as for DICOM. Where they
// disagree (a writer that left the matrix at the identity and said the orientation in the codes), the
// codes say where each index axis points. Codes that do not name three different body axes give none.
std::optional<PatientAxes> metaImagePatientAxes(itk::MetaImageIO& io) {
  const MetaImage* meta = io.GetMetaImagePointer();
  if (!meta || io.GetNumberOfDimensions() != 3) return std::nullopt;
  glm::dmat3 lpsFromIndexAxes(0.0), worldFromIndexAxes(1.0);  // columns: one index axis each
  glm::dvec3 covered(0.0);
  for (int a = 0; a < 3; ++a) {
    lpsFromIndexAxes[a] = lpsDirectionOf(meta->AnatomicalOrientation(a));
    covered += glm::abs(lpsFromIndexAxes[a]);
    const std::vector<double> column = io.GetDirection(unsigned(a));
    for (int r = 0; r < 3; ++r) worldFromIndexAxes[a][r] = column.at(size_t(r));
  }
  if (covered != glm::dvec3(1.0)) return std::nullopt;  // unknown, or one body axis named twice
  bool agree = true;
  for (int a = 0; a < 3; ++a) {
    const glm::dvec3 d = worldFromIndexAxes[a], m = glm::abs(d);
    const int dominant = m.x >= m.y && m.x >= m.z ? 0 : (m.y >= m.z ? 1 : 2);
    glm::dvec3 rounded(0.0);
    rounded[dominant] = d[dominant] < 0.0 ? -1.0 : 1.0;
    agree = agree && rounded == lpsFromIndexAxes[a];
  }
  if (agree) return PatientAxes{kSuperiorInPatient, kAnteriorInLps};
  // World vectors along the index axes (the matrix's columns) map to the codes' directions.
  return patientAxesFrom(lpsFromIndexAxes * glm::inverse(worldFromIndexAxes), kSuperiorInPatient, kAnteriorInLps);
}

}  // namespace

DenseVolume readMetaImage(const std::string& path) {
  try {
    const auto io = openMetaImageIO(path);
    auto reader = itk::ImageFileReader<Image>::New();
    reader->SetImageIO(io);
    reader->SetFileName(path);
    reader->Update();
    return toDense(*reader->GetOutput(), path, metaImagePatientAxes(*io));
  } catch (const itk::ExceptionObject& e) {
    throw InputError(path + ": cannot read this MetaImage: " + e.GetDescription());
  }
}

std::unique_ptr<DenseSource> openDicom(const std::string& path) {
  try {
    auto reader = itk::ImageSeriesReader<Image>::New();
    reader->SetImageIO(itk::GDCMImageIO::New());  // applies Rescale Slope/Intercept into float
    reader->SetFileNames(seriesFiles(path));
    // Else every slice's header is parsed again for each range of slices read.
    reader->MetaDataDictionaryArrayUpdateOff();
    return std::make_unique<ItkSource<itk::ImageSeriesReader<Image>>>(reader, path, "not a DICOM series ITK/GDCM can read",
                                                                          /*whole=*/false, lpsPatientAxes());
  } catch (const itk::ExceptionObject& e) {
    throw InputError(path + ": not a DICOM series ITK/GDCM can read: " + e.GetDescription());
  }
}

std::unique_ptr<DenseSource> openMetaImage(const std::string& path) {
  try {
    const auto io = openMetaImageIO(path);
    auto reader = itk::ImageFileReader<Image>::New();
    reader->SetImageIO(io);
    reader->SetFileName(path);
    reader->UseStreamingOn();
    return std::make_unique<ItkSource<itk::ImageFileReader<Image>>>(reader, path, "cannot read this MetaImage",
                                                                     !io->CanStreamRead(), metaImagePatientAxes(*io));
  } catch (const itk::ExceptionObject& e) {
    throw InputError(path + ": cannot read this MetaImage: " + e.GetDescription());
  }
}

}  // namespace fcc::io
