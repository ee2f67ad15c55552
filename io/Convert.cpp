#include "Convert.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "AtomicOutput.h"
#include "DenseSlabField.h"
#include "DenseSource.h"
#include "PatientMetadata.h"
#include "VdbFile.h"
#include "VdbLeafReader.h"
#include "VdbResampleField.h"
#include "VdbSourceField.h"
#include "sparse/BrickBounds.h"
#include "sparse/CubicBSpline.h"
#include "sparse/Error.h"
#include "sparse/FccBuilder.h"
#include "sparse/StreamedBuild.h"
#include "sparse/StreamedFccTree.h"

namespace fcc::io {
namespace {

bool inside(const glm::ivec3& ijk, const glm::ivec3& dims) {
  return glm::all(glm::greaterThanEqual(ijk, glm::ivec3(0))) && glm::all(glm::lessThan(ijk, dims));
}

// Subsampling keeps the even-parity voxels of a dense volume, at their own positions.
class DenseSubsampleField : public SampleField {
 public:
  DenseSubsampleField(const DenseVolume& volume, float background) : volume_(volume), background_(background) {}
  float sample(const glm::ivec3& ijk) const override {
    return inside(ijk, volume_.dims) ? volume_.at(ijk.x, ijk.y, ijk.z) : background_;
  }
  SiteBox bounds() const override { return {glm::ivec3(0), volume_.dims - 1}; }
  float background() const override { return background_; }

 private:
  const DenseVolume& volume_;
  float background_;
};

// Resampling reconstructs the source (tricubic B-spline) at the sites of a lattice of another spacing.
class DenseResampleField : public SampleField {
 public:
  DenseResampleField(const DenseVolume& volume, float background, double spacingInVoxels)
      : spline_(volume.dims, volume.values), background_(background), spacing_(spacingInVoxels) {
    latticeMax_ = glm::ivec3(glm::floor(glm::dvec3(volume.dims - 1) / spacing_ + 1e-9));
  }
  float sample(const glm::ivec3& ijk) const override {
    if (!inside(ijk, latticeMax_ + 1)) return background_;
    return spline_.evaluate(glm::dvec3(ijk) * spacing_);
  }
  SiteBox bounds() const override { return {glm::ivec3(0), latticeMax_}; }
  float background() const override { return background_; }

 private:
  CubicBSplineVolume spline_;
  float background_;
  double spacing_;
  glm::ivec3 latticeMax_;
};

// Subsampling a sparse float grid: every value (active or not) at even-parity voxels; values equal to
// the grid's background become `background` (the --background override).
class VdbSubsampleField : public SampleField {
 public:
  VdbSubsampleField(const openvdb::FloatGrid& grid, float background) : grid_(grid), background_(background) {
    const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
    if (grid.activeVoxelCount() > 0)
      bounds_ = {glm::ivec3(box.min().x(), box.min().y(), box.min().z()),
                 glm::ivec3(box.max().x(), box.max().y(), box.max().z())};
  }
  float sample(const glm::ivec3& ijk) const override {
    // Value accessors are not thread-safe; the tree's own lookup is.
    const float v = grid_.tree().getValue(openvdb::Coord(ijk.x, ijk.y, ijk.z));
    return v == grid_.background() ? background_ : v;
  }
  SiteBox bounds() const override { return bounds_; }
  bool mayHoldData(const SiteBox& box) const override {
    if (!box.intersects(bounds_)) return false;
    // Outside leaves the tree is piecewise constant (tiles): one probe per leaf-sized cell decides.
    const auto& tree = grid_.tree();
    constexpr int kLeaf = openvdb::FloatTree::LeafNodeType::DIM;
    for (int z = box.min.z & ~(kLeaf - 1); z <= box.max.z; z += kLeaf)
      for (int y = box.min.y & ~(kLeaf - 1); y <= box.max.y; y += kLeaf)
        for (int x = box.min.x & ~(kLeaf - 1); x <= box.max.x; x += kLeaf) {
          const openvdb::Coord c(x, y, z);
          if (tree.probeConstLeaf(c) || tree.getValue(c) != grid_.background()) return true;
        }
    return false;
  }
  float background() const override { return background_; }

