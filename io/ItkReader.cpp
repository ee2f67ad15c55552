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

#include "DenseVolume.h"
#include "sparse/Error.h"

namespace fcc::io {
namespace {

namespace fs = std::filesystem;
using Image = itk::Image<float, 3>;

// The image's samples and geometry; InputError if it is larger than any reader accepts.
DenseVolume toDense(const Image& image, const std::string& path) {
  const Image::SizeType size = image.GetLargestPossibleRegion().GetSize();
  DenseVolume v;
  for (int a = 0; a < 3; ++a) {
    if (size[a] > uint64_t(1) << 30) throw InputError(path + ": " + std::to_string(size[a]) + " voxels along an axis is too many");
    v.dims[a] = int(size[a]);
  }
  const uint64_t count = checkedVoxelCount(v.dims, path);
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
  const float* data = image.GetBufferPointer();
  v.values.assign(data, data + count);  // ITK's buffer is x fastest, as ours
  return v;
}

// The DICOM files of the series `path` names: a folder (its one series, or the largest, by slices) or
// one of its files (that file's series).
std::vector<std::string> seriesFiles(const std::string& path) {
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

}  // namespace

DenseVolume readDicom(const std::string& path) {
  try {
    const std::vector<std::string> files = seriesFiles(path);
    auto reader = itk::ImageSeriesReader<Image>::New();
    reader->SetImageIO(itk::GDCMImageIO::New());  // applies Rescale Slope/Intercept into float
    reader->SetFileNames(files);
    reader->Update();
    return toDense(*reader->GetOutput(), path);
  } catch (const itk::ExceptionObject& e) {
    throw InputError(path + ": not a DICOM series ITK/GDCM can read: " + e.GetDescription());
  }
}

DenseVolume readMetaImage(const std::string& path) {
  try {
    auto io = itk::MetaImageIO::New();
    if (!io->CanReadFile(path.c_str())) throw InputError(path + ": not a MetaImage (.mha/.mhd) file ITK can read");
    io->SetFileName(path);
    io->ReadImageInformation();
    if (io->GetNumberOfDimensions() != 3 || io->GetNumberOfComponents() != 1)
      throw InputError(path + ": a MetaImage of " + std::to_string(io->GetNumberOfDimensions()) + " dimensions and " +
                       std::to_string(io->GetNumberOfComponents()) + " components per voxel; valid: 3-D scalar images");
    auto reader = itk::ImageFileReader<Image>::New();
    reader->SetImageIO(io);
    reader->SetFileName(path);
    reader->Update();
    return toDense(*reader->GetOutput(), path);
  } catch (const itk::ExceptionObject& e) {
    throw InputError(path + ": cannot read this MetaImage: " + e.GetDescription());
  }
}

}  // namespace fcc::io
