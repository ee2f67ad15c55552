// Flags shared by `fccvdb render`, `fccvdb bench render` (and the viewer): the grid, the isovalue,
// the image size, the camera and the cache budgets, and turning them into renderer settings.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "io/BrickStore.h"
#include "viewer/Camera.h"
#include "viewer/Raycaster.h"

namespace fcc::cli {

struct RenderFlags {
  std::string file, grid, iso, res = "1024x1024", eye, lookat, up, fov;
  double gpuCacheMiB = 0.0, hostCacheMiB = 0.0;  // 0: the defaults
  std::string layout = "auto";                   // a render::BrickLayout by name, or auto (chooseBrickLayout)
};

// Registers FILE, --grid, --iso, --res, --eye, --lookat, --up, --fov, --gpu-cache, --host-cache, --layout.
void addRenderFlags(CLI::App& app, RenderFlags& flags);

// --iso (default: midway through the data's value range); ValueError if not a finite number.
float isoFromFlags(const RenderFlags& flags, const io::BrickStore& store);
// --res (or `flag`) "WxH"; ValueError naming the flag for anything else or a zero size.
void resolutionFromFlags(const std::string& res, int& width, int& height, const char* flag = "--res");
// The camera: frames the data unless --eye/--lookat/--up/--fov say otherwise.
render::Camera cameraFromFlags(const RenderFlags& flags, const io::BrickStore& store, double aspect);
render::RenderOptions renderOptionsFromFlags(const RenderFlags& flags);

// Fails before any rendering if `path` cannot be written: not .exr/.png, or its directory missing
// or read-only (OutputError).
void checkOutputWritable(const std::string& path);

}  // namespace fcc::cli
