// Runs the built `fccvdb` as a user would, capturing exit status, stdout and stderr.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fcc::test {

struct CommandResult {
  int status = -1;
  std::string out, err;
};

inline std::string readText(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs a shell command line; `stdinText` is fed on standard input.
inline CommandResult runShell(const std::string& commandLine, const std::string& stdinText = {}) {
  const auto dir = std::filesystem::temp_directory_path();
  const std::string tag = std::to_string(::getpid()) + "_" + std::to_string(std::rand());
  const auto in = dir / ("fcc_in_" + tag), out = dir / ("fcc_out_" + tag), err = dir / ("fcc_err_" + tag);
  std::ofstream(in) << stdinText;
  const std::string cmd = commandLine + " <" + in.string() + " >" + out.string() + " 2>" + err.string();
  const int raw = std::system(cmd.c_str());
  CommandResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  r.out = readText(out);
  r.err = readText(err);
  std::filesystem::remove(in);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

// `args` is appended to the executable's path as shell words.
inline CommandResult runFccvdb(const std::string& args, const std::string& stdinText = {}) {
  return runShell(std::string(FCC_FCCVDB_EXE) + " " + args, stdinText);
}

// A render that failed because this machine has no EGL/OpenGL 4.5: outside CI the test has nothing to
// check and skips; under CI (variable CI set) it never counts as that, so the test fails.
inline bool failedForLackOfGl(const CommandResult& r) {
  return r.status != 0 && !std::getenv("CI") && r.err.find("EGL") != std::string::npos;
}

inline int lineCount(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

// A fresh directory removed at the end of the test.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    path = std::filesystem::temp_directory_path() / ("fcc_test_" + std::to_string(::getpid()) + "_" + std::to_string(std::rand()));
    std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  std::string operator/(const std::string& name) const { return (path / name).string(); }
  // Files in the directory (to check that nothing half-written was left behind).
  int fileCount() const {
    int n = 0;
    for (auto& e : std::filesystem::directory_iterator(path)) n += e.is_regular_file();
    return n;
  }
};

// Runs `script` (Python asserts) on `jsonText` (a command's --json output), both written into `dir`;
// returns python3's exit status (0: every assert held).
inline int checkJsonWithPython(const TempDir& dir, const std::string& jsonText, const std::string& script) {
  const std::string json = dir / "check.json", check = dir / "check.py";
  std::ofstream(json) << jsonText;
  std::ofstream(check) << "import json,sys\nrows = json.load(open(sys.argv[1]))\n" << script;
  return std::system(("python3 " + check + " " + json).c_str());
}

}  // namespace fcc::test
