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

#include "sparse/TransferFunction.h"

namespace fcc::io {

// Reads `path` (JSON by the `.json` extension, else the text format). colorMapName: the JSON map to
// take by its "Name" (empty: the first); an InputError lists the names in the file when none matches.
TransferFunction readTransferFunctionFile(const std::string& path, const std::string& colorMapName = "");

// The same from text already read; `path` names it in messages.
TransferFunction parseParaViewColorMaps(const std::string& text, const std::string& path,
                                        const std::string& colorMapName = "");
TransferFunction parseTransferFunctionText(const std::string& text, const std::string& path);

// What `--tf SPEC` names: a preset (transferFunctionPreset: normalized, to be stretched onto the
// data's range), else a file. A SPEC that is neither: a ValueError naming the presets and formats.
TransferFunction transferFunctionFromSpec(const std::string& spec);

}  // namespace fcc::io
