// fccvdb bench bricks FILE.vdb: the brick path of the out-of-core renderer, stage by stage, without
// rendering. Each stage is timed over the same bricks (the file's leaves in file order, at most
// --bricks of them):
//   open          BrickStore's constructor (topology, leaf index, bounds grid);
//   decode        every brick read and decoded from the file (readBrick), in parallel;
//   file->blocks  the renderer's loader assembling pool-slot halo blocks from a cold host cache
//                 (each block needs its 26 neighbours decoded too);
//   cache->blocks the same from the warm host cache (nothing decoded);
//   blocks->pool  the blocks uploaded into a GPU pool as the renderer uploads them (EGL; --no-gl skips).
// Rates are bricks per second of wall time; the page cache is as the machine has it (run twice for warm).
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "Command.h"
#include "JsonText.h"
#include "io/BrickCache.h"
#include "io/BrickStore.h"
#include "viewer/BrickLoader.h"
#include "viewer/FccBrickSource.h"
#include "viewer/BrickPool.h"
#include "viewer/EglContext.h"

namespace fcc::cli {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

struct Stage {
  std::string name;
  uint64_t bricks = 0;
  double seconds = 0.0;
  uint64_t decoded = 0;  // bricks read from the file by the stage (blocks need their neighbours too)
};

// The bricks with leaves, in file order (the tree's leaf order), at most `limit`.
std::vector<glm::ivec3> leafBricks(const io::BrickStore& store, std::size_t limit) {
  std::vector<glm::ivec3> bricks;
  for (auto leaf = store.index().tree().cbeginLeaf(); leaf && bricks.size() < limit; ++leaf) {
    const openvdb::Coord o = leaf->origin();
    bricks.emplace_back(o.x() / kBrickPackedDim, o.y() / kBrickPackedDim, o.z() / kBrickPackedDim);
  }
  return bricks;
}

// All of `bricks` through a fresh loader on `cache`, taken in the renderer's batches of 256 and given
// back for reuse as the renderer does after uploading them: its path from request to halo block. The
// first `keep` blocks are kept for the upload stage instead.
Stage loadBlocks(const std::string& name, const io::BrickStore& store, io::BrickCache& cache,
                 const std::vector<glm::ivec3>& bricks, std::vector<render::LoadedBrick>* keep, std::size_t keepCount) {
  constexpr std::size_t kBatch = 256;
  const uint64_t decodedBefore = cache.decodedCount();
  const auto start = Clock::now();
  const render::FccBrickSource source(store, cache);
  render::BrickLoader loader(source, 4 * kBatch);  // as the renderer makes it
  loader.request(bricks);
  std::size_t taken = 0;
  for (;;) {
    std::vector<render::LoadedBrick> loaded = loader.take(kBatch, true);
    if (loaded.empty()) break;
    taken += loaded.size();
    if (keep)
      while (keep->size() < keepCount && !loaded.empty()) {
        keep->push_back(std::move(loaded.back()));
        loaded.pop_back();
      }
    loader.recycle(std::move(loaded));
  }
  const double seconds = secondsSince(start);
  return {name, taken, seconds, cache.decodedCount() - decodedBefore};
}

}  // namespace

