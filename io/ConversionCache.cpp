#include "ConversionCache.h"

#include <fcntl.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <vector>

#include "VdbLeafReader.h"
#include "sparse/Error.h"
#include "sparse/FccGrid.h"

namespace fcc::io {
namespace {

namespace fs = std::filesystem;

// Bumped when a conversion of the same source and flags would give another file.
constexpr const char* kCacheFormat = "fccvdb-cache-2";

uint64_t fnv1a(const std::string& s) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

// Everything the converted file depends on.
std::string describe(const std::string& input, const ConvertOptions& o) {
  struct stat st {};
  if (::stat(input.c_str(), &st) != 0) throw InputError(input + ": cannot open: no such file");
  std::ostringstream d;
  d << std::hexfloat;  // every bit of every floating-point flag: 0.5 and 0.5000001 are other conversions
  d << kCacheFormat << '\n' << fs::canonical(input).string() << '\n' << st.st_size << ' ' << st.st_mtim.tv_sec << '.'
    << st.st_mtim.tv_nsec << '\n' << o.mode << ' ' << o.samples << ' ' << o.scale << ' '
    << o.background.has_value() << ' ' << o.background.value_or(0.0f) << ' ' << o.prefilter << ' ' << o.tolerance << ' '
    << o.half << ' ' << o.gridName << ' ' << o.bounds;
  // A DICOM series is a folder: what its files are, not the folder's own size and time.
  std::error_code ec;
  if (fs::is_directory(input, ec)) {
    std::vector<std::string> files;
    for (const fs::directory_entry& e : fs::directory_iterator(input, ec)) {
      struct stat f {};
      if (::stat(e.path().c_str(), &f) != 0 || !S_ISREG(f.st_mode)) continue;
      files.push_back(e.path().filename().string() + ' ' + std::to_string(f.st_size) + ' ' +
                      std::to_string(f.st_mtim.tv_sec) + '.' + std::to_string(f.st_mtim.tv_nsec));
    }
    std::sort(files.begin(), files.end());
    for (const std::string& f : files) d << '\n' << f;
  }
  if (o.raw)
    d << " raw " << o.raw->dims.x << ',' << o.raw->dims.y << ',' << o.raw->dims.z << ' ' << int(o.raw->type) << ' '
      << o.raw->bigEndian << ' ' << o.raw->spacing.x << ',' << o.raw->spacing.y << ',' << o.raw->spacing.z << ' '
      << o.raw->headerBytes;
  return d.str();
}

std::string temporaryPath() {
  std::string pattern = (fs::temp_directory_path() / "fccvdb-XXXXXX.vdb").string();
  const int fd = ::mkstemps(pattern.data(), 4);
  if (fd < 0) throw OutputError(pattern + ": cannot create a temporary file for the FCC conversion");
  ::close(fd);
  return pattern;
}

}  // namespace

bool holdsFccGrid(const std::string& path) {
  if (detectFormat(path) != Format::Vdb) return false;
  for (const VdbGridEntry& g : VdbLeafReader::listGrids(path))
    if (g.type == kFccTreeTypeName) return true;
  return false;
}

FccInput::FccInput(const std::string& input, const ConvertOptions& options, bool useCache,
                   openvdb::util::NullInterrupter* progress, void (*say)(const std::string&)) {
  if (holdsFccGrid(input)) {
    path_ = input;
    return;
  }
  ConvertOptions o = options;
  o.overwrite = true;
  if (useCache) {
    const fs::path dir = conversionCacheDir();
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw OutputError(dir.string() + ": cannot create the conversion cache folder (" + ec.message() +
                              "); set FCCVDB_CACHE_DIR or use --no-cache");
    char key[17];
    std::snprintf(key, sizeof key, "%016llx", (unsigned long long)fnv1a(describe(input, o)));
    path_ = (dir / (fs::path(input).filename().string() + "-" + key + ".vdb")).string();
    if (fs::exists(path_)) {
      touchCacheFile(path_);
      origin_ = Origin::CacheHit;
      if (say) say("using the FCC conversion of " + input + " cached as " + path_);
      return;
    }
    if (say) o.onOpened = [say, line = "converting " + input + " to FCC once, to be cached as " + path_ + " (--no-cache: a temporary file)"] { say(line); };
    convertToFcc(input, path_, o, progress);
    origin_ = Origin::Converted;
    boundCacheFolder(dir.string(), path_);
    return;
  }
  path_ = temporaryPath();
  origin_ = Origin::Temporary;
  if (say) o.onOpened = [say, line = "converting " + input + " to a temporary FCC file " + path_] { say(line); };
  try {
    convertToFcc(input, path_, o, progress);
  } catch (...) {
    std::error_code ignored;
    fs::remove(path_, ignored);
    throw;
  }
}

FccInput::~FccInput() {
  if (origin_ != Origin::Temporary) return;
  std::error_code ignored;
  fs::remove(path_, ignored);
}

}  // namespace fcc::io
