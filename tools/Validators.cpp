#include "Command.h"
#include "Triple.h"
#include "kernels/ClBrickKernels.h"

namespace fcc::cli {

CLI::Validator tripleValidator(const std::string& what) {
  return CLI::Validator(
      [what](std::string& value) -> std::string {
        glm::dvec3 v;
        if (!parseTriple(value, v)) return "expected " + what + " as three comma-separated numbers X,Y,Z, got '" + value + "'";
        return {};
      },
      "X,Y,Z");
}

CLI::Option* addDeviceOption(CLI::App& app, std::string& device) {
  CLI::Validator check(
      [](std::string& value) -> std::string { return checkDeviceSelector(value); }, "DEVICE");
  return app.add_option("--cl-device", device, std::string("Where preprocessing runs: ") + kDeviceSelectorHelp)
      ->check(check)
      ->capture_default_str();
}

std::unique_ptr<BrickKernels> preprocessKernels(const std::string& device) { return makeBrickKernels(device); }

}  // namespace fcc::cli