Command addBenchBricksCommand(CLI::App& bench) {
  struct Args {
    std::string file, grid, layout = "ssbo-vec4";
    std::size_t bricks = 50000;
    int threads = 0;
    bool json = false, noGl = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* app = bench.add_subcommand(
      "bricks", "Bricks per second along the out-of-core path: open, decode, file -> halo blocks, host cache -> blocks, blocks -> GPU pool");
  app->add_option("FILE", args->file, "FCC .vdb file (from fccvdb convert or synth)")->required();
  app->add_option("--grid", args->grid, "The FCC grid (default: the first)");
  app->add_option("--bricks", args->bricks, "Bricks timed: the first N leaves in file order")->capture_default_str()->check(CLI::PositiveNumber);
  app->add_option("--threads", args->threads, "Decoding threads (0: all cores)")->capture_default_str()->check(CLI::NonNegativeNumber);
  app->add_option("--layout", args->layout, "GPU pool layout for the upload stage")->capture_default_str();
  app->add_flag("--no-gl", args->noGl, "Skip the upload stage (no EGL context)");
  app->add_flag("--json", args->json, "One JSON object: stages with bricks, seconds, bricks_per_second");
  return {app, [args]() {
            std::unique_ptr<tbb::global_control> threadLimit;
            if (args->threads > 0)
              threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, args->threads);
            const int threads = int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
            std::vector<Stage> stages;

            auto start = Clock::now();
            const io::BrickStore store(args->file, args->grid);
            stages.push_back({"open", 0, secondsSince(start)});
            const std::vector<glm::ivec3> bricks = leafBricks(store, args->bricks);

            start = Clock::now();
            tbb::parallel_for(std::size_t(0), bricks.size(), [&](std::size_t i) {
              io::BrickValues values;
              store.readBrick(bricks[i], values);
            });
            stages.push_back({"decode", bricks.size(), secondsSince(start), bricks.size()});

            // A host cache that holds every brick the blocks touch (the leaves and their neighbours).
            io::BrickCache cache(store, 27 * bricks.size() * io::BrickCache::kBytesPerBrick);
            stages.push_back(loadBlocks("file->blocks", store, cache, bricks, nullptr, 0));
            std::vector<render::LoadedBrick> blocks;  // for the upload stage: one batch, uploaded round robin
            stages.push_back(loadBlocks("cache->blocks", store, cache, bricks, &blocks, 256));

            std::string device = "-";
            if (!args->noGl) {
              const EglContext gl;
              device = gl.renderer();
              const render::BrickLayout layout = render::parseBrickLayout(args->layout);
              const std::size_t slots = std::min(bricks.size(), render::BrickPool::maxSlots(layout));
              render::BrickPool pool(layout, slots);
              glFinish();
              start = Clock::now();
              // In the renderer's batches of 256, the slots in order.
              std::vector<uint32_t> batchSlots;
              std::vector<const float*> batchBlocks;
              for (std::size_t first = 0; first < bricks.size(); first += 256) {
                batchSlots.clear();
                batchBlocks.clear();
                for (std::size_t i = first; i < std::min(first + 256, bricks.size()); ++i) {
                  batchSlots.push_back(uint32_t(i % slots));
                  batchBlocks.push_back(blocks[i % blocks.size()].halo.data());
                }
                pool.upload(batchSlots, batchBlocks);
              }
              glFinish();
              stages.push_back({"blocks->pool", bricks.size(), secondsSince(start)});
            }

            if (args->json) {
              std::printf("{\"file\": %s, \"threads\": %d, \"device\": %s, \"stages\": [", jsonString(args->file).c_str(),
                          threads, jsonString(device).c_str());
              for (std::size_t i = 0; i < stages.size(); ++i)
                std::printf("%s{\"stage\": %s, \"bricks\": %llu, \"decoded\": %llu, \"seconds\": %s, \"bricks_per_second\": %s}",
                            i ? ", " : "", jsonString(stages[i].name).c_str(), (unsigned long long)stages[i].bricks,
                            (unsigned long long)stages[i].decoded,
                            jsonNumber(stages[i].seconds).c_str(),
                            stages[i].bricks ? jsonNumber(stages[i].bricks / stages[i].seconds).c_str() : "null");
              std::printf("]}\n");
              return 0;
            }
            std::printf("file:    %s (%zu leaves timed, %d threads)\ndevice:  %s\n", args->file.c_str(), bricks.size(),
                        threads, device.c_str());
            for (const Stage& s : stages) {
              if (s.bricks)
                std::printf("%-14s %9.3f s %12.0f bricks/s   (%llu bricks decoded)\n", s.name.c_str(), s.seconds,
                            s.bricks / s.seconds, (unsigned long long)s.decoded);
              else std::printf("%-14s %9.3f s\n", s.name.c_str(), s.seconds);
            }
            return 0;
          }};
}

}  // namespace fcc::cli
