#include "OutputNames.h"

#include <sys/stat.h>

#include <ctime>

namespace fcc::render {
namespace {

bool exists(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0;
}

}  // namespace

std::string uniqueTimestampedStem(const std::string& directory, const std::string& prefix,
                                  const std::vector<std::string>& extensions) {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "-%Y%m%d-%H%M%S", &local);
  const std::string stem = (directory.empty() ? "" : directory + "/") + prefix + stamp;
  const auto taken = [&](const std::string& candidate) {
    for (const std::string& ext : extensions)
      if (exists(candidate + ext)) return true;
    return false;
  };
  std::string candidate = stem;
  for (int n = 2; taken(candidate); ++n) candidate = stem + "-" + std::to_string(n);
  return candidate;
}

}  // namespace fcc::render
