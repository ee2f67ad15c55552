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
#include "tools/BenchOrbit.h"
#include "tools/RenderData.h"
#include "tools/RenderJson.h"
#include "tools/SurfaceFlags.h"
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

// A rank's part of distributed rendering: the data, its GPU, the partition and its renderer. open()
// agrees with the other ranks on everything that can fail on one of them; frame() and reports() are
// collective.
class DistributedRenderer {
 public:
  // Null on every rank (rank 0 printed one line) when any rank failed.
  static std::unique_ptr<DistributedRenderer> open(const cli::RenderFlags& flags, const std::string& output, bool force,
                                                   bool quiet, const World& w) {
    auto r = std::unique_ptr<DistributedRenderer>(new DistributedRenderer);
    r->world_ = w;
    const bool ok = together(w, [&] {
      cli::resolutionFromFlags(flags.res, r->width_, r->height_);
      if (w.rank == 0 && !output.empty()) cli::checkOutputWritable(output, force);
      r->options_ = cli::renderOptionsFromFlags(flags);
      r->data_ = std::make_unique<cli::RenderData>(flags, r->options_.hostCacheBytes, quiet || w.rank != 0);
      r->data_->applyMode(flags, r->options_);
      const io::IsoChoice choice = r->data_->iso(flags);
      if (r->options_.mode == render::RenderMode::Iso) {
        // Ranks composite the nearest crossing per pixel: one opaque surface. Translucent or several
        // surfaces need every crossing in visibility order, which the compositor does not do yet.
        const std::vector<render::Isosurface> surfaces = cli::surfacesFromFlags(flags, choice);
        if (surfaces.size() > 1 || surfaces.front().opacity < 1.0f)
          throw ValueError("--iso with several surfaces or --surface-opacity below 1 is not composited across MPI ranks "
                           "(valid under mpirun: one opaque surface, or --mode dvr)");
        cli::setSurfaces(r->options_, surfaces);
      }
      r->options_.iso = choice.value;
      r->isoBasis_ = choice.basis;
      if (r->options_.mode == render::RenderMode::Iso && w.rank == 0) r->data_->warnIfIsoOutside(choice.value);
      r->camera_ = r->data_->camera(flags, double(r->width_) / r->height_);
    });
    if (!ok) return nullptr;
    if (!together(w, [&] { r->gl_ = std::make_unique<EglContext>(localRank(w)); })) return nullptr;
    // The partition: the same on every rank, from the bounds alone.
    const render::BrickSource& source = r->data_->source();
    const bool dvr = r->dvr();
    const float iso = r->options_.iso;
    std::vector<dist::WeightedBrick> bricks;
    source.forEachVaryingBrick([&](const glm::ivec3& brick, float lo, float hi) {
      const bool holds = dvr ? !r->options_.transfer->zeroOn(lo, hi) : (lo <= iso && iso <= hi);
      bricks.push_back({brick, holds ? 1.0 : 0.0});
    });
    r->partition_ = std::make_shared<const dist::KdPartition>(bricks, w.size);
    for (const dist::WeightedBrick& b : bricks) r->owned_ += b.weight > 0.0 && r->partition_->ownerOf(b.brick) == w.rank;
    const auto partition = r->partition_;
    const int rank = w.rank;
    r->options_.ownsBrick = [partition, rank](const glm::ivec3& brick) { return partition->ownerOf(brick) == rank; };
    if (!together(w, [&] { r->raycaster_ = std::make_unique<render::Raycaster>(source, r->options_); })) return nullptr;
    return r;
  }

