// This process's resident set from /proc/self/status (VmRSS): every page it holds in memory, the
// caches' and also the mapped files', the GL driver's and the loader threads' (docs/BENCHMARKS.md, "bench
// stream", says what that means for a budget check). 0 where /proc is not there.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstring>

namespace fcc::cli {

inline uint64_t residentSetBytes() {
  std::FILE* status = std::fopen("/proc/self/status", "r");
  if (!status) return 0;
  char line[256];
  unsigned long long kib = 0;
  while (std::fgets(line, sizeof line, status))
    if (std::strncmp(line, "VmRSS:", 6) == 0) {
      std::sscanf(line + 6, "%llu", &kib);
      break;
    }
  std::fclose(status);
  return uint64_t(kib) * 1024;
}

}  // namespace fcc::cli
