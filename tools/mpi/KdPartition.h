// Sort-last distributed rendering (docs/MPI.md): which process renders which bricks. The bricks are
// split by a k-d tree into N spatially compact parts of about equal weight (a brick weighs 1 when its
// bounds hold the isovalue or map to a non-zero opacity, else 0). The tree's levels follow the radices
// of the compositing (radix-k: N = k_0 k_1 ... k_{L-1}, binary swap when every k is 2): level r splits
// a node into k_r slabs along one axis, so that the processes that composite together in round r own
// the slabs of one node, and the image pieces they hold are composites of whole subtrees. Plain C++
// (no MPI): every process computes the same tree from the same bounds.
#pragma once

#include <glm/glm.hpp>

#include <memory>
#include <vector>

namespace fcc::dist {

struct WeightedBrick {
  glm::ivec3 brick;  // brick coordinates (16^3 index units)
  double weight = 0.0;
};

// N's radices for radix-k compositing: its prime factors, smallest first (2s first: binary swap).
std::vector<int> compositingRadices(int parts);

class KdPartition {
 public:
  // `parts` >= 1. Deterministic in its arguments.
  KdPartition(const std::vector<WeightedBrick>& bricks, int parts);
  ~KdPartition();
  KdPartition(KdPartition&&) noexcept;

  int parts() const { return parts_; }
  // Round r of the compositing merges groups of radices()[r] processes (round 0 first: the deepest
  // splits of the tree).
  const std::vector<int>& radices() const { return radices_; }
  // The process (rank) whose part holds `brick`; every brick coordinate has one (the parts' slabs
  // extend to infinity at the outside).
  int ownerOf(const glm::ivec3& brick) const;
  // Rank = sum over rounds of digit(rank, r) * stride(r), stride(r) = k_0 ... k_{r-1}.
  int digit(int rank, int round) const;
  int stride(int round) const;
  // Front-to-back order, for an eye at `eyeXyz` (lattice index space), of the slabs that the node of
  // `rank`'s group in `round` splits into: the digits of round `round`, nearest first. Every ray from
  // the eye meets the slabs in an order consistent with it (a slab the ray never enters lies anywhere
  // in it, and contributes nothing to that ray).
  std::vector<int> frontToBack(int round, int rank, const glm::dvec3& eyeXyz) const;
  // Every rank, front to back for an eye at `eyeXyz`: the order frontToBack gives at each level of the
  // tree (the order radix-k composites in; tests compare with it).
  std::vector<int> rankOrder(const glm::dvec3& eyeXyz) const;
  // Total weight of each part (balance; tests and --json).
  const std::vector<double>& partWeights() const { return partWeights_; }

  struct Node;  // a split (KdPartition.cpp)

 private:
  const Node& nodeOf(int round, int rank) const;
  int parts_;
  std::vector<int> radices_;
  std::unique_ptr<Node> root_;
  std::vector<double> partWeights_;
};

}  // namespace fcc::dist
