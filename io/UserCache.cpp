#include "UserCache.h"

#include <fcntl.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <vector>

namespace fcc::io {
namespace {
namespace fs = std::filesystem;
}  // namespace

std::string conversionCacheDir() {
  if (const char* d = std::getenv("FCCVDB_CACHE_DIR"); d && *d) return d;
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return (fs::path(x) / "fccvdb").string();
  if (const char* h = std::getenv("HOME"); h && *h) return (fs::path(h) / ".cache" / "fccvdb").string();
  return (fs::temp_directory_path() / "fccvdb-cache").string();
}

uint64_t conversionCacheMaxBytes() {
  if (const char* m = std::getenv("FCCVDB_CACHE_MAX_MIB"); m && *m) {
    char* end = nullptr;
    const unsigned long long mib = std::strtoull(m, &end, 10);
    if (end != m && *end == '\0') return uint64_t(mib) << 20;
  }
  return uint64_t(20) << 30;
}

void touchCacheFile(const std::string& path) { ::utimensat(AT_FDCWD, path.c_str(), nullptr, 0); }

void boundCacheFolder(const std::string& dir, const std::string& keep) {
  struct Entry {
    fs::path path;
    fs::file_time_type used;
    uint64_t bytes;
  };
  std::vector<Entry> entries;
  uint64_t total = 0;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const fs::path ext = e.path().extension();
    if (!e.is_regular_file(ec) || (ext != ".vdb" && ext != ".ccranges")) continue;
    const uint64_t bytes = e.file_size(ec);
    entries.push_back({e.path(), e.last_write_time(ec), bytes});
    total += bytes;
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.used < b.used; });
  const uint64_t maxBytes = conversionCacheMaxBytes();
  for (const Entry& e : entries) {
    if (total <= maxBytes) break;
    if (e.path == fs::path(keep)) continue;
    if (fs::remove(e.path, ec)) total -= e.bytes;
  }
}

}  // namespace fcc::io
