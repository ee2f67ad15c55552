// The fuzzer's input as a file. The readers take paths (they read with pread, stdio and zlib, and OpenVDB
// opens its own std::ifstream), so each input is written to a file in a private folder made once per
// process — in /dev/shm where there is one, so that thousands of rewrites a second stay in memory.
#pragma once

#include <stdlib.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace fcc::fuzz {

class InputFolder {
 public:
  InputFolder() {
    const bool shm = ::access("/dev/shm", W_OK) == 0;
    std::string pattern = (shm ? std::string("/dev/shm") : std::filesystem::temp_directory_path().string()) +
                          "/fccvdb_fuzz_XXXXXX";
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot make a folder for fuzz inputs");
    dir_ = pattern;
  }
  ~InputFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(dir_, ignored);
  }
  InputFolder(const InputFolder&) = delete;
  InputFolder& operator=(const InputFolder&) = delete;

  // Writes `size` bytes as the file `name` in the folder (replacing it) and returns its path.
  std::string write(const std::string& name, const uint8_t* data, size_t size) const {
    const std::string path = dir_ + "/" + name;
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (f == nullptr || (size > 0 && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0)
      throw std::runtime_error("cannot write the fuzz input " + path);
    return path;
  }

 private:
  std::string dir_;
};

// One folder per process, removed at exit (a crash leaves it behind, with the input that crashed).
inline const InputFolder& inputFolder() {
  static const InputFolder folder;
  return folder;
}

}  // namespace fcc::fuzz