 private:
  const openvdb::FloatGrid& grid_;
  float background_;
  SiteBox bounds_;
};

// The world transform of a dense volume's index space (its geometry; the values are not read).
openvdb::math::Transform::Ptr transformOf(const DenseVolume& v, double latticeSpacingInVoxels) {
  if (v.direction == glm::dmat3(1.0)) {  // axis-aligned: a scale and a translation
    auto xform = openvdb::math::Transform::createLinearTransform();
    xform->preScale(openvdb::Vec3d(v.spacing.x, v.spacing.y, v.spacing.z) * latticeSpacingInVoxels);
    xform->postTranslate(openvdb::Vec3d(v.origin.x, v.origin.y, v.origin.z));
    return xform;
  }
  // OpenVDB maps row vectors (p * M): row a is where index axis a goes, the last row the origin.
  openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
  for (int a = 0; a < 3; ++a) {
    for (int r = 0; r < 3; ++r) m[a][r] = v.direction[a][r] * v.spacing[a] * latticeSpacingInVoxels;
    m[3][a] = v.origin[a];
  }
  return openvdb::math::Transform::createLinearTransform(m);
}

// A dense input, read on demand.
std::unique_ptr<DenseSource> openDense(const std::string& input, Format format, const ConvertOptions& options) {
  switch (format) {
    case Format::Raw:
      if (!options.raw)
        throw ValueError(input + ": raw input needs --dims X,Y,Z (and --type, default u8; valid inputs by extension: .vdb, "
                                 ".nrrd, .nhdr, .nii, .nii.gz, .mha, .mhd, .dcm or a DICOM folder; anything else is raw)");
      return openRaw(input, *options.raw);
    case Format::Nrrd: return openNrrd(input);
    case Format::Nifti: return openNifti(input);
    case Format::Dicom: return openDicom(input);
    case Format::MetaImage: return openMetaImage(input);
    case Format::Vdb: break;
  }
  throw Error("internal: not a dense format");
}

// A dense input whole (the in-memory reference): DICOM and MetaImage by ITK's whole read, a second
// way to read them that their sources are tested against; the others are their sources read whole.
DenseVolume readDense(const std::string& input, Format format, const ConvertOptions& options) {
  if (format == Format::Dicom) return readDicom(input);
  if (format == Format::MetaImage) return readMetaImage(input);
  return readAllVoxels(*openDense(input, format, options));
}

// The lattice spacing h (in source voxels) whose FCC embedding over the source's extent holds about
// `samples` sites: (floor(E/h) + 1) points per axis, half of them FCC sites. Bisection on h.
double spacingForSampleCount(const glm::ivec3& dims, uint64_t samples) {
  const glm::dvec3 extent = glm::dvec3(dims - 1);
  auto sites = [&](double h) {
    const glm::dvec3 n = glm::floor(extent / h + 1e-9) + 1.0;  // as DenseResampleField rounds
    return n.x * n.y * n.z / 2.0;
  };
  double lo = 1e-3, hi = 2.0 * glm::max(extent.x, glm::max(extent.y, extent.z)) + 1.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = std::sqrt(lo * hi);
    (sites(mid) > double(samples) ? lo : hi) = mid;
  }
  return hi;
}

}  // namespace

