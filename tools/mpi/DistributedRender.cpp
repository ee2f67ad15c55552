#include "DistributedRender.h"

#include <mpi.h>

#include <chrono>
#include <climits>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <vector>

#include "Compositor.h"
#include "KdPartition.h"
#include "MpiSession.h"
#include "io/ImageOutput.h"
#include "sparse/Error.h"
#include "tools/RenderData.h"
#include "tools/RenderJson.h"
#include "viewer/EglContext.h"
#include "viewer/Raycaster.h"

namespace fcc::mpi {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The thin MPI side of the compositing: one round's pieces, all sent and received at once.
class MpiTransport : public dist::Transport {
 public:
  std::vector<std::vector<float>> exchange(const std::vector<int>& peers, const std::vector<std::vector<float>>& sends,
                                           const std::vector<std::size_t>& recvCounts) override {
    std::vector<std::vector<float>> received(peers.size());
    std::vector<MPI_Request> requests;
    for (std::size_t i = 0; i < peers.size(); ++i) {
      received[i].resize(recvCounts[i]);
      requests.emplace_back();
      MPI_Irecv(received[i].data(), int(recvCounts[i]), MPI_FLOAT, peers[i], kTag, MPI_COMM_WORLD, &requests.back());
    }
    for (std::size_t i = 0; i < peers.size(); ++i) {
      requests.emplace_back();
      MPI_Isend(sends[i].data(), int(sends[i].size()), MPI_FLOAT, peers[i], kTag, MPI_COMM_WORLD, &requests.back());
    }
    MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
    return received;
  }

