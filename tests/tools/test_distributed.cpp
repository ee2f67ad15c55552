// The plain-C++ half of sort-last distributed rendering (tools/mpi/KdPartition.h, Compositor.h): the
// k-d partition's properties and radix-k compositing over threads standing in for MPI ranks, against
// compositing every rank's image in one place.
#include <gtest/gtest.h>

#include <condition_variable>
#include <cstring>
#include <deque>
#include <map>
#include <mutex>
#include <random>
#include <set>
#include <thread>
#include <functional>
#include <limits>

#include "tools/mpi/Compositor.h"
#include "tools/mpi/KdPartition.h"

namespace fcc::dist {
namespace {

std::vector<WeightedBrick> gridOfBricks(glm::ivec3 dims, const std::function<double(const glm::ivec3&)>& weight) {
  std::vector<WeightedBrick> bricks;
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) bricks.push_back({{x, y, z}, weight({x, y, z})});
  return bricks;
}

TEST(CompositingRadices, MultiplyToTheCountSmallestFirst) {
  for (int n = 1; n <= 30; ++n) {
    const std::vector<int> radices = compositingRadices(n);
    int product = 1;
    for (std::size_t i = 0; i < radices.size(); ++i) {
      product *= radices[i];
      EXPECT_GE(radices[i], 2);
      if (i) {
        EXPECT_LE(radices[i - 1], radices[i]);
      }
    }
    EXPECT_EQ(product, n);
  }
  EXPECT_EQ(compositingRadices(8), (std::vector<int>{2, 2, 2}));  // binary swap
}

TEST(KdPartition, EqualWeightsAndBoxesOnAFullGrid) {
  for (int parts : {2, 3, 4, 6, 8}) {
    const auto bricks = gridOfBricks({12, 8, 6}, [](const glm::ivec3&) { return 1.0; });
    const KdPartition partition(bricks, parts);
    std::vector<int> count(std::size_t(parts), 0);
    std::vector<glm::ivec3> lo(std::size_t(parts), glm::ivec3(1 << 20)), hi(std::size_t(parts), glm::ivec3(-(1 << 20)));
    for (const WeightedBrick& b : bricks) {
      const int owner = partition.ownerOf(b.brick);
      ASSERT_GE(owner, 0);
      ASSERT_LT(owner, parts);
      ++count[std::size_t(owner)];
      lo[std::size_t(owner)] = glm::min(lo[std::size_t(owner)], b.brick);
      hi[std::size_t(owner)] = glm::max(hi[std::size_t(owner)], b.brick);
    }
    for (int p = 0; p < parts; ++p) {
      // 576 bricks split by planes: each part a box (compact), of equal size where the planes allow.
      const glm::ivec3 extent = hi[std::size_t(p)] - lo[std::size_t(p)] + 1;
      EXPECT_EQ(count[std::size_t(p)], extent.x * extent.y * extent.z) << parts << " parts, part " << p;
      EXPECT_NEAR(count[std::size_t(p)], 576.0 / parts, 0.25 * 576.0 / parts) << parts << " parts, part " << p;
      EXPECT_EQ(partition.partWeights()[std::size_t(p)], count[std::size_t(p)]);
    }
  }
}

TEST(KdPartition, BalancesTheWeightedBricksNotTheEmptyOnes) {
  // Only a corner holds the surface: the parts split the corner, not the box.
  const auto bricks = gridOfBricks({16, 16, 16}, [](const glm::ivec3& b) { return b.x < 4 && b.y < 4 && b.z < 8 ? 1.0 : 0.0; });
  const KdPartition partition(bricks, 4);
  for (double w : partition.partWeights()) EXPECT_EQ(w, 32.0);
}

TEST(KdPartition, RankOrderPutsTheEyesSideFirst) {
  const auto bricks = gridOfBricks({8, 2, 2}, [](const glm::ivec3&) { return 1.0; });
  const KdPartition two(bricks, 2);  // split along x at brick 4 (index x = 64)
  EXPECT_EQ(two.ownerOf({0, 0, 0}), 0);
  EXPECT_EQ(two.ownerOf({7, 0, 0}), 1);
  EXPECT_EQ(two.rankOrder({-100.0, 16.0, 16.0}), (std::vector<int>{0, 1}));
  EXPECT_EQ(two.rankOrder({500.0, 16.0, 16.0}), (std::vector<int>{1, 0}));
  const KdPartition eight(gridOfBricks({4, 4, 4}, [](const glm::ivec3&) { return 1.0; }), 8);
  const std::vector<int> order = eight.rankOrder({-10.0, -10.0, -10.0});
  EXPECT_EQ(std::set<int>(order.begin(), order.end()).size(), 8u);
  EXPECT_EQ(order.front(), eight.ownerOf({0, 0, 0}));  // the part nearest the eye first
  EXPECT_EQ(order.back(), eight.ownerOf({3, 3, 3}));
}

// Ranks as threads: each round's pieces through a mailbox per (sender, receiver).
class Mailbox {
 public:
  void post(int from, int to, std::vector<float> data) {
    std::lock_guard<std::mutex> lock(mutex_);
    boxes_[{from, to}].push_back(std::move(data));
    ready_.notify_all();
  }
  std::vector<float> take(int from, int to) {
    std::unique_lock<std::mutex> lock(mutex_);
    auto& box = boxes_[{from, to}];
    ready_.wait(lock, [&] { return !box.empty(); });
    std::vector<float> data = std::move(box.front());
    box.pop_front();
    return data;
  }