  // One frame from every rank, composited; the image (8 floats a pixel) on rank 0, empty elsewhere.
  // From here an error on one rank aborts all (main.cpp): none waits for ever.
  std::vector<float> frame(const render::Camera& camera, cli::RankReport& report) {
    const World& w = world_;
    report.rank = w.rank;
    report.device = gl_->renderer() + " (" + gl_->platform() + ")";
    const uint64_t decodedBefore = raycaster_->bricksDecoded();
    MPI_Barrier(MPI_COMM_WORLD);
    const Clock::time_point frameStart = Clock::now();
    const render::FrameStats stats = raycaster_->render(camera, width_, height_);
    const render::FrameImages images = raycaster_->readImages(/*withNormalDepth=*/true);
    report.renderSeconds = secondsSince(frameStart);
    report.passes = stats.passes;
    report.bricksUploaded = stats.bricksUploaded;
    report.bricksRead = raycaster_->bricksDecoded() - decodedBefore;
    report.bricksOwned = owned_;
    const std::size_t pixels = std::size_t(width_) * height_;
    std::vector<float> image(pixels * dist::kPixelFloats);
    for (std::size_t p = 0; p < pixels; ++p) {
      std::memcpy(&image[p * dist::kPixelFloats], &images.rgba[4 * p], 4 * sizeof(float));
      std::memcpy(&image[p * dist::kPixelFloats + 4], &images.normalDepth[4 * p], 4 * sizeof(float));
    }
    const Clock::time_point waitStart = Clock::now();
    MPI_Barrier(MPI_COMM_WORLD);  // so that compositing times the exchange, not the slowest renderer
    report.waitSeconds = secondsSince(waitStart);

    const Clock::time_point compositeStart = Clock::now();
    const glm::dvec3 eyeXyz = glm::dvec3(glm::inverse(data_->source().worldFromIndex()) * glm::dvec4(camera.eye, 1.0));
    MpiTransport transport;
    dist::CompositeStats composite;
    const std::vector<float> piece =
        dist::compositeRadixK(*partition_, w.rank, eyeXyz, dvr() ? dist::CompositeMode::FrontToBack : dist::CompositeMode::NearestDepth,
                              image, transport, composite);
    // The one gather of the final pieces.
    std::vector<int> counts(static_cast<std::size_t>(w.size)), displs(static_cast<std::size_t>(w.size));
    for (int r = 0; r < w.size; ++r) {
      const dist::PixelRange range = dist::finalRange(*partition_, r, pixels);
      counts[std::size_t(r)] = int(range.size() * dist::kPixelFloats);
      displs[std::size_t(r)] = int(range.begin * dist::kPixelFloats);
    }
    std::vector<float> whole(w.rank == 0 ? image.size() : 0);
    MPI_Gatherv(piece.data(), int(piece.size()), MPI_FLOAT, whole.data(), counts.data(), displs.data(), MPI_FLOAT, 0,
                MPI_COMM_WORLD);
    report.compositeSeconds = secondsSince(compositeStart);
    report.bytesSent = composite.bytesSent + (w.rank == 0 ? 0 : piece.size() * sizeof(float));
    report.bytesReceived = composite.bytesReceived;
    if (w.rank == 0)
      for (int r = 1; r < w.size; ++r) report.bytesReceived += uint64_t(counts[std::size_t(r)]) * sizeof(float);
    frameSeconds_ = secondsSince(frameStart);
    return whole;
  }

