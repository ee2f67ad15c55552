#include "Command.h"
#include "Triple.h"

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

}  // namespace fcc::cli