 private:
  std::mutex mutex_;
  std::condition_variable ready_;
  std::map<std::pair<int, int>, std::deque<std::vector<float>>> boxes_;
};

class ThreadTransport : public Transport {
 public:
  ThreadTransport(Mailbox& mailbox, int rank) : mailbox_(mailbox), rank_(rank) {}
  std::vector<std::vector<float>> exchange(const std::vector<int>& peers, const std::vector<std::vector<float>>& sends,
                                           const std::vector<std::size_t>&) override {
    for (std::size_t i = 0; i < peers.size(); ++i) mailbox_.post(rank_, peers[i], sends[i]);
    std::vector<std::vector<float>> received;
    for (int peer : peers) received.push_back(mailbox_.take(peer, rank_));
    return received;
  }

 private:
  Mailbox& mailbox_;
  int rank_;
};

// Every rank's final piece, assembled into the whole image.
std::vector<float> compositeOverThreads(const KdPartition& partition, const glm::dvec3& eye, CompositeMode mode,
                                        const std::vector<std::vector<float>>& images, uint64_t& bytesSent) {
  const int n = partition.parts();
  const std::size_t pixels = images[0].size() / kPixelFloats;
  Mailbox mailbox;
  std::vector<std::vector<float>> pieces(static_cast<std::size_t>(n));
  std::vector<CompositeStats> stats(static_cast<std::size_t>(n));
  std::vector<std::thread> threads;
  for (int r = 0; r < n; ++r)
    threads.emplace_back([&, r] {
      ThreadTransport transport(mailbox, r);
      pieces[std::size_t(r)] = compositeRadixK(partition, r, eye, mode, images[std::size_t(r)], transport, stats[std::size_t(r)]);
    });
  for (std::thread& t : threads) t.join();
  std::vector<float> whole(pixels * kPixelFloats, -1.0f);
  bytesSent = 0;
  for (int r = 0; r < n; ++r) {
    const PixelRange range = finalRange(partition, r, pixels);
    EXPECT_EQ(pieces[std::size_t(r)].size(), range.size() * kPixelFloats);
    std::memcpy(&whole[range.begin * kPixelFloats], pieces[std::size_t(r)].data(), pieces[std::size_t(r)].size() * sizeof(float));
    bytesSent += stats[std::size_t(r)].bytesSent;
  }
  return whole;
}

// Per pixel, some ranks hit (a random depth) and the others miss (+inf, zero colour), as the
// raycaster writes them; DVR layers are random premultiplied colours.
std::vector<std::vector<float>> randomImages(int ranks, std::size_t pixels, CompositeMode mode, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<std::vector<float>> images(std::size_t(ranks), std::vector<float>(pixels * kPixelFloats, 0.0f));
  for (auto& image : images)
    for (std::size_t p = 0; p < pixels; ++p) {
      float* px = &image[p * kPixelFloats];
      const bool hit = unit(rng) < 0.6f;
      const float a = mode == CompositeMode::NearestDepth ? (hit ? 1.0f : 0.0f) : (hit ? unit(rng) : 0.0f);
      for (int c = 0; c < 3; ++c) px[c] = a * unit(rng);
      px[3] = a;
      for (int c = 4; c < 7; ++c) px[c] = hit ? unit(rng) : 0.0f;
      px[7] = hit ? 1.0f + 100.0f * unit(rng) : std::numeric_limits<float>::infinity();
    }
  return images;
}

TEST(RadixK, NearestDepthEqualsTheMinimumOverRanksBitForBit) {
  for (int n : {2, 3, 4, 6, 8}) {
    const KdPartition partition(gridOfBricks({8, 8, 8}, [](const glm::ivec3&) { return 1.0; }), n);
    const std::size_t pixels = 37 * 23;  // no power of two: uneven pieces
    const auto images = randomImages(n, pixels, CompositeMode::NearestDepth, unsigned(n));
    uint64_t bytes = 0;
    const std::vector<float> whole = compositeOverThreads(partition, {-50.0, 20.0, 30.0}, CompositeMode::NearestDepth, images, bytes);
    for (std::size_t p = 0; p < pixels; ++p) {
      int best = 0;
      for (int r = 1; r < n; ++r)
        if (images[std::size_t(r)][p * kPixelFloats + 7] < images[std::size_t(best)][p * kPixelFloats + 7]) best = r;
      const bool miss = std::isinf(images[std::size_t(best)][p * kPixelFloats + 7]);
      if (miss) {
        ASSERT_TRUE(std::isinf(whole[p * kPixelFloats + 7])) << n << " ranks, pixel " << p;
        continue;
      }
      for (int c = 0; c < kPixelFloats; ++c)
        ASSERT_EQ(whole[p * kPixelFloats + c], images[std::size_t(best)][p * kPixelFloats + c]) << n << " ranks, pixel " << p;
    }
    // Radix-k's exchange: each rank sends (1 - 1/k) of what it holds per round, never a whole image per peer.
    double expected = 0.0, held = double(pixels) * kPixelFloats * sizeof(float) * n;
    for (int k : partition.radices()) {
      expected += held * (k - 1) / k;
      held /= k;
    }
    EXPECT_NEAR(double(bytes), expected, n * 64.0 * kPixelFloats);
  }
}

TEST(RadixK, FrontToBackIsOverInTheRanksVisibilityOrder) {
  for (int n : {2, 4, 6}) {
    const KdPartition partition(gridOfBricks({6, 6, 6}, [](const glm::ivec3&) { return 1.0; }), n);
    for (const glm::dvec3 eye : {glm::dvec3(-40.0, 48.0, 48.0), glm::dvec3(200.0, 120.0, -30.0)}) {
      const std::size_t pixels = 500;
      const auto images = randomImages(n, pixels, CompositeMode::FrontToBack, unsigned(7 * n));
      uint64_t bytes = 0;
      const std::vector<float> whole = compositeOverThreads(partition, eye, CompositeMode::FrontToBack, images, bytes);
      const std::vector<int> order = partition.rankOrder(eye);
      for (std::size_t p = 0; p < pixels; ++p) {
        double rgba[4] = {0, 0, 0, 0};
        for (int r : order)
          for (int c = 0; c < 4; ++c) rgba[c] += (1.0 - rgba[3]) * images[std::size_t(r)][p * kPixelFloats + c];
        for (int c = 0; c < 4; ++c) ASSERT_NEAR(whole[p * kPixelFloats + c], rgba[c], 1e-5) << n << " ranks, pixel " << p;
      }
    }
  }
}

}  // namespace
}  // namespace fcc::dist
