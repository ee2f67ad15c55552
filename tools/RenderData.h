// The data `render` and `bench render` draw, opened by the flags: an FCC .vdb (a Cartesian input is
// converted first, io/ConversionCache.h), or with --reconstruction naming a Cartesian reconstruction, a
// Cartesian .vdb float grid as it is (io/CartesianBrickStore.h), or a BCC dataset's two cosets
// (viewer/BccBrickSource.h; kDefaultBccReconstruction unless --reconstruction names another BCC one).
// Either way one render::BrickSource for the raycaster, the default isovalue and the file's damage report.
#pragma once

#include <memory>
#include <string>

#include "RenderFlags.h"
#include "io/CartesianBrickStore.h"
#include "viewer/BrickSource.h"
#include "viewer/DvrTransfer.h"
#include "viewer/ProjectedTetrahedra.h"
#include "viewer/PyramidLevels.h"

namespace fcc::cli {

// Linear on the BCC Delaunay tetrahedra: of the BCC schemes the one whose function does not change with
// the view (the plane-stack schemes pick their stack per frame from the camera).
inline constexpr const char* kDefaultBccReconstruction = "barycentric";

class RenderData {
 public:
  // ValueError for an unknown --reconstruction (naming the valid ones) or one of another lattice than
  // a BCC dataset's; InputError (one line) for a file that does not open or is not of the lattice named.
  RenderData(const RenderFlags& flags, std::size_t hostCacheBytes, bool quiet);
  // The Cartesian grid `same` renders, with another CC reconstruction (the viewer's choice): the store —
  // its topology, leaf index and bricks' ranges — is shared, so nothing is read again; or the BCC
  // dataset `same` renders, with another BCC reconstruction (its cosets opened again). ValueError for
  // an unknown name or one of another lattice, or when `same` is FCC data (its one reconstruction is
  // boxspline).
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
  // --density-scale and --stop-opacity. ValueError / InputError (one line) for a bad --tf, for the
  // other mode's flags (which would be ignored) and for a --clip box that holds none of the data.
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
  // --dvr-method tetrahedra: paper 002's projected tetrahedra of this BCC dataset (built now, in core;
  // needs a current GL context and applyMode's options), else null. ValueError (one line) for data
  // they do not draw.
  std::unique_ptr<render::ProjectedTetrahedra> projectedTetrahedra(const RenderFlags& flags,
                                                                   const render::RenderOptions& options) const;
  // Damage met so far (io/Damage.h): FCC bricks, Cartesian or BCC leaves, each rendered as a hole.
  io::Damage damage() const;

 private:
  std::unique_ptr<io::FccInput> input_;
  std::unique_ptr<io::BrickStore> fccStore_;
  std::shared_ptr<io::CartesianBrickStore> ccStore_;  // shared by the RenderData of each reconstruction
  std::unique_ptr<render::BrickSource> source_;
  std::unique_ptr<render::PyramidLevels> levels_;
  bool levelSet_ = false;  // a Cartesian or BCC level set (FCC files: the store's rules)
  bool cacheRanges_ = false;  // Cartesian and BCC bricks' ranges kept in the user cache (not --no-cache)
};

}  // namespace fcc::cli