ConvertSummary convertToFcc(const std::string& input, const std::string& output, const ConvertOptions& options,
                            openvdb::util::NullInterrupter* interrupter) {
  if (options.mode != "subsample" && options.mode != "resample")
    throw ValueError("--mode " + options.mode + " is not valid (valid: subsample, resample)");
  const bool resample = options.mode == "resample";
  if (resample && options.samples == 0 && !(options.scale > 0.0))
    throw ValueError("--mode resample needs --samples N or --scale S (> 0)");
  // Fail on the output before reading a large input.
  { AtomicOutput probe(output, options.overwrite, input); }
  const auto openStart = std::chrono::steady_clock::now();

  initializeVdb();
  const Format format = detectFormat(input);
  FccProvenance provenance;
  provenance.sourceFile = std::filesystem::path(input).filename().string();
  provenance.mode = options.mode;
  provenance.coefficients = options.prefilter;
  ConvertSummary summary;

  openvdb::FloatGrid::Ptr sourceGrid;          // the whole source grid (the in-memory subsample reference)
  std::shared_ptr<const VdbLeafReader> reader;  // or its topology, leaves read on demand
  DenseVolume dense;                            // a dense input, whole (the in-memory reference)
  std::unique_ptr<DenseSource> source;          // or read on demand
  openvdb::math::Transform::Ptr xform;
  std::optional<PatientAxes> patient;  // a medical dense input's: recorded for the default camera
  float background = options.background.value_or(0.0f);
  glm::ivec3 extent(0);  // the source's voxels per axis (its active box for a .vdb): resampling's extent
  if (format == Format::Vdb && (resample || !options.inMemory)) {
    const std::vector<std::string> floatTrees{openvdb::FloatTree::treeType()};
    // OpenVDB parses the header and topology: first in the guard's process, which a damaged file may crash.
    guardLeafRead(input, options.gridName, floatTrees);
    reader = std::make_shared<VdbLeafReader>(input, options.gridName, floatTrees);
    const auto& topology = static_cast<const openvdb::FloatGrid&>(*reader->grid());
    provenance.sourceGrid = summary.gridName = topology.getName();
    provenance.levelSet = topology.getGridClass() == openvdb::GRID_LEVEL_SET;
    background = options.background.value_or(topology.background());
    summary.inputVoxels = topology.activeVoxelCount();
    xform = topology.transform().copy();
    const openvdb::Coord dim = topology.evalActiveVoxelBoundingBox().dim();
    extent = glm::ivec3(dim.x(), dim.y(), dim.z());
  } else if (format == Format::Vdb) {
    sourceGrid = readFloatGrid(input, options.gridName);
    provenance.sourceGrid = summary.gridName = sourceGrid->getName();
    provenance.levelSet = sourceGrid->getGridClass() == openvdb::GRID_LEVEL_SET;
    background = options.background.value_or(sourceGrid->background());
    summary.inputVoxels = sourceGrid->activeVoxelCount();
    xform = sourceGrid->transform().copy();
  } else if (options.inMemory) {
    dense = readDense(input, format, options);
    summary.gridName = "density";
    summary.inputVoxels = dense.values.size();
    xform = transformOf(dense, 1.0);
    patient = dense.patient;
    extent = dense.dims;
  } else {
    // Read when the field is made, below: into a scratch file of x-slabs (SlabScratch.h).
    source = openDense(input, format, options);
    summary.gridName = "density";
    summary.inputVoxels = source->voxelCount();
    xform = transformOf(source->geometry(), 1.0);
    patient = source->geometry().patient;
    extent = source->geometry().dims;
  }

  if (options.onOpened) options.onOpened();
  std::unique_ptr<SampleField> field;
  const auto readStart = std::chrono::steady_clock::now();
  const double opening = std::chrono::duration<double>(readStart - openStart).count();
  if (resample) {
    const double h = options.scale > 0.0 ? options.scale : spacingForSampleCount(extent, options.samples);
    if (!(h > 0.0) || !std::isfinite(h)) throw ValueError("--samples/--scale give no valid lattice spacing");
    if (reader) field = std::make_unique<VdbResampleField>(reader, h, background);
    else if (source)
      field = std::make_unique<DenseSlabResampleField>(slabsOfCoefficients(*source, interrupter), background, h);
    else field = std::make_unique<DenseResampleField>(dense, background, h);
    xform->preScale(h);
  } else if (reader) {
    field = std::make_unique<VdbSourceField>(reader, background);
  } else if (sourceGrid) {
    field = std::make_unique<VdbSubsampleField>(*sourceGrid, background);
  } else if (source) {
    field = std::make_unique<DenseSlabSubsampleField>(slabsOfSamples(*source, interrupter), background);
  } else {
    field = std::make_unique<DenseSubsampleField>(dense, background);
  }
  const double slabbing = std::chrono::duration<double>(std::chrono::steady_clock::now() - readStart).count();
  BuildOptions build;
  build.prefilter = options.prefilter;
  build.tolerance = options.tolerance;
  auto describe = [&](FccGrid& grid, const SampleSummary& samples) {
    grid.setTransform(xform);
    grid.setName(summary.gridName);
    provenance.sampleMin = samples.min;
    provenance.sampleMax = samples.max;
    setFccMetadata(grid, provenance);
    if (patient) recordPatientAxes(grid, *patient);
    recordSampleHistogram(grid, samples);
    grid.setSaveFloatAsHalf(options.half);
    summary.activeSamples = grid.activeVoxelCount() * 4;
    summary.bricks = grid.tree().leafCount();
  };

  if (options.inMemory) {
    // Out-of-core fields read only what they were prepared for: here, everything a block may read
    // (a block's samples reach 2 * 8 + 1 sites beyond the field's bounds).
    if (!field->bounds().empty()) field->prepare({field->bounds().expandedBy(17)});
    BuildResult built = buildFccGrid(*field, build, interrupter);
    describe(*built.grid, built.samples);
    openvdb::GridCPtrVec grids{built.grid};
    if (options.bounds) {
      // Bounds of the spline the renderer evaluates: of the prefiltered coefficients for a samples grid.
      BoundsGrid::Ptr bounds =
          computeBrickBounds(*coefficientsOf(valuesAsStored(built.grid), options.preprocess), options.preprocess);
      summary.boundsBricks = bounds->activeVoxelCount();
      grids.push_back(bounds);
    }
    writeVdbAtomically(output, grids, options.overwrite, input);
    return summary;
  }

  const FccBlockBuilder builder(*field, build);
  StreamedBuildOptions streamed;
  streamed.half = options.half;
  streamed.kernels = options.preprocess;
  const auto passStart = std::chrono::steady_clock::now();
  const StreamedBuild built = buildFccGridStreamed(builder, streamed, interrupter);
  const double pass1 = std::chrono::duration<double>(std::chrono::steady_clock::now() - passStart).count();
  describe(*built.grid, built.samples);
  openvdb::GridCPtrVec grids{built.grid};
  if (options.bounds) {
    const BoundsGrid::Ptr bounds = boundsGridOf(built.bounds, *built.grid);
    summary.boundsBricks = bounds->activeVoxelCount();
    grids.push_back(bounds);
  }
  // The grid's tree writes its leaves while it is written: those pass 1 kept, copied; any other rebuilt
  // from `field`, alive until then.
  const auto writeStart = std::chrono::steady_clock::now();
  writeVdbAtomically(output, grids, options.overwrite, input);
  const double pass2 = std::chrono::duration<double>(std::chrono::steady_clock::now() - writeStart).count();
  const StreamedBuild::Times& t = built.times;
  const auto& tree = static_cast<const StreamedFccTree&>(built.grid->tree());
  char text[480];
  std::snprintf(text, sizeof text,
                "pass 1 %.2f s (blocks %.2f, prepare %.2f, build %.2f, window %.2f, bounds %.2f of which kernels %.2f, "
                "prune %.2f); pass 2 (write: %zu leaves copied as pass 1 kept them, %zu rebuilt) %.2f s",
                pass1, t.blocks, t.prepare, t.build, t.window, t.bounds, t.boundsKernels, t.prune, tree.leavesCopied(),
                tree.leavesRebuilt(), pass2);
  summary.timings = text;
  if (source) {  // the dense input read once, into the slab scratch, before pass 1
    std::snprintf(text, sizeof text, "read into slabs %.2f s; ", slabbing);
    summary.timings = text + summary.timings;
  }
  // Opening: the source's header and topology (for a .vdb, first in the guard's process), its leaf index.
  std::snprintf(text, sizeof text, "open %.2f s; ", opening);
  summary.timings = text + summary.timings;
  return summary;
}

}  // namespace fcc::io
