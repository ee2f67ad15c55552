#include "CompareFps.h"

#include <stdlib.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>

#include "CpuRenderer.h"
#include "Median.h"
#include "io/BrickStore.h"
#include "io/CartesianBrickStore.h"
#include "io/VdbFile.h"
#include "sparse/BccGrids.h"
#include "sparse/BrickBounds.h"
#include "sparse/CartesianGridBuilder.h"
#include "sparse/Error.h"
#include "sparse/FccBuilder.h"
#include "viewer/BccBrickSource.h"
#include "viewer/CartesianBrickSource.h"
#include "viewer/EglContext.h"
#include "viewer/Raycaster.h"

namespace fcc::cli {
namespace {

// A directory of its own under TMPDIR, removed with everything in it.
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "fccvdb-compare-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw Error("compare: cannot create a temporary directory in " + std::filesystem::temp_directory_path().string());
    path_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

// The field at the lattice's sites inside the domain (|ijk| <= reach), in an index space shifted by
// `offset` (even per axis: parity, and so the FCC sites, are kept) so that every index is >= 0; world =
// h (ijk - offset). Other points of the box (not sites) hold NaN and are never read.
struct DomainSamples {
  Lattice lattice;
  glm::ivec3 offset, dims;
  SiteBox box;  // in the shifted index space
  std::vector<float> values;
  float min = 0.0f, max = 0.0f;

  DomainSamples(const AnalyticField& field, const LatticeSampling& sampling) : lattice(sampling.lattice) {
    const glm::ivec3 reach = sampling.reach;
    offset = 2 * ((reach + 1) / 2);
    dims = 2 * reach + 1;
    box = SiteBox{offset - reach, offset + reach};
    values.assign(size_t(dims.x) * dims.y * dims.z, std::numeric_limits<float>::quiet_NaN());
    const double h = sampling.worldPerIndex;
    tbb::parallel_for(0, dims.z, [&](int z) {
      for (int y = 0; y < dims.y; ++y)
        for (int x = 0; x < dims.x; ++x) {
          const glm::ivec3 ijk = glm::ivec3(x, y, z) - reach;
          if (isLatticeSite(lattice, ijk)) values[index(ijk + offset)] = float(field.value(h * glm::dvec3(ijk)));
        }
    });
    min = std::numeric_limits<float>::max();
    max = std::numeric_limits<float>::lowest();
    for (float v : values)
      if (!std::isnan(v)) min = std::min(min, v), max = std::max(max, v);
  }
  size_t index(const glm::ivec3& shifted) const {
    const glm::ivec3 l = shifted - box.min;
    return (size_t(l.z) * dims.y + l.y) * dims.x + l.x;
  }
  // Outside the domain the data holds its lowest sample: what lies beyond is below the isovalue
  // wherever the surface is that of values above it (the usual way of a fog volume).
  float background() const { return min; }
  float at(const glm::ivec3& shifted) const { return box.contains(shifted) ? values[index(shifted)] : background(); }
  openvdb::math::Transform::Ptr transform(double h) const {
    auto xform = openvdb::math::Transform::createLinearTransform(h);
    xform->postTranslate(-h * openvdb::Vec3d(offset.x, offset.y, offset.z));
    return xform;
  }
};

class DomainSampleField : public SampleField {
 public:
  explicit DomainSampleField(const DomainSamples& s) : s_(s) {}
  float sample(const glm::ivec3& ijk) const override { return s_.at(ijk); }
  SiteBox bounds() const override { return s_.box; }
  float background() const override { return s_.background(); }

