// The data `render` and `bench render` draw, opened by the flags: an FCC .vdb (a Cartesian input is
// converted first, io/ConversionCache.h), or with --reconstruction naming a Cartesian reconstruction, a
// Cartesian .vdb float grid as it is (io/CartesianBrickStore.h). Either way one render::BrickSource for
// the raycaster, the default isovalue and the file's damage report.
#pragma once

#include <memory>
#include <string>

#include "RenderFlags.h"
#include "io/CartesianBrickStore.h"
#include "viewer/BrickSource.h"
#include "viewer/DvrTransfer.h"
#include "viewer/PyramidLevels.h"

namespace fcc::cli {

class RenderData {
 public:
  // ValueError for an unknown --reconstruction (naming the valid ones) or one whose lattice the
  // renderer cannot store yet; InputError (one line) for a file that does not open.
  RenderData(const RenderFlags& flags, std::size_t hostCacheBytes, bool quiet);
  // The Cartesian grid `same` renders, with another CC reconstruction (the viewer's choice): the store —
  // its topology, leaf index and bricks' ranges — is shared, so nothing is read again. ValueError for an
  // unknown or non-CC name, or when `same` is FCC data (its one reconstruction is boxspline).
  RenderData(const RenderData& same, const std::string& reconstruction);
  ~RenderData();

  const render::BrickSource& source() const { return *source_; }
  const io::BrickStore* fccStore() const { return fccStore_.get(); }  // null for a Cartesian grid
  // --iso, or the default: the FCC rules of io/DefaultIsovalue.h; for a Cartesian grid 0 for a level
  // set, else the middle of the range the reconstruction takes.
  io::IsoChoice iso(const RenderFlags& flags) const;
  void warnIfIsoOutside(float iso) const;
  // --mode and, for DVR, the transfer function (--tf: a preset stretched onto the range the
  // reconstruction takes, from the background when that lies at its low end; or a file's values as
  // they are; a warning when the background gets an opacity: bricks without data are not drawn) sampled for the GPU with --unit-distance
  // (default: the world length of one index unit, the cube root of worldFromIndex's determinant),
  // --density-scale and --stop-opacity. ValueError / InputError (one line) for a bad --tf.
  void applyMode(const RenderFlags& flags, render::RenderOptions& options) const;
  // --tf fitted to the source with the optical scale of --unit-distance and --density-scale (the
  // viewer keeps it to rebuild the table). ValueError / InputError (one line) for a bad --tf.
  render::DvrTransfer dvrTransfer(const RenderFlags& flags) const;
  render::Camera camera(const RenderFlags& flags, double aspect) const;
  // Level of detail: with a bias from --lod-bias (or `levelsByDefault`, view's) and not
  // --full-resolution, opens the FCC file's pyramid levels (none in a file without one: drawn as today)
  // into options.coarserLevels and sets options.lodBias. ValueError (one line) for a bad --lod-bias.
  // Returns the levels drawn (1: full resolution). A note on stderr (unless `quiet`) when --lod-bias
  // names a file without a pyramid, or a mode that draws full resolution only.
  int applyLevels(const RenderFlags& flags, bool levelsByDefault, bool quiet, render::RenderOptions& options);
  // Closes the pyramid's levels (and their host caches): the next applyLevels opens them afresh.
  // Raycasters given their sources must be gone.
  void closeLevels() { levels_.reset(); }
  // Damage met so far (io/Damage.h): FCC bricks or Cartesian leaves, each rendered as a hole.
  io::Damage damage() const;

 private:
  std::unique_ptr<io::FccInput> input_;
  std::unique_ptr<io::BrickStore> fccStore_;
  std::shared_ptr<io::CartesianBrickStore> ccStore_;  // shared by the RenderData of each reconstruction
  std::unique_ptr<render::BrickSource> source_;
  std::unique_ptr<render::PyramidLevels> levels_;
};

}  // namespace fcc::cli