  // Every rank's report, on rank 0 (empty elsewhere).
  std::vector<cli::RankReport> reports(const cli::RankReport& mine) const {
    constexpr int kNumbers = 9, kDeviceChars = 160;
    const double numbers[kNumbers] = {mine.renderSeconds, mine.waitSeconds, mine.compositeSeconds, double(mine.bytesSent),
                                      double(mine.bytesReceived), double(mine.bricksRead), double(mine.bricksOwned),
                                      double(mine.bricksUploaded), double(mine.passes)};
    char device[kDeviceChars] = {};
    std::strncpy(device, mine.device.c_str(), kDeviceChars - 1);
    const std::size_t size = std::size_t(world_.size);
    std::vector<double> allNumbers(world_.rank == 0 ? kNumbers * size : 0);
    std::vector<char> allDevices(world_.rank == 0 ? kDeviceChars * size : 0);
    MPI_Gather(numbers, kNumbers, MPI_DOUBLE, allNumbers.data(), kNumbers, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    MPI_Gather(device, kDeviceChars, MPI_CHAR, allDevices.data(), kDeviceChars, MPI_CHAR, 0, MPI_COMM_WORLD);
    std::vector<cli::RankReport> all(world_.rank == 0 ? size : 0);
    for (std::size_t r = 0; r < all.size(); ++r) {
      const double* n = &allNumbers[kNumbers * r];
      cli::RankReport& rr = all[r];
      rr.rank = int(r);
      rr.renderSeconds = n[0];
      rr.waitSeconds = n[1];
      rr.compositeSeconds = n[2];
      rr.bytesSent = uint64_t(n[3]);
      rr.bytesReceived = uint64_t(n[4]);
      rr.bricksRead = uint64_t(n[5]);
      rr.bricksOwned = uint64_t(n[6]);
      rr.bricksUploaded = uint64_t(n[7]);
      rr.passes = int(n[8]);
      rr.device = std::string(&allDevices[kDeviceChars * r]);
    }
    return all;
  }

  // Damage met by all ranks together (collective): FCC bricks or Cartesian leaves (io/Damage.h).
  io::Damage damage() const {
    io::Damage d = data_->damage();
    uint64_t mine = d.count, all = 0;
    MPI_Allreduce(&mine, &all, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    d.count = all;
    return d;
  }

  bool dvr() const { return options_.mode == render::RenderMode::Dvr; }
  const render::RenderOptions& options() const { return options_; }
  int width() const { return width_; }
  int height() const { return height_; }
  float iso() const { return options_.iso; }
  const std::string& isoBasis() const { return isoBasis_; }
  const render::Camera& camera() const { return camera_; }
  const dist::KdPartition& partition() const { return *partition_; }
  double frameSeconds() const { return frameSeconds_; }  // rank 0: the barrier before the last frame to its gather

 private:
  DistributedRenderer() = default;
  World world_;
  int width_ = 0, height_ = 0;
  render::RenderOptions options_;
  std::unique_ptr<cli::RenderData> data_;
  render::Camera camera_;
  std::string isoBasis_;
  std::unique_ptr<EglContext> gl_;
  std::shared_ptr<const dist::KdPartition> partition_;
  uint64_t owned_ = 0;
  std::unique_ptr<render::Raycaster> raycaster_;
  double frameSeconds_ = 0.0;
};

}  // namespace

int renderDistributed(const DistributedRenderRequest& request) {
  const World w = world();
  const cli::RenderFlags& flags = request.flags;
  std::unique_ptr<DistributedRenderer> renderer = DistributedRenderer::open(flags, request.output, request.force, request.quiet, w);
  if (!renderer) return 1;
  cli::RankReport report;
  const std::vector<float> whole = renderer->frame(renderer->camera(), report);
  const std::vector<cli::RankReport> reports = renderer->reports(report);
  const io::Damage damage = renderer->damage();
  const int status = damage.count > 0 && !request.allowDamaged ? 1 : 0;
  if (w.rank != 0) return status;

  const int width = renderer->width(), height = renderer->height();
  const std::size_t pixels = std::size_t(width) * height;
  std::vector<float> rgba(pixels * 4), normalDepth(pixels * 4);
  for (std::size_t p = 0; p < pixels; ++p) {
    std::memcpy(&rgba[4 * p], &whole[p * dist::kPixelFloats], 4 * sizeof(float));
    std::memcpy(&normalDepth[4 * p], &whole[p * dist::kPixelFloats + 4], 4 * sizeof(float));
  }
  io::RenderedImage out{width, height, &rgba, &normalDepth, /*normals=*/!renderer->dvr()};
  io::writeRenderedImage(request.output, out, glm::vec3(0.08f, 0.09f, 0.11f));
  if (request.json)
    std::fputs(cli::renderJson(flags.file, request.output, flags.mode, width, height, renderer->partition().radices(),
                               renderer->frameSeconds(), reports, {}, cli::frameLook(renderer->options(), flags.tf))
                   .c_str(),
               stdout);
  if (!request.quiet) {
    uint64_t read = 0;
    double slowest = 0.0, compositing = 0.0;
    for (const cli::RankReport& rr : reports) {
      read += rr.bricksRead;
      slowest = std::max(slowest, rr.renderSeconds);
      compositing = std::max(compositing, rr.compositeSeconds);
    }
    const std::string& basis = renderer->isoBasis();
    const std::string what = renderer->dvr() ? "dvr (--tf " + flags.tf + ")"
                                             : "iso " + std::to_string(renderer->iso()) + (basis == "--iso" ? "" : " (default: " + basis + ")");
    std::fprintf(stderr, "wrote %s: %dx%d, %s, %d ranks, %llu bricks read in all, slowest render %.3f s, compositing %.3f s\n",
                 request.output.c_str(), width, height, what.c_str(), w.size, (unsigned long long)read, slowest, compositing);
  }
  if (damage.count > 0)
    std::fprintf(stderr, "fccvdb: %s rendered as holes in %s%s\n", io::damagedCountText(damage).c_str(),
                 request.output.c_str(), request.allowDamaged ? "" : "; --allow-damaged to exit 0");
  return status;
}

int benchRenderDistributed(const cli::RenderFlags& flags, int frames, int warmup, double arc, bool json) {
  const World w = world();
  std::unique_ptr<DistributedRenderer> renderer = DistributedRenderer::open(flags, "", false, true, w);
  if (!renderer) return 1;
  // A cold frame (every rank's bricks streamed), the warm-up, then the timed orbit: per rank the mean
  // of each time over the timed frames.
  cli::RankReport cold, sum, one;
  renderer->frame(renderer->camera(), cold);
  for (int i = 0; i < warmup; ++i) renderer->frame(cli::orbitStep(renderer->camera(), i, std::max(warmup, 1), arc), one);
  double frameSeconds = 0.0;
  for (int i = 0; i < frames; ++i) {
    renderer->frame(cli::orbitStep(renderer->camera(), i, frames, arc), one);
    frameSeconds += renderer->frameSeconds();
    sum.renderSeconds += one.renderSeconds;
    sum.waitSeconds += one.waitSeconds;
    sum.compositeSeconds += one.compositeSeconds;
    sum.bytesSent += one.bytesSent;
    sum.bytesReceived += one.bytesReceived;
    sum.bricksRead += one.bricksRead;
    sum.bricksUploaded += one.bricksUploaded;
    sum.passes += one.passes;
  }
  cli::RankReport mean = one;
  mean.renderSeconds = sum.renderSeconds / frames;
  mean.waitSeconds = sum.waitSeconds / frames;
  mean.compositeSeconds = sum.compositeSeconds / frames;
  mean.bytesSent = sum.bytesSent / uint64_t(frames);
  mean.bytesReceived = sum.bytesReceived / uint64_t(frames);
  mean.bricksRead = cold.bricksRead + sum.bricksRead;  // over the whole run, the cold frame's included
  mean.bricksUploaded = sum.bricksUploaded / uint64_t(frames);
  mean.passes = sum.passes / frames;
  const std::vector<cli::RankReport> reports = renderer->reports(mean);
  const std::vector<cli::RankReport> coldReports = renderer->reports(cold);
  if (w.rank != 0) return 0;
  const double meanFrame = frameSeconds / frames;
  if (json) {
    std::string text = cli::renderJson(flags.file, "", flags.mode, renderer->width(), renderer->height(),
                                       renderer->partition().radices(), meanFrame, reports);
    double coldSeconds = 0.0;
    for (const cli::RankReport& rr : coldReports) coldSeconds = std::max(coldSeconds, rr.renderSeconds + rr.compositeSeconds);
    text.insert(1, "\"frames\": " + std::to_string(frames) + ", \"fps\": " + cli::jsonNumber(1.0 / meanFrame) +
                       ", \"arc_degrees\": " + cli::jsonNumber(arc) + ", \"first_frame_seconds\": " + cli::jsonNumber(coldSeconds) + ", ");
    std::fputs(text.c_str(), stdout);
    return 0;
  }
  std::printf("%d ranks (radices", w.size);
  for (int k : renderer->partition().radices()) std::printf(" %d", k);
  std::printf("), %dx%d, %d frames over %g degrees: %.1f fps, %.3f s a frame (rank 0, with compositing)\n", renderer->width(),
              renderer->height(), frames, arc, 1.0 / meanFrame, meanFrame);
  std::printf("%6s %10s %10s %12s %12s %12s %12s\n", "rank", "render s", "wait s", "composite s", "MiB sent", "bricks read",
              "bricks owned");
  for (const cli::RankReport& rr : reports)
    std::printf("%6d %10.4f %10.4f %12.4f %12.2f %12llu %12llu\n", rr.rank, rr.renderSeconds, rr.waitSeconds, rr.compositeSeconds,
                rr.bytesSent / 1048576.0, (unsigned long long)rr.bricksRead, (unsigned long long)rr.bricksOwned);
  return 0;
}

}  // namespace fcc::mpi