 private:
  const DomainSamples& s_;
};

std::string writeCcFile(const DomainSamples& samples, double h, const std::string& path) {
  const openvdb::FloatGrid::Ptr grid =
      buildCartesianGrid(samples.box, samples.background(), [&](const glm::ivec3& ijk) { return samples.at(ijk); });
  grid->setTransform(samples.transform(h));
  grid->setName("compare");
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  io::writeVdbAtomically(path, openvdb::GridCPtrVec{grid}, /*overwrite=*/true);
  return path;
}

std::string writeBccFile(const DomainSamples& samples, double h, const std::string& path) {
  const BccGrids grids = buildBccGrids(samples.box, samples.background(), [&](const glm::ivec3& x) { return samples.at(x); },
                                       *samples.transform(h));
  io::writeVdbAtomically(path, openvdb::GridCPtrVec{grids.primary, grids.secondary}, /*overwrite=*/true);
  return path;
}

std::string writeFccFile(const DomainSamples& samples, double h, const std::string& path) {
  const DomainSampleField field(samples);
  BuildResult built = buildFccGrid(field, BuildOptions{});
  built.grid->setTransform(samples.transform(h));
  built.grid->setName("compare");
  FccProvenance p;
  p.mode = "compare";
  p.sampleMin = built.samples.min;
  p.sampleMax = built.samples.max;
  setFccMetadata(*built.grid, p);
  const BoundsGrid::Ptr bounds = computeBrickBounds(*built.grid);
  io::writeVdbAtomically(path, openvdb::GridCPtrVec{built.grid, bounds}, /*overwrite=*/true);
  return path;
}

struct FrameTiming {
  double seconds = 0.0;  // median of the timed frames
  bool gpu = false;      // GPU time (else wall)
  uint64_t streamed = 0; // bricks uploaded during the timed frames (a pool too small for the data)
};

FrameTiming timeFrames(render::Raycaster& raycaster, const render::Camera& camera, int width, int height,
                       const FpsSettings& settings) {
  raycaster.render(camera, width, height);  // cold: every brick the frame needs is read and uploaded
  for (int i = 0; i < settings.warmupFrames; ++i) raycaster.render(camera, width, height);
  std::vector<double> gpu, wall;
  FrameTiming t;
  for (int i = 0; i < settings.timedFrames; ++i) {
    const render::FrameStats s = raycaster.render(camera, width, height);
    gpu.push_back(s.gpuSeconds);
    wall.push_back(s.seconds);
    t.streamed += s.bricksUploaded;
  }
  t.gpu = std::all_of(gpu.begin(), gpu.end(), [](double s) { return s > 0.0; });
  t.seconds = median(t.gpu ? gpu : wall);
  return t;
}

}  // namespace

FpsReport timeCompareRows(const AnalyticField& field, const CompareOptions& options, std::vector<CompareRow>& rows,
                          const FpsSettings& asked) {
  FpsReport report;
  if (options.width <= 0 || options.height <= 0) {
    report.line = "fps: not timed (no renders: --res 0x0)";
    return report;
  }
  std::unique_ptr<EglContext> context;
  try {
    context = std::make_unique<EglContext>();
  } catch (const Error& e) {
    report.line = std::string("fps: not timed (") + e.what() + ")";
    return report;
  }
  report.renderer = context->describe();
  FpsSettings settings = asked;
  if (isCpuRenderer(context->renderer())) {
    settings.warmupFrames = asked.cpuWarmupFrames;
    settings.timedFrames = asked.cpuTimedFrames;
  }
  initializeVdb();
  const ScratchDir scratch;
  const glm::dvec3 e = field.halfExtent();
  const CompareCamera cam(e);
  render::Camera camera;
  camera.eye = cam.eye;
  camera.lookat = cam.lookAt;
  camera.up = cam.up;
  camera.fovYDegrees = cam.fovDeg;
  render::RenderOptions renderOptions;
  renderOptions.iso = float(options.iso);
  renderOptions.timeGpu = true;
  renderOptions.hostCacheBytes = std::size_t(256) << 20;
  bool anyGpu = false, anyWall = false;
  std::string failure, streamedAt;
  for (int64_t budget : options.budgets) {
    for (Lattice lattice : {Lattice::Cc, Lattice::Bcc, Lattice::Fcc}) {
      const std::string name(latticeName(lattice));
      std::vector<CompareRow*> picked;
      for (auto& row : rows)
        if (row.budget == budget && row.lattice == name) picked.push_back(&row);
      if (picked.empty()) continue;
      const LatticeSampling sampling = samplingFor(lattice, budget, e);
      const double h = sampling.worldPerIndex;
      try {
        std::string path;
        {
          const DomainSamples samples(field, sampling);
          const std::string file = scratch.file(name + "_" + std::to_string(budget) + ".vdb");
          path = lattice == Lattice::Cc    ? writeCcFile(samples, h, file)
                 : lattice == Lattice::Bcc ? writeBccFile(samples, h, file)
                                           : writeFccFile(samples, h, file);
        }
        auto timeRow = [&](render::Raycaster& raycaster, CompareRow& row) {
          const FrameTiming t = timeFrames(raycaster, camera, options.width, options.height, settings);
          if (t.seconds > 0.0) row.fps = 1.0 / t.seconds;
          (t.gpu ? anyGpu : anyWall) = true;
          if (t.streamed > 0 && streamedAt.empty()) streamedAt = name + " " + row.reconstruction + " " + std::to_string(budget);
        };
        if (lattice == Lattice::Cc) {
          const io::CartesianBrickStore store(path);
          for (CompareRow* row : picked) {
            const render::CartesianBrickSource source(store, findReconstruction(row->reconstruction));
            render::Raycaster raycaster(source, renderOptions);
            timeRow(raycaster, *row);
          }
        } else if (lattice == Lattice::Bcc) {
          for (CompareRow* row : picked) {
            const render::BccBrickSource source(path, findReconstruction(row->reconstruction));
            render::Raycaster raycaster(source, renderOptions);
            timeRow(raycaster, *row);
          }
        } else {
          const io::BrickStore store(path);
          for (CompareRow* row : picked) {
            render::Raycaster raycaster(store, renderOptions);
            timeRow(raycaster, *row);
          }
        }
        std::filesystem::remove(path);
      } catch (const std::exception& err) {
        if (failure.empty()) failure = name + " at budget " + std::to_string(budget) + ": " + err.what();
      }
    }
  }
  for (const auto& row : rows) report.timed = report.timed || row.fps.has_value();
  const std::string clock = anyGpu && !anyWall ? "GPU time of its raycasting passes" : anyWall && !anyGpu ? "wall time" : "GPU or wall time";
  report.line = "fps: 1 / the median frame time (" + clock + ") of " + std::to_string(settings.timedFrames) +
                " frames after a cold one and " + std::to_string(settings.warmupFrames) +
                " warm-up, at the renders' size and camera; each row's samples in a .vdb through the brick-paged "
                "raycaster on " + report.renderer;
  if (!streamedAt.empty()) report.line += "; bricks were streamed during timed frames (the GPU pool held less than the data), first at " + streamedAt;
  if (!failure.empty()) report.line += "; not timed: " + failure;
  return report;
}

}  // namespace fcc::cli
