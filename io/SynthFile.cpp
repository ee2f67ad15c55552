#include "SynthFile.h"

#include "VdbFile.h"
#include "sparse/BrickBounds.h"
#include "sparse/StreamedBuild.h"

namespace fcc::io {

void describeSynthGrid(FccGrid& grid, const std::string& kind, const SynthField& synth, bool prefilter,
                       const SampleSummary& samples) {
  auto xform = openvdb::math::Transform::createLinearTransform();
  const glm::dvec3 s = synth.worldFromIndexScale, o = synth.worldFromIndexOrigin;
  xform->preScale(openvdb::Vec3d(s.x, s.y, s.z));
  xform->postTranslate(openvdb::Vec3d(o.x, o.y, o.z));
  grid.setTransform(xform);
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

}  // namespace fcc::io
