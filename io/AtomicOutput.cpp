#include "AtomicOutput.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "sparse/Error.h"

namespace fcc::io {
namespace fs = std::filesystem;

AtomicOutput::AtomicOutput(std::string finalPath, bool overwrite, const std::string& input)
    : finalPath_(std::move(finalPath)) {
  std::error_code ec;
  if (!input.empty() && fs::exists(finalPath_, ec) && fs::equivalent(finalPath_, input, ec))
    throw OutputError(finalPath_ + ": output is the input file; choose another output path");
  if (fs::exists(finalPath_, ec) && !overwrite)
    throw OutputError(finalPath_ + ": exists; pass --force to overwrite it");
  const fs::path dir = fs::path(finalPath_).parent_path();
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw OutputError(finalPath_ + ": directory " + dir.string() + " does not exist");
  // A unique name beside the output keeps the final rename on one file system.
  std::string pattern = (dir.empty() ? std::string() : dir.string() + "/") + "." +
                         fs::path(finalPath_).filename().string() + ".tmp.XXXXXX";
  const int fd = mkstemp(pattern.data());
  if (fd < 0) throw OutputError(finalPath_ + ": cannot create a file beside it: " + std::strerror(errno));
  ::close(fd);
  tempPath_ = pattern;
}

AtomicOutput::~AtomicOutput() {
  if (!committed_ && !tempPath_.empty()) std::remove(tempPath_.c_str());
}

void AtomicOutput::commit() {
  ::chmod(tempPath_.c_str(), 0644);  // mkstemp creates 0600; outputs are ordinary files
  if (std::rename(tempPath_.c_str(), finalPath_.c_str()) != 0)
    throw OutputError(finalPath_ + ": cannot rename the finished output into place: " + std::strerror(errno));
  committed_ = true;
}

}  // namespace fcc::io
