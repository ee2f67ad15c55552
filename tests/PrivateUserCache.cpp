// Gives this test process a user cache folder of its own (tests/PrivateUserCache.h).
#include "PrivateUserCache.h"

#include <stdlib.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace fcc::test {
namespace {

constexpr const char* kNoFolder = "/nonexistent/fccvdb_test_cache";

struct PrivateUserCache {
  std::string dir;
  PrivateUserCache() {
    std::error_code ec;
    std::string pattern = (std::filesystem::temp_directory_path(ec) / "fccvdb_test_cache_XXXXXX").string();
    if (ec || ::mkdtemp(pattern.data()) == nullptr) {
      // No folder of our own: a test that writes the cache fails there rather than in the user's home.
      std::fprintf(stderr, "tests: cannot make a private user cache folder (%s); the cache is unusable\n", pattern.c_str());
      pattern = kNoFolder;
    }
    dir = pattern;
    ::setenv("FCCVDB_CACHE_DIR", dir.c_str(), 1);
    // PoCL (the CPU OpenCL device the kernel tests run on) caches every program it compiles in
    // ~/.cache/pocl, which the tests would fill: its cache goes into this folder too, and goes with
    // it. A POCL_CACHE_DIR the user or CI set is kept; so is PoCL's default when there is no folder.
    if (!std::getenv("POCL_CACHE_DIR") && dir != kNoFolder) {
      const std::string pocl = dir + "/pocl";
      std::error_code ignored;
      std::filesystem::create_directory(pocl, ignored);  // PoCL makes it too; made here for older ones
      ::setenv("POCL_CACHE_DIR", pocl.c_str(), 1);
    }
  }
  ~PrivateUserCache() {
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
  }
};

// Constructed before main() (and so before any test or any `fccvdb` a test starts).
const PrivateUserCache privateCache;

}  // namespace

const std::string& privateUserCacheDir() { return privateCache.dir; }

}  // namespace fcc::test
