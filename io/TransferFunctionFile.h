// Transfer functions from files (issue 18; docs/DVR.md, "Files"): ParaView's colour-map JSON and a
// plain text format of our own. A file's values (x) are data values as written: the caller stretches
// them onto another range only if it chooses to (TransferFunction::stretchedTo).
//
// - `.json`: ParaView's exported colour maps, a list of objects with "Name", "ColorSpace",
//   "RGBPoints": [x, r, g, b, ...] and optionally "Points": [x, alpha, midpoint, sharpness, ...]
//   (other keys, e.g. "NanColor", are ignored). The first map, or the one named. Without "Points" the
//   opacity is ParaView's default, a ramp from 0 to 1 over the RGBPoints' range. Colours are
//   interpolated in RGB whatever the "ColorSpace" (one of ParaView's names); midpoint and sharpness
//   other than 0.5 and 0.0 (ParaView's defaults: linear) are refused.
// - any other extension: one control point a line, `value r g b alpha` (five numbers, colour and
//   opacity in [0, 1], values non-decreasing), `#` starting a comment, blank lines ignored.
//
// Every problem is an InputError of one line: the file, what is wrong, what is valid.
#pragma once

#include <string>
#include <vector>

#include "sparse/TransferFunction.h"

namespace fcc::io {

// Reads `path` (JSON by the `.json` extension, else the text format). colorMapName: the JSON map to
// take by its "Name" (empty: the first); an InputError lists the names in the file when none matches.
TransferFunction readTransferFunctionFile(const std::string& path, const std::string& colorMapName = "");

// The same from text already read; `path` names it in messages.
TransferFunction parseParaViewColorMaps(const std::string& text, const std::string& path,
                                        const std::string& colorMapName = "");
TransferFunction parseTransferFunctionText(const std::string& text, const std::string& path);

// Every colour map of a ParaView JSON file, in the file's order (each named by its "Name", else by
// the file's path), for the viewer's colour-map choice.
std::vector<TransferFunction> readParaViewColorMaps(const std::string& path);

// `tf` as ParaView's colour-map JSON: a list of one map {"Name", "ColorSpace": "RGB", "RGBPoints",
// "Points" (each opacity point's midpoint and sharpness as tf holds them)}, numbers written so that
// they read back bit for bit.
std::string paraViewColorMapJson(const TransferFunction& tf, const std::string& name);
// The same written to `path` atomically (io/AtomicOutput.h; OutputError as writeTextFile's).
void writeParaViewColorMap(const std::string& path, const TransferFunction& tf, const std::string& name,
                           bool overwrite);

// `--tf SPEC` split into a file and a colour map's name: "FILE.json:NAME" (the last ".json:" in SPEC,
// any case) names the map NAME of FILE.json, unless SPEC itself is an existing file; anything else is
// the file (or preset) alone, with an empty name.
struct TransferFunctionSpec {
  std::string path;
  std::string colorMapName;
};
TransferFunctionSpec splitTransferFunctionSpec(const std::string& spec);

// What `--tf SPEC` names: a preset (transferFunctionPreset: normalized, to be stretched onto the
// data's range), else a file, or a ParaView file's map by name ("FILE.json:NAME"; an InputError lists
// the file's names when none matches). A SPEC that is neither: a ValueError naming the presets and
// formats.
TransferFunction transferFunctionFromSpec(const std::string& spec);

}  // namespace fcc::io
