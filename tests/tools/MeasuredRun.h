// Runs the built `fccvdb` as its own process and measures its peak resident set size (wait4's
// ru_maxrss: the process, or the largest of the children it waited for, such as the guarded read).
#pragma once

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <string>
#include <vector>

#include "RunCommand.h"

extern char** environ;

namespace fcc::test {

struct MeasuredRun {
  int status = -1;
  long peakRssKiB = 0;  // ru_maxrss of the process
  std::string err;
};

// Runs fccvdb with `args` as its own process and reads its peak resident set size (wait4).
inline MeasuredRun runMeasured(const std::vector<std::string>& args, const TempDir& dir) {
  std::vector<std::string> words{FCC_FCCVDB_EXE};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const std::string errPath = dir / "stderr.txt";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  MeasuredRun run;
  const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return run;
  int status = 0;
  rusage usage{};
  if (::wait4(pid, &status, 0, &usage) != pid) return run;
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  run.peakRssKiB = usage.ru_maxrss;
  run.err = readText(errPath);
  return run;
}

}  // namespace fcc::test
