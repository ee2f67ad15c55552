#include "SynthFile.h"

#include "VdbFile.h"
#include "sparse/BccGrids.h"
#include "sparse/BrickBounds.h"
#include "sparse/CartesianGridBuilder.h"
#include "sparse/StreamedBuild.h"

namespace fcc::io {

namespace {

openvdb::math::Transform::Ptr synthTransform(const SynthField& synth) {
  auto xform = openvdb::math::Transform::createLinearTransform();
  const glm::dvec3 s = synth.worldFromIndexScale, o = synth.worldFromIndexOrigin;
  xform->preScale(openvdb::Vec3d(s.x, s.y, s.z));
  xform->postTranslate(openvdb::Vec3d(o.x, o.y, o.z));
  return xform;
}

}  // namespace

void describeSynthGrid(FccGrid& grid, const std::string& kind, const SynthField& synth, bool prefilter,
                       const SampleSummary& samples) {
  grid.setTransform(synthTransform(synth));
  grid.setName(kind);
  FccProvenance p;
  p.coefficients = prefilter;
  p.mode = "synth:" + kind;
  p.sampleMin = samples.min;
  p.sampleMax = samples.max;
  p.levelSet = synth.levelSet;
  setFccMetadata(grid, p);
  recordSampleHistogram(grid, samples);
}

SynthSummary writeSynthFile(const std::string& output, const SynthOptions& options,
                            openvdb::util::NullInterrupter* progress) {
  const SynthField synth = makeSynthField(options.spec);
  initializeVdb();
  BuildOptions build;
  build.prefilter = options.prefilter;
  const FccBlockBuilder builder(*synth.field, build);
  StreamedBuildOptions streamed;
  streamed.half = options.half;
  streamed.kernels = options.preprocess;
  const StreamedBuild built = buildFccGridStreamed(builder, streamed, progress);
  describeSynthGrid(*built.grid, options.spec.kind, synth, options.prefilter, built.samples);
  const BoundsGrid::Ptr bounds = boundsGridOf(built.bounds, *built.grid);
  // The grid's tree builds its leaves' values while it is written, from `synth`, alive until then.
  writeVdbAtomically(output, openvdb::GridCPtrVec{built.grid, bounds}, options.overwrite);
  SynthSummary summary;
  summary.activeSamples = built.grid->activeVoxelCount() * 4;
  summary.bricks = built.grid->tree().leafCount();
  summary.boundsBricks = bounds->activeVoxelCount();
  return summary;
}

SynthSummary writeSynthCartesianFile(const std::string& output, const SynthOptions& options) {
  const SynthField synth = makeSynthField(options.spec);
  initializeVdb();
  const SampleField& field = *synth.field;
  // Every point is a sample: the synth fields are functions of the point, whatever its parity.
  const openvdb::FloatGrid::Ptr grid = buildCartesianGrid(
      SiteBox{glm::ivec3(0), options.spec.dims - 1}, field.background(),
      [&](const glm::ivec3& ijk) { return field.sample(ijk); },
      [&](const SiteBox& box) { return field.mayHoldData(box); });
  grid->setTransform(synthTransform(synth));
  grid->setName(options.spec.kind);
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  grid->setSaveFloatAsHalf(options.half);
  writeVdbAtomically(output, openvdb::GridCPtrVec{grid}, options.overwrite);
  SynthSummary summary;
  summary.activeSamples = grid->activeVoxelCount();
  summary.bricks = grid->tree().leafCount();
  return summary;
}

SynthSummary writeSynthBccFile(const std::string& output, const SynthOptions& options) {
  const SynthField synth = makeSynthField(options.spec);
  initializeVdb();
  const SampleField& field = *synth.field;
  const BccGrids grids = buildBccGrids(
      SiteBox{glm::ivec3(0), options.spec.dims - 1}, field.background(), [&](const glm::ivec3& x) { return field.sample(x); },
      *synthTransform(synth), openvdb::GRID_FOG_VOLUME, [&](const SiteBox& box) { return field.mayHoldData(box); });
  SynthSummary summary;
  for (const openvdb::FloatGrid::Ptr& grid : {grids.primary, grids.secondary}) {
    grid->setSaveFloatAsHalf(options.half);
    summary.activeSamples += grid->activeVoxelCount();
    summary.bricks += grid->tree().leafCount();
  }
  writeVdbAtomically(output, openvdb::GridCPtrVec{grids.primary, grids.secondary}, options.overwrite);
  return summary;
}

}  // namespace fcc::io
