// The test suite never writes into the user's own cache folder ($XDG_CACHE_HOME/fccvdb or
// ~/.cache/fccvdb, io/UserCache.h): every test executable links tests/PrivateUserCache.cpp, which
// points FCCVDB_CACHE_DIR at a fresh folder of its own in TMPDIR before main() runs and removes it at
// exit. CTest runs each test case in its own process, so each test has its own cache folder, and the
// `fccvdb` processes a test starts inherit it. A test that wants a folder of its own sets the variable
// with a ScopedEnv, which puts the private folder back afterwards. PoCL's kernel cache (POCL_CACHE_DIR,
// unless set already) goes to the build tree's pocl-cache, shared by the tests.
#pragma once

#include <cstdlib>
#include <optional>
#include <string>

namespace fcc::test {

// The folder FCCVDB_CACHE_DIR was set to for this process.
const std::string& privateUserCacheDir();

// Sets (or, with nullptr, unsets) an environment variable while it lives; then restores its former value
// or absence.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) previous_ = old;
    if (value)
      ::setenv(name, value, 1);
    else
      ::unsetenv(name);
  }
  ~ScopedEnv() {
    if (previous_)
      ::setenv(name_.c_str(), previous_->c_str(), 1);
    else
      ::unsetenv(name_.c_str());
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  std::string name_;
  std::optional<std::string> previous_;
};

}  // namespace fcc::test
