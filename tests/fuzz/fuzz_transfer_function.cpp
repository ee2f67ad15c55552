// libFuzzer target of the transfer-function file reader (io/TransferFunctionFile.cpp): ParaView's
// colour-map JSON (parsed by nlohmann-json, then our checks: the map's name, the point arrays, colour
// spaces, midpoints and sharpnesses) and the text format. The first input byte chooses the file's kind
// (.json or .txt), the rest is the file. Whatever reads must be a function that evaluates to colours
// and opacities in [0, 1] and writes back as ParaView JSON that reads back the same, bit for bit.
#include <cmath>
#include <cstdint>
#include <string>

#include "FuzzInputFile.h"
#include "io/TransferFunctionFile.h"
#include "sparse/Error.h"

namespace {

bool samePoints(const fcc::TransferFunction& a, const fcc::TransferFunction& b) {
  return a.colors() == b.colors() && a.opacities() == b.opacities();
}

bool inUnit(double v) { return std::isfinite(v) && v >= 0.0 && v <= 1.0; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string path = fcc::fuzz::inputFolder().write(data[0] & 1 ? "map.json" : "map.txt", data + 1, size - 1);
  try {
    const fcc::TransferFunction tf = fcc::io::readTransferFunctionFile(path);
    // Between and at its points, the function is a colour and an opacity in [0, 1].
    const auto& points = tf.opacities();
    for (size_t i = 0; i < points.size(); ++i) {
      const double next = i + 1 < points.size() ? points[i + 1].x : points[i].x + 1.0;
      for (double v : {points[i].x, 0.5 * (points[i].x + next), points[i].x + 0.1 * (next - points[i].x)}) {
        if (!inUnit(tf.opacity(v))) __builtin_trap();
        const glm::dvec3 rgb = tf.color(v);
        if (!inUnit(rgb.r) || !inUnit(rgb.g) || !inUnit(rgb.b)) __builtin_trap();
      }
    }
    // Written as ParaView JSON, it reads back the same.
    const fcc::TransferFunction back = fcc::io::parseParaViewColorMaps(fcc::io::paraViewColorMapJson(tf, "fuzz"), "back.json");
    if (!samePoints(tf, back)) __builtin_trap();
  } catch (const fcc::InputError&) {
  } catch (const fcc::ValueError&) {
  }
  return 0;
}