 private:
  static constexpr int kTag = 20;
};

// Every rank learns whether any failed; the lowest failing rank's message, or nullopt. `allFailed`:
// every rank failed (then they most likely failed alike: the file is missing for all).
std::optional<std::string> agree(const std::string& error, const World& world, bool& allFailed) {
  const int mine = error.empty() ? INT_MAX : world.rank;
  int first = INT_MAX, failures = 0, failed = error.empty() ? 0 : 1;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  MPI_Allreduce(&failed, &failures, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  if (first == INT_MAX) return std::nullopt;
  allFailed = failures == world.size;
  int length = world.rank == first ? int(error.size()) : 0;
  MPI_Bcast(&length, 1, MPI_INT, first, MPI_COMM_WORLD);
  std::string message(std::size_t(length), '\0');
  if (world.rank == first) message = error;
  MPI_Bcast(message.data(), length, MPI_CHAR, first, MPI_COMM_WORLD);
  if (allFailed) return message;
  return "rank " + std::to_string(first) + " of " + std::to_string(world.size) + ": " + message;
}

// Runs `step`; an exception on any rank makes every rank return false, rank 0 having printed one line.
template <class Step>
bool together(const World& world, Step&& step) {
  std::string error;
  try {
    step();
  } catch (const std::exception& e) {
    error = e.what();
    if (error.empty()) error = "unknown error";
  }
  bool allFailed = false;
  const std::optional<std::string> line = agree(error, world, allFailed);
  if (!line) return true;
  if (world.rank == 0) std::fprintf(stderr, "fccvdb: %s\n", line->c_str());
  return false;
}

// The GPU of this rank: its rank on this host (Open MPI's local rank) modulo the GPUs EGL lists.
int localRank(const World& world) {
  if (const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_RANK")) return std::atoi(local);
  return world.rank;
}

}  // namespace

int renderDistributed(const DistributedRenderRequest& request) {
  const World w = world();
  const cli::RenderFlags& flags = request.flags;
  // 1. Everything that can fail on one rank: agreed on before any rank waits for another.
  int width = 0, height = 0;
  render::RenderOptions options;
  std::unique_ptr<cli::RenderData> data;
  render::Camera camera;
  float iso = 0.0f;
  std::string isoBasis;
  const bool ok = together(w, [&] {
    cli::resolutionFromFlags(flags.res, width, height);
    if (w.rank == 0) cli::checkOutputWritable(request.output, request.force);
    options = cli::renderOptionsFromFlags(flags);
    data = std::make_unique<cli::RenderData>(flags, options.hostCacheBytes, request.quiet || w.rank != 0);
    data->applyMode(flags, options);
    const io::IsoChoice choice = data->iso(flags);
    iso = choice.value;
    isoBasis = choice.basis;
    if (options.mode == render::RenderMode::Iso && w.rank == 0) data->warnIfIsoOutside(iso);
    camera = data->camera(flags, double(width) / height);
    options.iso = iso;
  });
  if (!ok) return 1;
  std::unique_ptr<EglContext> gl;
  if (!together(w, [&] { gl = std::make_unique<EglContext>(localRank(w)); })) return 1;

  // 2. The partition: the same on every rank, from the bounds alone.
  const render::BrickSource& source = data->source();
  const bool dvr = options.mode == render::RenderMode::Dvr;
  std::vector<dist::WeightedBrick> bricks;
  source.forEachVaryingBrick([&](const glm::ivec3& brick, float lo, float hi) {
    const bool holds = dvr ? !options.transfer->zeroOn(lo, hi) : (lo <= iso && iso <= hi);
    bricks.push_back({brick, holds ? 1.0 : 0.0});
  });
  const auto partition = std::make_shared<const dist::KdPartition>(bricks, w.size);
  uint64_t owned = 0;
  for (const dist::WeightedBrick& b : bricks) owned += b.weight > 0.0 && partition->ownerOf(b.brick) == w.rank;
  const int rank = w.rank;
  options.ownsBrick = [partition, rank](const glm::ivec3& brick) { return partition->ownerOf(brick) == rank; };
  std::unique_ptr<render::Raycaster> raycaster;
  if (!together(w, [&] { raycaster = std::make_unique<render::Raycaster>(source, options); })) return 1;

  // 3. The frame: from here an error on one rank aborts all (main.cpp), none waits for ever.
  cli::RankReport report;
  report.rank = w.rank;
  report.device = gl->renderer() + " (" + gl->platform() + ")";
  MPI_Barrier(MPI_COMM_WORLD);
  const Clock::time_point frameStart = Clock::now();
  const render::FrameStats stats = raycaster->render(camera, width, height);
  const render::FrameImages images = raycaster->readImages(/*withNormalDepth=*/true);
  report.renderSeconds = secondsSince(frameStart);
  report.passes = stats.passes;
  report.bricksUploaded = stats.bricksUploaded;
  report.bricksRead = raycaster->bricksDecoded();
  report.bricksOwned = owned;
  const std::size_t pixels = std::size_t(width) * height;
  std::vector<float> image(pixels * dist::kPixelFloats);
  for (std::size_t p = 0; p < pixels; ++p) {
    std::memcpy(&image[p * dist::kPixelFloats], &images.rgba[4 * p], 4 * sizeof(float));
    std::memcpy(&image[p * dist::kPixelFloats + 4], &images.normalDepth[4 * p], 4 * sizeof(float));
  }
  const Clock::time_point waitStart = Clock::now();
  MPI_Barrier(MPI_COMM_WORLD);  // so that compositing times the exchange, not the slowest renderer
  report.waitSeconds = secondsSince(waitStart);

  const Clock::time_point compositeStart = Clock::now();
  const glm::dvec3 eyeXyz = glm::dvec3(glm::inverse(source.worldFromIndex()) * glm::dvec4(camera.eye, 1.0));
  MpiTransport transport;
  dist::CompositeStats composite;
  const std::vector<float> piece = dist::compositeRadixK(*partition, w.rank, eyeXyz,
                                                         dvr ? dist::CompositeMode::FrontToBack : dist::CompositeMode::NearestDepth,
                                                         image, transport, composite);
  // The one gather of the final pieces.
  std::vector<int> counts(std::size_t(w.size)), displs(std::size_t(w.size));
  for (int r = 0; r < w.size; ++r) {
    const dist::PixelRange range = dist::finalRange(*partition, r, pixels);
    counts[std::size_t(r)] = int(range.size() * dist::kPixelFloats);
    displs[std::size_t(r)] = int(range.begin * dist::kPixelFloats);
  }
  std::vector<float> final(w.rank == 0 ? image.size() : 0);
  MPI_Gatherv(piece.data(), int(piece.size()), MPI_FLOAT, final.data(), counts.data(), displs.data(), MPI_FLOAT, 0,
              MPI_COMM_WORLD);
  report.compositeSeconds = secondsSince(compositeStart);
  report.bytesSent = composite.bytesSent + (w.rank == 0 ? 0 : piece.size() * sizeof(float));
  report.bytesReceived = composite.bytesReceived;
  if (w.rank == 0)
    for (int r = 1; r < w.size; ++r) report.bytesReceived += uint64_t(counts[std::size_t(r)]) * sizeof(float);
  const double frameSeconds = secondsSince(frameStart);

  // 4. The reports, the damage and the image, on rank 0.
  constexpr int kDeviceChars = 160;
  double numbers[10] = {report.renderSeconds, report.waitSeconds, report.compositeSeconds, double(report.bytesSent),
                        double(report.bytesReceived), double(report.bricksRead), double(report.bricksOwned),
                        double(report.bricksUploaded), double(report.passes), double(data->damage().bricks)};
  char device[kDeviceChars] = {};
  std::strncpy(device, report.device.c_str(), kDeviceChars - 1);
  std::vector<double> allNumbers(w.rank == 0 ? 10 * std::size_t(w.size) : 0);
  std::vector<char> allDevices(w.rank == 0 ? kDeviceChars * std::size_t(w.size) : 0);
  MPI_Gather(numbers, 10, MPI_DOUBLE, allNumbers.data(), 10, MPI_DOUBLE, 0, MPI_COMM_WORLD);
  MPI_Gather(device, kDeviceChars, MPI_CHAR, allDevices.data(), kDeviceChars, MPI_CHAR, 0, MPI_COMM_WORLD);
  uint64_t damaged = data->damage().bricks, damagedAll = 0;
  MPI_Allreduce(&damaged, &damagedAll, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
  int status = damagedAll > 0 && !request.allowDamaged ? 1 : 0;
  if (w.rank != 0) return status;

  std::vector<float> rgba(pixels * 4), normalDepth(pixels * 4);
  for (std::size_t p = 0; p < pixels; ++p) {
    std::memcpy(&rgba[4 * p], &final[p * dist::kPixelFloats], 4 * sizeof(float));
    std::memcpy(&normalDepth[4 * p], &final[p * dist::kPixelFloats + 4], 4 * sizeof(float));
  }
  io::RenderedImage out{width, height, &rgba, &normalDepth, /*normals=*/!dvr};
  io::writeRenderedImage(request.output, out, glm::vec3(0.08f, 0.09f, 0.11f));
  std::vector<cli::RankReport> reports(std::size_t(w.size));
  for (int r = 0; r < w.size; ++r) {
    const double* n = &allNumbers[10 * std::size_t(r)];
    cli::RankReport& rr = reports[std::size_t(r)];
    rr.rank = r;
    rr.renderSeconds = n[0];
    rr.waitSeconds = n[1];
    rr.compositeSeconds = n[2];
    rr.bytesSent = uint64_t(n[3]);
    rr.bytesReceived = uint64_t(n[4]);
    rr.bricksRead = uint64_t(n[5]);
    rr.bricksOwned = uint64_t(n[6]);
    rr.bricksUploaded = uint64_t(n[7]);
    rr.passes = int(n[8]);
    rr.device = std::string(&allDevices[kDeviceChars * std::size_t(r)]);
  }
  if (request.json)
    std::fputs(cli::renderJson(flags.file, request.output, flags.mode, width, height, partition->radices(), frameSeconds, reports).c_str(),
               stdout);
  if (!request.quiet) {
    uint64_t read = 0;
    double slowest = 0.0, compositing = 0.0;
    for (const cli::RankReport& rr : reports) {
      read += rr.bricksRead;
      slowest = std::max(slowest, rr.renderSeconds);
      compositing = std::max(compositing, rr.compositeSeconds);
    }
    const std::string what = dvr ? "dvr (--tf " + flags.tf + ")" : "iso " + std::to_string(iso) +
                                                                      (isoBasis == "--iso" ? "" : " (default: " + isoBasis + ")");
    std::fprintf(stderr, "wrote %s: %dx%d, %s, %d ranks, %llu bricks read in all, slowest render %.3f s, compositing %.3f s\n",
                 request.output.c_str(), width, height, what.c_str(), w.size, (unsigned long long)read, slowest, compositing);
  }
  if (damagedAll > 0)
    std::fprintf(stderr, "fccvdb: %llu damaged brick%s rendered as holes in %s%s\n", (unsigned long long)damagedAll,
                 damagedAll == 1 ? "" : "s", request.output.c_str(), request.allowDamaged ? "" : "; --allow-damaged to exit 0");
  return status;
}

}  // namespace fcc::mpi
