// fccvdb bench convert [INPUT.vdb]: the conversion of a Cartesian .vdb against OpenVDB's own full read
// of the same file, each in a process of its own, timed (wall clock) and measured (peak resident set,
// of the process and the guard process it spawns). Without INPUT, a narrow-band level-set sphere of --radius
// voxels is made with OpenVDB first (the most common .vdb there is; its interior is tiles).
//
// The figures: seconds and peak RSS of both; the ratio convert / read; input (active) voxels per second.
#include <fcntl.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <thread>
#include <string>
#include <vector>

#include "Command.h"
#include "JsonText.h"
#include "io/VdbFile.h"
#include "sparse/Error.h"

extern char** environ;

namespace fcc::cli {
namespace {

struct Measured {
  double seconds = 0.0;
  double peakRssMiB = 0.0;
};

// Runs this executable with `args` (stdout and stderr to /dev/null unless the run fails) and
// measures it; throws with its last error line if it fails.
Measured runSelf(const std::vector<std::string>& args, const std::string& errPath) {
  std::vector<std::string> words{"/proc/self/exe"};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const auto start = std::chrono::steady_clock::now();
  const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw Error("bench convert: cannot start " + words[1]);
  int status = 0;
  rusage usage{};
  while (::wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  Measured m;
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  m.peakRssMiB = double(usage.ru_maxrss) / 1024.0;  // KiB; includes the children it waited for
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    FILE* f = std::fopen(errPath.c_str(), "r");
    std::string last;
    char line[1024];
    while (f && std::fgets(line, sizeof line, f)) last = line;
    if (f) std::fclose(f);
    throw Error("bench convert: `fccvdb " + args[0] + " " + args[1] + "` failed: " + last);
  }
  return m;
}

// The last line a stage wrote on stderr (without its newline).
std::string lastLineOf(const std::string& path) {
  FILE* f = std::fopen(path.c_str(), "r");
  std::string last;
  char line[1024];
  while (f && std::fgets(line, sizeof line, f)) last = line;
  if (f) std::fclose(f);
  while (!last.empty() && (last.back() == '\n' || last.back() == '\r')) last.pop_back();
  return last;
}

// What the OpenVDB read stage does: every grid, every buffer, no delayed loading.
void readFully(const std::string& path) {
  initializeVdb();
  openvdb::io::File file(path);
  file.setCopyMaxBytes(0);
  file.open(false);
  openvdb::GridPtrVecPtr grids = file.getGrids();
  uint64_t active = 0;
  for (const auto& g : *grids) active += g->activeVoxelCount();
  file.close();
  std::printf("%llu\n", (unsigned long long)active);
}

// The level-set sphere the benchmark converts when given no input.
void makeSphere(const std::string& path, double radius) {
  if (path.empty()) throw ValueError("--stage make needs --keep FILE");
  initializeVdb();
  auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(float(radius), openvdb::Vec3f(0.0f), 1.0f, 3.0f);
  sphere->setName("sphere");
  openvdb::io::File file(path);
  file.write(openvdb::GridCPtrVec{sphere});
  file.close();
}

struct Args {
  std::string input, stage, device = "auto", keep;
  double radius = 600.0;
  int repetitions = 1;
  bool printJson = false;
};

}  // namespace

Command addBenchConvertCommand(CLI::App& bench) {
  auto args = std::make_shared<Args>();
  CLI::App* app = bench.add_subcommand(
      "convert", "Convert a Cartesian .vdb (default: a level-set sphere made here) and compare with OpenVDB's full read of it: seconds, peak RSS");
  app->add_option("INPUT", args->input, "A .vdb with a float grid (default: make a level-set sphere of --radius voxels)");
  app->add_option("--radius", args->radius, "Radius in voxels of the level-set sphere made when no INPUT is given (half width 3)")
      ->check(CLI::Range(4.0, 5000.0))->capture_default_str();
  app->add_option("--keep", args->keep, "Write the made sphere here and keep it (default: a temporary file, removed)");
  app->add_option("--repetitions", args->repetitions, "Runs of each stage; the fastest is reported")
      ->check(CLI::Range(1, 20))->capture_default_str();
  app->add_flag("--json", args->printJson, "One JSON object on stdout");
  app->add_option("--stage", args->stage, "internal: run one stage (read, make) in this process")->group("");
  addDeviceOption(*app, args->device);
  return {app, [args]() {
            if (args->stage == "read") {
              readFully(args->input);
              return 0;
            }
            if (args->stage == "make") {
              makeSphere(args->keep, args->radius);
              return 0;
            }
            if (!args->stage.empty()) throw ValueError("--stage " + args->stage + " is not valid (valid: read, make)");
            const std::filesystem::path tmp = std::filesystem::temp_directory_path() /
                                              ("fccvdb_bench_convert_" + std::to_string(::getpid()));
            std::filesystem::create_directories(tmp);
            struct Cleanup {
              std::filesystem::path dir;
              ~Cleanup() { std::error_code ec; std::filesystem::remove_all(dir, ec); }
            } cleanup{tmp};
            const std::string err = (tmp / "stderr.txt").string(), out = (tmp / "out.vdb").string();
            std::string input = args->input;
            if (input.empty()) {
              // In a process of its own: a child starts with its parent's peak RSS as its own
              // (exec keeps it), so this process stays as small as it started.
              input = args->keep.empty() ? (tmp / "sphere.vdb").string() : args->keep;
              char radius[32];
              std::snprintf(radius, sizeof radius, "%.17g", args->radius);
              const Measured made = runSelf({"bench", "convert", "--stage", "make", "--keep", input, "--radius", radius}, err);
              std::fprintf(stderr, "made %s: level-set sphere, radius %g voxels, half width 3 (%.1f s)\n", input.c_str(),
                           args->radius, made.seconds);
            }
            struct stat st {};
            if (::stat(input.c_str(), &st) != 0) throw InputError(input + ": cannot open");
            Measured read{1e30, 0}, convert{1e30, 0};
            std::string stages;
            for (int i = 0; i < args->repetitions; ++i) {
              const Measured r = runSelf({"bench", "convert", input, "--stage", "read"}, err);
              const Measured c =
                  runSelf({"convert", input, out, "--force", "--quiet", "--timings", "--cl-device", args->device}, err);
              if (r.seconds < read.seconds) read = r;
              if (c.seconds < convert.seconds) {
                convert = c;
                stages = lastLineOf(err);  // "timings: ..."
              }
            }
            // The input's active voxels, from the converted file's provenance would need a read; the
            // topology is cheap: open with delayed loading (nothing but topology is read).
            initializeVdb();
            openvdb::io::File file(input);
            file.open(true);
            uint64_t active = 0;
            for (auto name = file.beginName(); name != file.endName(); ++name) active += file.readGrid(*name)->activeVoxelCount();
            file.close();
            const double ratio = convert.seconds / read.seconds;
            const unsigned cores = std::thread::hardware_concurrency();
            if (args->printJson) {
              std::printf("{\"input\": %s, \"file_mib\": %s, \"active_voxels\": %llu, \"cores\": %u, "
                          "\"read_seconds\": %s, \"read_peak_rss_mib\": %s, \"convert_seconds\": %s, "
                          "\"convert_peak_rss_mib\": %s, \"ratio\": %s, \"voxels_per_second\": %s, \"stages\": %s}\n",
                          jsonString(input).c_str(), jsonNumber(double(st.st_size) / (1 << 20)).c_str(),
                          (unsigned long long)active, cores, jsonNumber(read.seconds).c_str(),
                          jsonNumber(read.peakRssMiB).c_str(), jsonNumber(convert.seconds).c_str(),
                          jsonNumber(convert.peakRssMiB).c_str(), jsonNumber(ratio).c_str(),
                          jsonNumber(double(active) / convert.seconds).c_str(), jsonString(stages).c_str());
            } else {
              std::printf("input: %s (%.0f MiB, %llu active voxels), %u cores\n", input.c_str(),
                          double(st.st_size) / (1 << 20), (unsigned long long)active, cores);
              std::printf("OpenVDB full read: %8.2f s  peak RSS %7.0f MiB\n", read.seconds, read.peakRssMiB);
              std::printf("fccvdb convert:    %8.2f s  peak RSS %7.0f MiB  (%.2fx the read, %.1f M input voxels/s)\n",
                          convert.seconds, convert.peakRssMiB, ratio, double(active) / convert.seconds / 1e6);
              std::printf("%s\n", stages.c_str());
            }
            return 0;
          }};
}

}  // namespace fcc::cli
