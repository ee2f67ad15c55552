// Gives this test process a user cache folder of its own (tests/PrivateUserCache.h).
#include "PrivateUserCache.h"

#include <stdlib.h>

#include <cstdio>
#include <filesystem>
#include <system_error>

namespace fcc::test {
namespace {

struct PrivateUserCache {
  std::string dir;
  PrivateUserCache() {
    std::error_code ec;
    std::string pattern = (std::filesystem::temp_directory_path(ec) / "fccvdb_test_cache_XXXXXX").string();
    if (ec || ::mkdtemp(pattern.data()) == nullptr) {
      // No folder of our own: a test that writes the cache fails there rather than in the user's home.
      std::fprintf(stderr, "tests: cannot make a private user cache folder (%s); the cache is unusable\n", pattern.c_str());
      pattern = "/nonexistent/fccvdb_test_cache";
    }
    dir = pattern;
    ::setenv("FCCVDB_CACHE_DIR", dir.c_str(), 1);
    // PoCL's compiled kernels: in the build tree, shared by the tests (a fresh folder each would
    // compile every kernel again), not in the user's ~/.cache/pocl. A caller's own setting stays.
    ::setenv("POCL_CACHE_DIR", FCC_TEST_POCL_CACHE_DIR, 0);
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
