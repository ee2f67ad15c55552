// Flags shared by `fccvdb render`, `fccvdb bench render` (and the viewer): the grid, the isovalue,
// the image size, the camera and the cache budgets, and turning them into renderer settings.
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "SourceFlags.h"
#include "io/BrickStore.h"
#include "io/ConversionCache.h"
#include "io/DefaultIsovalue.h"
#include "viewer/Camera.h"
#include "viewer/Raycaster.h"

namespace fcc::cli {

struct RenderFlags {
  std::string file, grid, iso, res = "1024x1024", eye, lookat, up, fov;
  std::string camera;  // a camera file (viewer/CameraFile.h); --eye/--lookat/--up/--fov replace its fields
  double gpuCacheMiB = 0.0, hostCacheMiB = 0.0;  // 0: the defaults
  std::string layout = "auto";                   // a render::BrickLayout by name, or auto (chooseBrickLayout)
  SourceFlags source;                            // how to read a Cartesian FILE (raw layout)
  bool noCache = false;                          // convert a Cartesian FILE into a temporary file; no cached ranges
  std::string reconstruction;                    // empty: FCC (converting a Cartesian FILE); else by name
  std::string mode = "iso";                      // iso | dvr (render::parseRenderMode)
  std::string tf = "grayscale";                  // DVR: a preset or a file (io/TransferFunctionFile.h)
  bool tfGiven = false;                          // --tf was on the command line (the isosurface refuses it)
  double unitDistance = 0.0;                     // DVR: world units; 0: one index unit of the grid
  double densityScale = 1.0;                     // DVR: multiplies every extinction
  double terminationOpacity = 0.995;             // DVR: a ray stops once this opaque
  std::string shading = "off";                   // DVR: on | off, gradient shading (docs/DVR.md)
  double specular = 0.0, specularPower = 20.0;    // DVR with shading: the specular term
  std::string light;                             // "headlight" or "AZIMUTH,ELEVATION" (degrees); empty: the mode's default
  std::string dvrMethod = "ray";                 // DVR: ray | tetrahedra (BCC barycentric: viewer/ProjectedTetrahedra.h)
  std::string clip;                              // "X0,Y0,Z0,X1,Y1,Z1": the clipping box, world space
  // Several isosurfaces (tools/SurfaceFlags.h): --iso holds 1 to 4 values; a colour and an opacity each.
  std::vector<std::string> surfaceColors;        // --surface-color, each '#rrggbb' or 'r,g,b', ';'-separated
  std::string surfaceOpacity;                    // --surface-opacity "1,0.4"
  // Level of detail (docs/RENDERER.md): --lod-bias B draws a file's pyramid levels with bias B (render
  // and bench render draw full resolution without it; view draws the levels at bias 0 by default);
  // --full-resolution draws level 0 only.
  std::string lodBias;
  bool fullResolution = false;
  int lookahead = render::RenderOptions::kLookaheadAuto;
};

// The bias the levels are drawn with, or none: full resolution (--full-resolution, or neither flag
// where `levelsByDefault` is false). ValueError (one line) for a --lod-bias that is not a number in
// [-8, 16], or given with --full-resolution.
std::optional<float> lodBiasFromFlags(const RenderFlags& flags, bool levelsByDefault);

// Registers FILE, --grid, --iso, --res, --camera, --eye, --lookat, --up, --fov, --gpu-cache, --host-cache, --layout,
// --reconstruction, --mode, --tf, --unit-distance, --density-scale, --stop-opacity, --clip, --lod-bias,
// --full-resolution, the raw input flags (--dims, --type, ...) and --no-cache. `levelsByDefault`: the
// command draws a pyramid's levels without --lod-bias (view), which the help says.
void addRenderFlags(CLI::App& app, RenderFlags& flags, bool levelsByDefault = false);

// FILE as an FCC .vdb: itself, or its conversion (io/ConversionCache.h: cached, or temporary with
// --no-cache), saying so in one line on stderr with a progress bar unless `quiet`.
std::unique_ptr<io::FccInput> openFccInput(const RenderFlags& flags, bool quiet);
// The same for `file` with its raw layout flags, --grid (a Cartesian .vdb's float grid) and the cache
// choice (info's flags, which are not all of render's).
std::unique_ptr<io::FccInput> openFccInput(const std::string& file, const SourceFlags& source, const std::string& grid,
                                           bool useCache, bool quiet);

// --iso's first value, or the default (io/DefaultIsovalue.h, with its basis); ValueError if --iso is
// not a list of 1 to 4 finite numbers (tools/SurfaceFlags.h).
io::IsoChoice isoFromFlags(const RenderFlags& flags, const io::IsoChoice& fallback);
io::IsoChoice isoFromFlags(const RenderFlags& flags, const io::BrickStore& store);
// Every surface: --iso's values (the first replaced by `first`, the default when --iso is not given),
// --surface-color and --surface-opacity (tools/SurfaceFlags.h). ValueError (one line) for a bad list.
std::vector<render::Isosurface> surfacesFromFlags(const RenderFlags& flags, const io::IsoChoice& first);
// One line on stderr if `iso` lies outside [valueMin, valueMax], the range the reconstruction of
// `path` takes (the hull of the bounds): the image would show no surface. Not an error: the user may
// want exactly that.
void warnIfIsoOutside(float iso, const std::string& path, float valueMin, float valueMax);
void warnIfIsoOutside(float iso, const io::BrickStore& store);
// --res (or `flag`) "WxH"; ValueError naming the flag for anything else or a zero size.
void resolutionFromFlags(const std::string& res, int& width, int& height, const char* flag = "--res");
// The flags that give `camera` again, ready to paste: "--eye X,Y,Z --lookat X,Y,Z --up X,Y,Z --fov F",
// every number with all the digits a double needs to come back the same.
std::string cameraFlags(const render::Camera& camera);
// The camera: --camera FILE.json, else one that frames the data (render::frameBox; for medical data,
// whose file records the patient's axes (io/PatientMetadata.h), upright: up is superior and the eye
// lies on the anterior side); --eye/--lookat/--up/--fov replace what they name. Without --up the data's
// superior stays up (anterior, where --eye looks along superior). InputError for damaged patient axes.
render::Camera cameraFromFlags(const RenderFlags& flags, const io::BrickStore& store, double aspect);
// The same for data in the world box [worldLo, worldHi] with the patient's axes if known.
render::Camera cameraFromFlags(const RenderFlags& flags, const glm::dvec3& worldLo, const glm::dvec3& worldHi,
                               const std::optional<io::PatientAxes>& patient, double aspect);
render::RenderOptions renderOptionsFromFlags(const RenderFlags& flags);

// Fails before any rendering if `path` cannot be written: not .exr/.png (ValueError), an existing
// file without `overwrite` (--force), or its directory missing or read-only (io::AtomicOutput's checks).
void checkOutputWritable(const std::string& path, bool overwrite);

}  // namespace fcc::cli
