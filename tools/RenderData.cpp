#include "RenderData.h"

#include <cstdio>
#include <string>

#include "io/TransferFunctionFile.h"
#include "sparse/Error.h"
#include "viewer/BccBrickSource.h"
#include "viewer/CartesianBrickSource.h"
#include "viewer/FccBrickSource.h"

namespace fcc::cli {

RenderData::RenderData(const RenderFlags& flags, std::size_t hostCacheBytes, bool quiet) : cacheRanges_(!flags.noCache) {
  // A BCC dataset is drawn with a BCC reconstruction, the view-independent one unless one is named.
  const bool bccFile = render::holdsBccGrids(flags.file);
  const std::string name = !flags.reconstruction.empty() ? flags.reconstruction : bccFile ? kDefaultBccReconstruction : "boxspline";
  const ReconstructionInfo& info = findReconstruction(name);
  const Lattice bcc = Lattice::Bcc;
  if (bccFile && info.lattice != Lattice::Bcc)
    throw ValueError("--reconstruction " + std::string(info.name) + ": " + flags.file +
                     " holds a BCC dataset; its reconstructions are " + reconstructionNames(&bcc));
  if (info.lattice == Lattice::Bcc) {
    auto bccSource = std::make_unique<render::BccBrickSource>(flags.file, info, /*cacheRanges=*/!flags.noCache);
    levelSet_ = bccSource->levelSet();
    source_ = std::move(bccSource);
    return;
  }
  if (info.lattice == Lattice::Fcc) {
    input_ = openFccInput(flags, quiet);
    fccStore_ = std::make_unique<io::BrickStore>(input_->path(), flags.grid);
    source_ = std::make_unique<render::FccBrickSource>(*fccStore_, hostCacheBytes);
    return;
  }
  // The bricks' ranges from the user cache, as conversions are (--no-cache: computed every time).
  ccStore_ = std::make_shared<io::CartesianBrickStore>(flags.file, flags.grid, /*cacheRanges=*/!flags.noCache);
  levelSet_ = ccStore_->levelSet();
  source_ = std::make_unique<render::CartesianBrickSource>(*ccStore_, info);
}

RenderData::RenderData(const RenderData& same, const std::string& reconstruction)
    : ccStore_(same.ccStore_), levelSet_(same.levelSet_), cacheRanges_(same.cacheRanges_) {
  if (same.source().slotBlock() == render::SlotBlock::BccPacked) {  // the cosets opened again
    source_ = std::make_unique<render::BccBrickSource>(same.source().path(), findReconstruction(reconstruction), cacheRanges_);
    return;
  }
  if (!ccStore_)
    throw ValueError(same.source().path() + " is FCC data: its one reconstruction is boxspline (a Cartesian .vdb rendered "
                     "as it is, view --reconstruction, offers the CC ones)");
  // CartesianBrickSource refuses a reconstruction of another lattice by name.
  source_ = std::make_unique<render::CartesianBrickSource>(*ccStore_, findReconstruction(reconstruction));
}

RenderData::~RenderData() = default;

io::IsoChoice RenderData::iso(const RenderFlags& flags) const {
  if (fccStore_) return isoFromFlags(flags, *fccStore_);
  if (levelSet_) return isoFromFlags(flags, io::IsoChoice{0.0f, "a level set's zero crossing"});
  return isoFromFlags(flags, io::IsoChoice{0.5f * (source_->valueMin() + source_->valueMax()),
                                           "the middle of the range the surface can take"});
}

void RenderData::warnIfIsoOutside(float iso) const {
  cli::warnIfIsoOutside(iso, source_->path(), source_->valueMin(), source_->valueMax());
}

render::Camera RenderData::camera(const RenderFlags& flags, double aspect) const {
  if (fccStore_) return cameraFromFlags(flags, *fccStore_, aspect);
  glm::dvec3 lo, hi;
  source_->worldBounds(lo, hi);
  return cameraFromFlags(flags, lo, hi, std::nullopt, aspect);  // Cartesian and BCC .vdb files carry no patient axes
}

render::DvrTransfer RenderData::dvrTransfer(const RenderFlags& flags) const {
  const TransferFunction tf = render::fitTransferFunction(io::transferFunctionFromSpec(flags.tf), *source_);
  const OpticalScale scale{flags.unitDistance > 0.0 ? flags.unitDistance : render::defaultUnitDistance(*source_),
                           flags.densityScale};
  return render::DvrTransfer{flags.tf, tf, scale};
}

void RenderData::applyMode(const RenderFlags& flags, render::RenderOptions& options) const {
  if (!flags.clip.empty()) {
    // A box that misses the data would draw an empty image without a word.
    glm::dvec3 lo, hi;
    source_->worldBounds(lo, hi);
    if (glm::any(glm::lessThan(options.clipHi, lo)) || glm::any(glm::greaterThan(options.clipLo, hi))) {
      const auto text = [](const glm::dvec3& v) {
        char s[96];
        std::snprintf(s, sizeof s, "%.6g,%.6g,%.6g", v.x, v.y, v.z);
        return std::string(s);
      };
      throw ValueError("--clip '" + flags.clip + "' holds none of " + source_->path() + ", whose world bounds are " +
                       text(lo) + " to " + text(hi));
    }
  }
  options.mode = render::parseRenderMode(flags.mode);
  if (flags.dvrMethod != "ray" && options.mode != render::RenderMode::Dvr)
    throw ValueError("--dvr-method " + flags.dvrMethod + " draws direct volume rendering: add --mode dvr");
  if (options.mode != render::RenderMode::Dvr) {
    if (flags.shading == "on")
      throw ValueError("--shading on applies to --mode dvr (the isosurface is always shaded)");
    if (flags.specular > 0.0)
      throw ValueError("--specular applies to --mode dvr --shading on");
    if (flags.light == "kit")
      throw ValueError("--light kit lights --mode dvr --shading on; the isosurface takes headlight or AZIMUTH,ELEVATION");
    // The transfer function's flags would be ignored: a user who gives them wants the volume.
    const char* dvrOnly = flags.tfGiven                ? "--tf"
                          : flags.densityScale != 1.0  ? "--density-scale"
                          : flags.unitDistance != 0.0  ? "--unit-distance"
                                                       : nullptr;
    if (dvrOnly) throw ValueError(std::string(dvrOnly) + " applies to direct volume rendering: add --mode dvr");
    return;
  }
  // ... and the isosurfaces' would be too: DVR shows every value through the transfer function.
  if (!flags.iso.empty() || !flags.surfaceColors.empty() || !flags.surfaceOpacity.empty())
    throw ValueError(std::string(!flags.iso.empty() ? "--iso" : !flags.surfaceColors.empty() ? "--surface-color" : "--surface-opacity") +
                     " applies to --mode iso; --mode dvr shows every value through --tf (drop one of them)");
  options.dvrShading.on = flags.shading == "on";
  if (flags.specular > 0.0 && !options.dvrShading.on)
    throw ValueError("--specular lights the gradient shading: add --shading on");
  if (!flags.light.empty() && !options.dvrShading.on)
    throw ValueError("--light lights the gradient shading in --mode dvr: add --shading on");
  options.dvrShading.specular = float(flags.specular);
  options.dvrShading.specularPower = float(flags.specularPower);
  options.transfer = dvrTransfer(flags).table();
  const float background = source_->background();
  if (!options.transfer->zeroOn(background, background))
    std::fprintf(stderr,
                 "fccvdb: warning: --tf %s gives the background value %g of %s an opacity: only bricks with data are "
                 "drawn, not the empty space around them\n",
                 flags.tf.c_str(), double(background), source_->path().c_str());
  options.terminationOpacity = float(flags.terminationOpacity);
}

int RenderData::applyLevels(const RenderFlags& flags, bool levelsByDefault, bool quiet, render::RenderOptions& options) {
  const std::optional<float> bias = lodBiasFromFlags(flags, levelsByDefault);
  options.coarserLevels.clear();
  if (!bias) return 1;
  const auto note = [&](const std::string& why) {
    if (!quiet && !flags.lodBias.empty()) std::fprintf(stderr, "fccvdb: note: --lod-bias: %s: drawn at full resolution\n", why.c_str());
  };
  if (!fccStore_) {
    note(std::string("a ") + (ccStore_ ? "Cartesian grid" : "BCC dataset") + " has no pyramid");
    return 1;
  }
  if (!levels_ || levels_->builtForHostBytes() != options.hostCacheBytes)
    levels_ = std::make_unique<render::PyramidLevels>(*fccStore_, options.hostCacheBytes);
  // --host-cache is the total: level 0's cache gives the coarser levels their share.
  static_cast<render::FccBrickSource&>(*source_).setHostCacheBytes(options.hostCacheBytes - levels_->hostCacheBytes());
  if (levels_->size() == 0) {
    note(fccStore_->path() + " has no pyramid (`fccvdb pyramid` adds one)");
    return 1;
  }
  options.coarserLevels = levels_->sources();
  options.lodBias = *bias;
  return int(levels_->size()) + 1;
}

std::unique_ptr<render::ProjectedTetrahedra> RenderData::projectedTetrahedra(const RenderFlags& flags,
                                                                            const render::RenderOptions& options) const {
  if (flags.dvrMethod != "tetrahedra") return nullptr;
  if (!flags.clip.empty())
    throw ValueError("--dvr-method tetrahedra draws every tetrahedron with data: --clip is the raycaster's (drop one of them)");
  render::ProjectedTetrahedra::Options o;
  o.transfer = options.transfer;
  o.shading = options.dvrShading;
  o.lightInCamera = options.lightInCamera;
  o.timeGpu = options.timeGpu;
  return std::make_unique<render::ProjectedTetrahedra>(*source_, o);
}

io::Damage RenderData::damage() const { return source_->damage(); }

}  // namespace fcc::cli
