#include "KdPartition.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>

namespace fcc::dist {

std::vector<int> compositingRadices(int parts) {
  if (parts < 1) throw std::invalid_argument("partition into " + std::to_string(parts) + " parts: need at least 1");
  std::vector<int> radices;
  for (int p = 2; parts > 1;) {
    if (parts % p == 0) {
      radices.push_back(p);
      parts /= p;
    } else {
      p = p * p > parts ? parts : p + 1;
    }
  }
  return radices;
}

// A node splits along `axis` into cuts.size() + 1 slabs: slab j holds brick coordinates c with
// cuts[j - 1] <= c < cuts[j] (cuts[-1] = -inf, cuts[k - 1] = +inf).
struct KdPartition::Node {
  int axis = 0;
  std::vector<int> cuts;
  std::vector<std::unique_ptr<Node>> children;  // empty at a leaf
  int slabOf(int c) const { return int(std::upper_bound(cuts.begin(), cuts.end(), c) - cuts.begin()); }
};

namespace {

// The k - 1 cuts along `axis` that split `bricks` into k slabs of about equal weight: each cut at the
// brick coordinate whose prefix weight comes nearest its share (ties: the lower coordinate).
std::vector<int> balancedCuts(std::vector<WeightedBrick>& bricks, int axis, int k) {
  std::sort(bricks.begin(), bricks.end(), [axis](const WeightedBrick& a, const WeightedBrick& b) {
    if (a.brick[axis] != b.brick[axis]) return a.brick[axis] < b.brick[axis];
    return std::make_tuple(a.brick.x, a.brick.y, a.brick.z) < std::make_tuple(b.brick.x, b.brick.y, b.brick.z);
  });
  // Distinct coordinates and the weight strictly below each.
  std::vector<int> coords;
  std::vector<double> below;
  double total = 0.0;
  for (const WeightedBrick& b : bricks) {
    if (coords.empty() || coords.back() != b.brick[axis]) {
      coords.push_back(b.brick[axis]);
      below.push_back(total);
    }
    total += b.weight;
  }
  coords.push_back(coords.empty() ? 0 : coords.back() + 1);
  below.push_back(total);
  std::vector<int> cuts;
  std::size_t from = 0;
  for (int j = 1; j < k; ++j) {
    const double target = total * j / k;
    std::size_t best = from;
    for (std::size_t i = from; i < coords.size(); ++i)
      if (std::abs(below[i] - target) < std::abs(below[best] - target)) best = i;
    cuts.push_back(coords[best]);
    from = best;
  }
  return cuts;
}


std::unique_ptr<KdPartition::Node> build(std::vector<WeightedBrick> bricks, const std::vector<int>& radices, int level,
                                          int firstRank, int rankStride, std::vector<double>& partWeights) {
  auto node = std::make_unique<KdPartition::Node>();
  if (level < 0) {  // a leaf: one rank's part
    for (const WeightedBrick& b : bricks) partWeights[std::size_t(firstRank)] += b.weight;
    return node;
  }
  const int k = radices[std::size_t(level)];
  // The axis along which the weighted bricks (all bricks when none weighs) extend furthest.
  glm::ivec3 lo(std::numeric_limits<int>::max()), hi(std::numeric_limits<int>::min());
  bool anyWeight = false;
  for (const WeightedBrick& b : bricks) anyWeight |= b.weight > 0.0;
  for (const WeightedBrick& b : bricks)
    if (!anyWeight || b.weight > 0.0) {
      lo = glm::min(lo, b.brick);
      hi = glm::max(hi, b.brick);
    }
  if (bricks.empty()) lo = hi = glm::ivec3(0);
  const glm::ivec3 extent = hi - lo;
  node->axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  node->cuts = balancedCuts(bricks, node->axis, k);
  std::vector<std::vector<WeightedBrick>> slabs(static_cast<std::size_t>(k));
  for (const WeightedBrick& b : bricks) slabs[std::size_t(node->slabOf(b.brick[node->axis]))].push_back(b);
  // Round `level`'s digit: children j are the ranks firstRank + j * rankStride (+ lower digits).
  const int childStride = rankStride / k;
  for (int j = 0; j < k; ++j)
    node->children.push_back(build(std::move(slabs[std::size_t(j)]), radices, level - 1, firstRank + j * childStride,
                                   childStride, partWeights));
  return node;
}

}  // namespace

KdPartition::KdPartition(const std::vector<WeightedBrick>& bricks, int parts)
    : parts_(parts), radices_(compositingRadices(parts)), partWeights_(std::size_t(parts), 0.0) {
  // The root splits by the last round's radix, whose digit has the largest stride (parts / k).
  root_ = build(bricks, radices_, int(radices_.size()) - 1, 0, parts, partWeights_);
}

KdPartition::~KdPartition() = default;
KdPartition::KdPartition(KdPartition&&) noexcept = default;

int KdPartition::stride(int round) const {
  int s = 1;
  for (int r = 0; r < round; ++r) s *= radices_[std::size_t(r)];
  return s;
}

int KdPartition::digit(int rank, int round) const { return (rank / stride(round)) % radices_[std::size_t(round)]; }

const KdPartition::Node& KdPartition::nodeOf(int round, int rank) const {
  const Node* node = root_.get();
  for (int r = int(radices_.size()) - 1; r > round; --r) node = node->children[std::size_t(digit(rank, r))].get();
  return *node;
}

int KdPartition::ownerOf(const glm::ivec3& brick) const {
  const Node* node = root_.get();
  int rank = 0;
  for (int r = int(radices_.size()) - 1; r >= 0; --r) {
    const int slab = node->slabOf(brick[node->axis]);
    rank += slab * stride(r);
    node = node->children[std::size_t(slab)].get();
  }
  return rank;
}

std::vector<int> KdPartition::frontToBack(int round, int rank, const glm::dvec3& eyeXyz) const {
  const Node& node = nodeOf(round, rank);
  const int k = int(node.cuts.size()) + 1;
  // The slab holding the eye (slab j spans [16 cuts[j-1], 16 cuts[j]) in index space), then the others
  // by distance from it: those on the near side of the eye's slab and those beyond are never both
  // entered by one ray, so interleaving them is as good as any order.
  const double e = eyeXyz[node.axis];
  int eyeSlab = 0;
  while (eyeSlab < k - 1 && e >= 16.0 * node.cuts[std::size_t(eyeSlab)]) ++eyeSlab;
  std::vector<int> order{eyeSlab};
  for (int d = 1; int(order.size()) < k; ++d) {
    if (eyeSlab - d >= 0) order.push_back(eyeSlab - d);
    if (eyeSlab + d < k) order.push_back(eyeSlab + d);
  }
  return order;
}

std::vector<int> KdPartition::rankOrder(const glm::dvec3& eyeXyz) const {
  std::vector<int> ranks{0};  // the digits of the rounds above the current one
  for (int r = int(radices_.size()) - 1; r >= 0; --r) {
    std::vector<int> next;
    for (int base : ranks)
      for (int j : frontToBack(r, base, eyeXyz)) next.push_back(base + j * stride(r));
    ranks = std::move(next);
  }
  return ranks;
}

}  // namespace fcc::dist
