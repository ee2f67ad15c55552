// Google Benchmark: `convert` throughput (input voxels per second, reading and writing included) on a
// raw u8 volume, by default the engine CT beside the checkout, with the bounds on the device `convert`
// picks by default (`--cl-device auto`: a GPU, else PoCL's CPU device; the C++ reference without OpenCL):
//   bench_convert [--benchmark_...] [FILE X Y Z]
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "io/Convert.h"
#include "kernels/ClBrickKernels.h"

namespace {

std::string gInput = "../shared/data/engine_256x256x128_uint8.raw.gz";
glm::ivec3 gDims(256, 256, 128);

void runConvert(benchmark::State& state, const std::string& mode) {
  fcc::io::ConvertOptions o;
  o.raw = fcc::io::RawLayout{gDims, fcc::io::ScalarType::U8, false, glm::dvec3(1.0), 0};
  o.mode = mode;
  o.overwrite = true;
  const std::unique_ptr<fcc::BrickKernels> kernels = fcc::makeBrickKernels("auto");  // as convert's default
  o.preprocess = kernels.get();
  if (mode == "resample") o.samples = uint64_t(gDims.x) * gDims.y * gDims.z / 2;  // the subsample's count
  const std::string out = (std::filesystem::temp_directory_path() / "fcc_bench_convert.vdb").string();
  uint64_t voxels = 0;
  for (auto _ : state) voxels += fcc::io::convertToFcc(gInput, out, o).inputVoxels;
  std::filesystem::remove(out);
  state.counters["input_voxels_per_second"] = benchmark::Counter(double(voxels), benchmark::Counter::kIsRate);
}

void BM_ConvertSubsample(benchmark::State& state) { runConvert(state, "subsample"); }
void BM_ConvertResample(benchmark::State& state) { runConvert(state, "resample"); }
BENCHMARK(BM_ConvertSubsample)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ConvertResample)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (argc == 5) {
    gInput = argv[1];
    gDims = glm::ivec3(std::atoi(argv[2]), std::atoi(argv[3]), std::atoi(argv[4]));
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
