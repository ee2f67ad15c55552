#include "AtomicOutput.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "sparse/Error.h"

namespace fcc::io {
namespace fs = std::filesystem;

namespace {

std::string directoryOf(const std::string& path) {
  const fs::path dir = fs::path(path).parent_path();
  return dir.empty() ? "." : dir.string();
}

}  // namespace

void checkOutputPath(const std::string& path, bool overwrite) {
  std::error_code ec;
  if (fs::exists(path, ec) && !overwrite) throw OutputError(path + ": exists; pass --force to overwrite it");
  const std::string dir = directoryOf(path);
  if (!fs::is_directory(dir, ec)) throw OutputError(path + ": cannot write there (directory '" + dir + "' does not exist)");
  if (::access(dir.c_str(), W_OK) != 0)
    throw OutputError(path + ": cannot write there (directory '" + dir + "' is not writable: " + std::strerror(errno) + ")");
}

AtomicOutput::AtomicOutput(std::string finalPath, bool overwrite, const std::string& input)
    : finalPath_(std::move(finalPath)) {
  std::error_code ec;
  if (!input.empty() && fs::exists(finalPath_, ec) && fs::equivalent(finalPath_, input, ec))
    throw OutputError(finalPath_ + ": output is the input file; choose another output path");
  checkOutputPath(finalPath_, overwrite);
  // A unique name beside the output keeps the final rename on one file system.
  const std::string dir = directoryOf(finalPath_);
  std::string pattern = dir + "/." + fs::path(finalPath_).filename().string() + ".tmp.XXXXXX";
  const int fd = mkstemp(pattern.data());
  // access() passes for root everywhere; the file system may still refuse (read-only, /proc).
  if (fd < 0)
    throw OutputError(finalPath_ + ": cannot write there (directory '" + dir + "' is not writable: " + std::strerror(errno) + ")");
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

void writeTextFile(const std::string& path, const std::string& text, bool overwrite) {
  AtomicOutput out(path, overwrite);
  {
    std::ofstream file(out.tempPath(), std::ios::binary);
    file << text;
    if (!file.flush()) throw OutputError("cannot write " + path);
  }
  out.commit();
}

}  // namespace fcc::io
