#include "RenderFlags.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "ProgressBar.h"
#include "SurfaceFlags.h"
#include "Triple.h"
#include "io/AtomicOutput.h"
#include "io/ImageOutput.h"
#include "io/PatientMetadata.h"
#include "sparse/Error.h"
#include "viewer/CameraFile.h"

namespace fcc::cli {
namespace {

glm::dvec3 tripleOrThrow(const std::string& text, const char* flag) {
  glm::dvec3 v;
  if (!parseTriple(text, v) || !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw ValueError(std::string(flag) + " '" + text + "': expected three finite numbers X,Y,Z");
  return v;
}

std::size_t mibToBytes(double mib) { return std::size_t(mib * 1024.0 * 1024.0); }

}  // namespace

std::unique_ptr<io::FccInput> openFccInput(const std::string& file, const SourceFlags& source, const std::string& grid,
                                           bool useCache, bool quiet) {
  io::ConvertOptions options;
  options.raw = rawLayoutFromFlags(source, file);
  options.gridName = grid;
  ProgressBar progress(quiet);
  return std::make_unique<io::FccInput>(file, options, useCache, &progress,
                                        quiet ? nullptr : +[](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); });
}

std::unique_ptr<io::FccInput> openFccInput(const RenderFlags& flags, bool quiet) {
  return openFccInput(flags.file, flags.source, flags.grid, !flags.noCache, quiet);
}

void addRenderFlags(CLI::App& app, RenderFlags& flags, bool levelsByDefault) {
  app.add_option("FILE", flags.file,
                 "FCC .vdb file (from fccvdb convert or synth), or anything convert takes (a Cartesian .vdb, NRRD, "
                 "NIfTI, raw with --dims/--type): converted once and cached (--no-cache: a temporary file); or a BCC "
                 "dataset (synth --lattice bcc), rendered as it is")
      ->required();
  app.add_option("--grid", flags.grid, "The FCC grid to render (default: the first); for a Cartesian .vdb, the float grid to convert or render");
  app.add_option("--reconstruction", flags.reconstruction,
                 "How the data between samples is reconstructed: boxspline (FCC data; the default, converting a "
                 "Cartesian FILE), or trilinear, tricubic (interpolating B-spline), tricubic-bspline (approximating), "
                 "type6 (Sorokina-Zeilfelder cubic C1 spline on 24 tetrahedra a cube, paper 003) to render a "
                 "Cartesian .vdb float grid as it is, without converting; for a BCC dataset (grids bcc_primary and "
                 "bcc_secondary, docs/FORMAT.md) barycentric (its default), sheared-trilinear, bilinear-spatial or "
                 "bilinear (paper 002)");
  app.add_option("--mode", flags.mode, "iso: the isosurface; dvr: direct volume rendering (emission and absorption through the reconstructed field, with --tf)")
      ->capture_default_str()->check(CLI::IsMember({"iso", "dvr"}));
  std::string presets;
  for (const std::string& name : transferFunctionPresetNames()) presets += (presets.empty() ? "" : ", ") + name;
  app.add_option("--tf", flags.tf,
                 "DVR transfer function: a preset (" + presets + "; stretched onto the data's value range) or a file: "
                 "ParaView's colour-map JSON (RGBPoints, Points) or text lines `value r g b alpha` (docs/DVR.md)")
      ->capture_default_str()
      ->each([&flags](const std::string&) { flags.tfGiven = true; });
  app.add_option("--unit-distance", flags.unitDistance,
                 "DVR: the world length over which an opacity alpha of the transfer function applies (ParaView's "
                 "scalar-opacity unit distance; default: the grid's voxel size)")
      ->check(CLI::PositiveNumber);
  app.add_option("--density-scale", flags.densityScale, "DVR: multiplies every extinction")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  app.add_option("--stop-opacity", flags.terminationOpacity, "DVR: a ray stops once this opaque (and reads no brick behind)")
      ->capture_default_str()->check(CLI::Range(0.5, 1.0));
  app.add_option("--shading", flags.shading,
                 "DVR: on shades the emission by the reconstruction's gradient (the light's, --light, Lambert term over "
                 "an ambient of 0.3; opacity unchanged); off: unshaded emission")
      ->capture_default_str()->check(CLI::IsMember({"on", "off"}));
  app.add_option("--specular", flags.specular,
                 "DVR with --shading on: a white highlight of this strength, K |cos|^P of the angle between the "
                 "gradient and Blinn-Phong's half vector (the ray itself under the headlight); 0: none")
      ->capture_default_str()->check(CLI::Range(0.0, 1.0));
  app.add_option("--specular-power", flags.specularPower, "DVR: the highlight's exponent P (larger: smaller highlights)")
      ->capture_default_str()->check(CLI::Range(1e-3, 1000.0));
  app.add_option("--light", flags.light,
                 "The light, fixed to the camera: headlight (at the eye; DVR's default), AZIMUTH,ELEVATION in "
                 "degrees, a directional light that far right of the view axis and above it (the isosurface's "
                 "default is 17,30), or kit (DVR: ParaView's light kit, key, fill, two back lights and the "
                 "headlight); DVR: lights --shading on")
      ->type_name("headlight|AZ,EL|kit");
  app.add_option("--dvr-method", flags.dvrMethod,
                 "DVR: ray (the raycaster's integration through the reconstruction), or tetrahedra: paper 002's "
                 "projected tetrahedra, in core, for a BCC dataset with the barycentric reconstruction (render and "
                 "bench render)")
      ->capture_default_str()->check(CLI::IsMember({"ray", "tetrahedra"}));
  app.add_option("--clip", flags.clip,
                 "Clipping box X0,Y0,Z0,X1,Y1,Z1 in world space (info --json gives the data's world_bounds): rays are "
                 "cut to it, bricks outside it are never read");
  addRawFlags(app, flags.source);
  app.add_flag("--no-cache", flags.noCache, "Convert a Cartesian FILE into a temporary file instead of the user cache ($XDG_CACHE_HOME/fccvdb); with --reconstruction, keep no brick ranges there");
  app.add_option("--iso", flags.iso,
                 "Isovalue (default: 0 for a level set; else Otsu's threshold of the samples' histogram, as "
                 "`fccvdb info` suggests; the middle of the range the surface can take for files without one); "
                 "several surfaces at once: up to 4 values separated by commas, e.g. 0.2,0.5 (each crossing is "
                 "composited front to back with its surface's colour and opacity)");
  app.add_option("--surface-color", flags.surfaceColors,
                 "Colour of each --iso surface, in order: #rrggbb or r,g,b (sRGB, 0 to 1), separated by ';' or the flag "
                 "repeated, e.g. '#d9b88f;0.3,0.5,0.9' (default: sand, sky blue, sage, brick red)")
      ->expected(1)
      ->take_all();
  app.add_option("--surface-opacity", flags.surfaceOpacity,
                 "Opacity of each --iso surface, 0 to 1, separated by commas, e.g. 1,0.4 (default: 1, opaque; a "
                 "translucent surface shows what lies behind it)");
  app.add_option("--res", flags.res, "Image size WxH")->capture_default_str();
  app.add_option("--camera", flags.camera,
                 "Camera file FILE.json, as the viewer's C key saves it: {\"eye\": [X,Y,Z], \"lookat\": [X,Y,Z], "
                 "\"up\": [X,Y,Z], \"fov\": DEGREES} (--eye/--lookat/--up/--fov replace its fields)");
  app.add_option("--eye", flags.eye,
                 "Camera position X,Y,Z in world space (default: frames the data; medical data from its anterior side)");
  app.add_option("--lookat", flags.lookat, "Point looked at X,Y,Z (default: the data's centre)");
  app.add_option("--up", flags.up,
                 "Up vector X,Y,Z (default: 0,1,0; for medical data (NIfTI, DICOM, NRRD with an anatomical space, MetaImage with an AnatomicalOrientation) "
                 "the patient's superior direction, or anterior when --eye looks along it)");
  app.add_option("--fov", flags.fov, "Vertical field of view in degrees (default: 40)");
  app.add_option("--gpu-cache", flags.gpuCacheMiB, "GPU brick pool in MiB (default: 1024, or what the driver allows)")
      ->check(CLI::PositiveNumber);
  app.add_option("--host-cache", flags.hostCacheMiB, "Decoded bricks in host memory, MiB (default: a quarter of RAM)")
      ->check(CLI::PositiveNumber);
  std::string layouts;
  for (render::BrickLayout l : render::allBrickLayouts()) layouts += (layouts.empty() ? "" : ", ") + render::brickLayoutName(l);
  app.add_option("--layout", flags.layout,
                 "How the GPU pool stores bricks: " + layouts + ", or auto (one channel when every varying brick fits the GPU cache)")
      ->capture_default_str();
  app.add_option("--lod-bias", flags.lodBias,
                 std::string("Level of detail: draw a file's pyramid (fccvdb pyramid) brick by brick from the level whose voxels match a "
                             "pixel, plus this many levels (-8 to 16; 0: no voxel larger than a pixel; < 0 finer). Isosurface: coarse levels stand in while finer ones load; "
                             "DVR: each brick waits for its level. The bias rises "
                             "when the GPU cache cannot hold the bricks a frame wants. ") +
                     (levelsByDefault ? "Default 0 (a file without a pyramid is drawn at full resolution)"
                                      : "Without it: full resolution (level 0 only)"));
  app.add_flag("--full-resolution", flags.fullResolution,
               "Draw level 0 only, as for a file without a pyramid (measurements)");
  app.add_option("--lookahead", flags.lookahead,
                 "Bricks a ray that reaches a missing brick requests beyond it: more bricks a pass, fewer passes a frame "
                 "while streaming; the image is the same (default: 0 for complete frames of one opaque isosurface at full "
                 "resolution, as render and bench render draw them; 2 for progressive frames, as view and bench stream draw "
                 "them, levels of detail, several surfaces and DVR)")
      ->check(CLI::Range(0, 64));
}

std::optional<float> lodBiasFromFlags(const RenderFlags& flags, bool levelsByDefault) {
  if (flags.fullResolution) {
    if (!flags.lodBias.empty())
      throw ValueError("--lod-bias " + flags.lodBias + " with --full-resolution: give one of them (--full-resolution draws level 0 only)");
    return std::nullopt;
  }
  if (flags.lodBias.empty()) return levelsByDefault ? std::optional<float>(0.0f) : std::nullopt;
  double bias = 0.0;
  char rest = 0;
  if (std::sscanf(flags.lodBias.c_str(), "%lf%c", &bias, &rest) != 1 || !std::isfinite(bias) || bias < -8.0 ||
      bias > 16.0)
    throw ValueError("--lod-bias '" + flags.lodBias + "': expected a number from -8 to 16 (levels added to the one whose voxels match a pixel; 0: none)");
  return float(bias);
}

void warnIfIsoOutside(float iso, const std::string& path, float valueMin, float valueMax) {
  if (iso >= valueMin && iso <= valueMax) return;
  std::fprintf(stderr,
               "fccvdb: warning: isovalue %g is outside the values the reconstruction takes in %s (%g .. %g): no "
               "surface will show; pick --iso in that range\n",
               double(iso), path.c_str(), double(valueMin), double(valueMax));
}

void warnIfIsoOutside(float iso, const io::BrickStore& store) {
  warnIfIsoOutside(iso, store.path(), store.valueMin(), store.valueMax());
}

io::IsoChoice isoFromFlags(const RenderFlags& flags, const io::BrickStore& store) {
  return flags.iso.empty() ? io::defaultIsovalue(store) : isoFromFlags(flags, io::IsoChoice{});
}

io::IsoChoice isoFromFlags(const RenderFlags& flags, const io::IsoChoice& fallback) {
  if (flags.iso.empty()) return fallback;
  return {parseIsoList(flags.iso).front(), "--iso"};
}

std::vector<render::Isosurface> surfacesFromFlags(const RenderFlags& flags, const io::IsoChoice& first) {
  std::vector<float> isos = flags.iso.empty() ? std::vector<float>{first.value} : parseIsoList(flags.iso);
  isos[0] = first.value;
  return surfacesFrom(isos, flags.surfaceColors, flags.surfaceOpacity);
}

void resolutionFromFlags(const std::string& res, int& width, int& height, const char* flag) {
  char x = 0;
  long w = 0, h = 0;
  char rest = 0;
  if (std::sscanf(res.c_str(), "%ld%c%ld%c", &w, &x, &h, &rest) != 3 || (x != 'x' && x != 'X'))
    throw ValueError(std::string(flag) + " '" + res + "': expected WIDTHxHEIGHT, e.g. 1024x1024");
  if (w <= 0 || h <= 0 || w > 16384 || h > 16384)
    throw ValueError(std::string(flag) + " '" + res + "': width and height must be 1 to 16384");
  width = int(w);
  height = int(h);
}

std::string cameraFlags(const render::Camera& camera) {
  const auto number = [](double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", v);
    return std::string(text);
  };
  const auto triple = [&](const glm::dvec3& v) { return number(v.x) + "," + number(v.y) + "," + number(v.z); };
  return "--eye " + triple(camera.eye) + " --lookat " + triple(camera.lookat) + " --up " + triple(camera.up) +
         " --fov " + number(camera.fovYDegrees);
}

render::Camera cameraFromFlags(const RenderFlags& flags, const io::BrickStore& store, double aspect) {
  glm::dvec3 lo, hi;
  store.worldBounds(lo, hi);
  // A medical volume's patient axes (io/PatientMetadata.h): its default camera is upright.
  return cameraFromFlags(flags, lo, hi, io::patientAxesOf(store.index(), store.path()), aspect);
}

render::Camera cameraFromFlags(const RenderFlags& flags, const glm::dvec3& worldLo, const glm::dvec3& worldHi,
                               const std::optional<io::PatientAxes>& patient, double aspect) {
  double fov = 40.0;
  if (!flags.fov.empty()) {
    char* end = nullptr;
    fov = std::strtod(flags.fov.c_str(), &end);
    if (end == flags.fov.c_str() || *end != '\0' || !(fov > 0.0 && fov < 180.0))
      throw ValueError("--fov '" + flags.fov + "': valid is a number of degrees in (0, 180)");
  }
  render::Camera camera;
  if (!flags.camera.empty()) {
    camera = render::readCameraFile(flags.camera);
    if (!flags.fov.empty()) camera.fovYDegrees = fov;
    if (!flags.lookat.empty()) camera.lookat = tripleOrThrow(flags.lookat, "--lookat");
  } else {
    camera = render::frameBox(worldLo, worldHi, fov, aspect);
    if (patient) {  // upright: superior up, the eye on the anterior side (the face towards the viewer)
      const double distance = glm::length(camera.eye - camera.lookat);
      camera.up = patient->superior;
      camera.eye = camera.lookat + glm::normalize(patient->anterior - glm::dot(patient->anterior, patient->superior) * patient->superior) * distance;
    }
    // Rounding noise of the framing and the upright turn (1e-16 where a 0 is meant) would show in the
    // printed camera: components that small against the scene's scale are zeros, in the camera used
    // too (a camera file's and the flags' numbers are the user's, kept as they are).
    const double scale = std::max({1.0, glm::length(camera.eye), glm::length(camera.lookat)});
    for (glm::dvec3* v : {&camera.eye, &camera.lookat})
      for (int a = 0; a < 3; ++a)
        if (std::abs((*v)[a]) < 1e-12 * scale) (*v)[a] = 0.0;
    for (int a = 0; a < 3; ++a)
      if (std::abs(camera.up[a]) < 1e-12 * glm::length(camera.up)) camera.up[a] = 0.0;
    if (!flags.lookat.empty()) {  // the framing distance kept: the eye moves with the look-at point
      const glm::dvec3 lookat = tripleOrThrow(flags.lookat, "--lookat");
      camera.eye += lookat - camera.lookat;
      camera.lookat = lookat;
    }
  }
  if (!flags.eye.empty()) camera.eye = tripleOrThrow(flags.eye, "--eye");
  if (!flags.up.empty()) {
    camera.up = tripleOrThrow(flags.up, "--up");
  } else if (render::viewRunsAlongUp(camera)) {
    // An --eye straight above or below the look-at point along the up vector: that up cannot be kept.
    // Above or below a patient, anterior is up (the axial convention); elsewhere render::upAcross.
    camera.up = patient && flags.camera.empty() ? patient->anterior : render::upAcross(camera.lookat - camera.eye);
  }
  render::cameraFrame(camera, aspect);  // validates: throws for a degenerate camera
  return camera;
}

render::RenderOptions renderOptionsFromFlags(const RenderFlags& flags) {
  render::RenderOptions options;
  const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGESIZE);
  const std::size_t ram = pages > 0 && pageSize > 0 ? std::size_t(pages) * std::size_t(pageSize) : (std::size_t(4) << 30);
  options.hostCacheBytes = flags.hostCacheMiB > 0.0 ? mibToBytes(flags.hostCacheMiB) : ram / 4;
  options.gpuCacheBytes = flags.gpuCacheMiB > 0.0 ? mibToBytes(flags.gpuCacheMiB) : (std::size_t(1) << 30);
  if (!flags.clip.empty()) {
    double v[6];
    char rest = 0;
    const int n = std::sscanf(flags.clip.c_str(), "%lf,%lf,%lf,%lf,%lf,%lf%c", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &rest);
    bool finite = n == 6;
    for (int i = 0; i < 6 && finite; ++i) finite = std::isfinite(v[i]);
    if (!finite)
      throw ValueError("--clip '" + flags.clip + "': expected six finite numbers X0,Y0,Z0,X1,Y1,Z1 (the box's corners, world space)");
    options.clipLo = glm::min(glm::dvec3(v[0], v[1], v[2]), glm::dvec3(v[3], v[4], v[5]));
    options.clipHi = glm::max(glm::dvec3(v[0], v[1], v[2]), glm::dvec3(v[3], v[4], v[5]));
  }
  if (!flags.light.empty()) {
    double azimuth = 0.0, elevation = 0.0;
    char rest = 0;
    if (flags.light == "kit") {
      options.dvrShading.light = render::DvrLight::Kit;  // DVR's only (RenderData::applyMode says so for the isosurface)
    } else if (flags.light == "headlight") {
      options.lightInCamera = glm::vec3(0.0f, 0.0f, 1.0f);
      options.dvrShading.light = render::DvrLight::Headlight;
    } else if (std::sscanf(flags.light.c_str(), "%lf,%lf%c", &azimuth, &elevation, &rest) == 2 &&
               azimuth >= -180.0 && azimuth <= 180.0 && elevation >= -90.0 && elevation <= 90.0) {
      options.lightInCamera = render::lightInCameraFromAngles(float(azimuth), float(elevation));
      options.dvrShading.light = render::DvrLight::Directional;
    } else {
      throw ValueError("--light '" + flags.light + "': valid are headlight, kit, or AZIMUTH,ELEVATION in degrees "
                       "(azimuth -180 to 180 right of the view axis, elevation -90 to 90 above it), e.g. 30,45");
    }
  }
  options.lookahead = flags.lookahead;
  if (flags.layout != "auto") {
    try {
      options.layout = render::parseBrickLayout(flags.layout);
    } catch (const ValueError& e) {
      throw ValueError("--layout: " + std::string(e.what()) + ", or auto");
    }
  }
  return options;
}

void checkOutputWritable(const std::string& path, bool overwrite) {
  io::checkImageExtension(path);
  // A temporary file created and removed: what the writer will do, so root and read-only file
  // systems fail here too, before any rendering.
  io::AtomicOutput probe(path, overwrite);
}

}  // namespace fcc::cli
