// The pool bookkeeping (viewer/Residency.h): page entries, node occupancy, eviction order.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "viewer/Camera.h"
#include "sparse/Error.h"
#include "viewer/Residency.h"

namespace fcc::render {
namespace {

TEST(Residency, PageEntriesFollowNeedAndResidence) {
  Residency r(glm::ivec3(-2, 0, 0), glm::ivec3(20, 2, 2), 2);
  EXPECT_EQ(r.nodeDims(), glm::ivec3(2, 1, 1));
  const glm::ivec3 a(-2, 0, 0), b(17, 1, 1), c(0, 1, 0);
  EXPECT_EQ(r.brickAt(r.brickIndex(b)), b);
  r.setNeeded({a, b});
  EXPECT_EQ(r.missingCount(), 2u);
  EXPECT_EQ(r.pageEntries()[r.brickIndex(a)], Residency::kMissing);
  EXPECT_EQ(r.pageEntries()[r.brickIndex(c)], Residency::kSkip);
  EXPECT_EQ(r.nodeEntries()[0], 1u);
  EXPECT_EQ(r.nodeEntries()[1], 1u);
  const auto assigned = r.assign({a, b}, {0, 0});
  ASSERT_EQ(assigned.size(), 2u);
  EXPECT_EQ(r.pageEntries()[r.brickIndex(a)], assigned[0].second);
  EXPECT_EQ(r.pageEntries()[r.brickIndex(b)], assigned[1].second);
  EXPECT_EQ(r.missingCount(), 0u);
  // A new isovalue that needs only c: a and b stay resident but are skipped; node 1 is empty.
  r.setNeeded({c});
  EXPECT_EQ(r.pageEntries()[r.brickIndex(a)], Residency::kSkip);
  EXPECT_TRUE(r.isResident(a));
  EXPECT_EQ(r.nodeEntries()[1], 0u);
  EXPECT_EQ(r.missingCount(), 1u) << "c is needed and not resident";
  r.setNeeded({a, c});
  EXPECT_EQ(r.missingCount(), 1u) << "a is resident, c is not";
}

// A pool far larger than the part of the order sorted at a time (Residency sorts the eviction order
// in parts as assigning reaches them): every slot is handed out in the order of a stable sort of all
// slots by (free first, last use), over a pass taking most of the pool in batches.
TEST(Residency, PartlySortedOrderEqualsAStableSortOfAllSlots) {
  const uint32_t slots = 9000;
  Residency r(glm::ivec3(0), glm::ivec3(100, 100, 2), slots);
  std::vector<glm::ivec3> all;
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 100; ++y)
      for (int x = 0; x < 100; ++x) all.push_back(glm::ivec3(x, y, z));
  r.setNeeded(all);
  // Fill all but 300 slots, then a pass whose use stamps have many ties.
  const std::vector<glm::ivec3> firstBricks(all.begin(), all.begin() + (slots - 300));
  const auto first = r.assign(firstBricks, std::vector<uint32_t>(slots, 0));
  ASSERT_EQ(first.size(), firstBricks.size());
  std::vector<int> slotHolds(slots, -1);
  for (std::size_t i = 0; i < first.size(); ++i) slotHolds[first[i].second] = int(i);
  std::vector<uint32_t> lastUse(slots);
  for (uint32_t s = 0; s < slots; ++s) lastUse[s] = (s * 7919u) % 37u;  // ties between slots
  std::vector<uint32_t> expected(slots);
  for (uint32_t s = 0; s < slots; ++s) expected[s] = s;
  std::stable_sort(expected.begin(), expected.end(), [&](uint32_t a, uint32_t b) {
    const bool freeA = slotHolds[a] < 0, freeB = slotHolds[b] < 0;
    if (freeA != freeB) return freeA;
    return lastUse[a] < lastUse[b];
  });
  r.startAssigning(lastUse);
  std::vector<uint32_t> handedOut;
  for (std::size_t next = firstBricks.size(); next < all.size(); next += 777) {
    const std::vector<glm::ivec3> batch(all.begin() + next, all.begin() + std::min(all.size(), next + 777));
    for (const auto& [brick, slot] : r.assign(batch)) handedOut.push_back(slot);
  }
  ASSERT_EQ(handedOut.size(), std::size_t(slots)) << "every slot once, then the order runs out";
  for (uint32_t i = 0; i < slots; ++i) ASSERT_EQ(handedOut[i], expected[i]) << "position " << i << " of the order";
}

TEST(Residency, EvictsTheLeastRecentlyUsedAndNeverWhatItJustAssigned) {
  Residency r(glm::ivec3(0), glm::ivec3(8, 1, 1), 3);
  std::vector<glm::ivec3> all;
  for (int x = 0; x < 8; ++x) all.push_back(glm::ivec3(x, 0, 0));
  r.setNeeded(all);
  const auto first = r.assign({all[0], all[1], all[2]}, {0, 0, 0});
  ASSERT_EQ(first.size(), 3u);
  // Slot of brick 1 used last in pass 9, brick 0 in pass 5, brick 2 in pass 7: brick 0 goes first.
  std::vector<uint32_t> lastUse(3);
  lastUse[first[0].second] = 5;
  lastUse[first[1].second] = 9;
  lastUse[first[2].second] = 7;
  const auto second = r.assign({all[3]}, lastUse);
  ASSERT_EQ(second.size(), 1u);
  EXPECT_EQ(second[0].second, first[0].second);
  EXPECT_FALSE(r.isResident(all[0]));
  EXPECT_EQ(r.pageEntries()[r.brickIndex(all[0])], Residency::kMissing);
  EXPECT_EQ(r.missingCount(), 5u) << "8 needed, 3 resident after an eviction";
  // More requests than slots: only slotCount() are assigned, each to a different slot.
  const auto third = r.assign({all[4], all[5], all[6], all[7]}, lastUse);
  ASSERT_EQ(third.size(), 3u);
  EXPECT_NE(third[0].second, third[1].second);
  EXPECT_NE(third[1].second, third[2].second);
  EXPECT_NE(third[0].second, third[2].second);
  EXPECT_EQ(r.residentCount(), 3u);
}

TEST(Residency, OnePassOrderServesSeveralBatchesAndNamesTheChangedEntries) {
  Residency r(glm::ivec3(0), glm::ivec3(16, 1, 1), 4);
  std::vector<glm::ivec3> all;
  for (int x = 0; x < 16; ++x) all.push_back(glm::ivec3(x, 0, 0));
  r.setNeeded(all);
  EXPECT_TRUE(r.allEntriesChanged()) << "a new need rewrites the whole table";
  EXPECT_TRUE(r.takeChangedEntries().empty());
  EXPECT_FALSE(r.allEntriesChanged());
  const auto first = r.assign({all[0], all[1], all[2], all[3]}, {0, 0, 0, 0});
  ASSERT_EQ(first.size(), 4u);
  std::vector<uint32_t> changed = r.takeChangedEntries();
  std::sort(changed.begin(), changed.end());
  EXPECT_EQ(changed, (std::vector<uint32_t>{0, 1, 2, 3}));
  // Next pass: slots used in passes 4, 1, 3, 2 (by brick 0..3). Two batches within the pass take the
  // two oldest slots, then the next two, never one twice (the order is made once per pass).
  std::vector<uint32_t> lastUse(4);
  for (int i = 0; i < 4; ++i) lastUse[first[i].second] = uint32_t(std::vector<int>{4, 1, 3, 2}[i]);
  r.startAssigning(lastUse);
  const auto batch1 = r.assign({all[4], all[5]});
  const auto batch2 = r.assign({all[6], all[7], all[8]});
  ASSERT_EQ(batch1.size(), 2u);
  ASSERT_EQ(batch2.size(), 2u) << "four slots: the pass's order runs out";
  EXPECT_EQ(batch1[0].second, first[1].second);
  EXPECT_EQ(batch1[1].second, first[3].second);
  EXPECT_EQ(batch2[0].second, first[2].second);
  EXPECT_EQ(batch2[1].second, first[0].second);
  // Changed: the four evicted bricks (back to missing) and the four loaded ones, each once.
  changed = r.takeChangedEntries();
  std::sort(changed.begin(), changed.end());
  EXPECT_EQ(changed, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6, 7}));
  for (uint32_t index = 0; index < 4; ++index) EXPECT_EQ(r.pageEntries()[index], Residency::kMissing);
  EXPECT_TRUE(r.takeChangedEntries().empty());
}

TEST(Camera, PixelRaysAndFraming) {
  Camera c;
  c.eye = glm::dvec3(0, 0, 10);
  c.lookat = glm::dvec3(0);
  c.fovYDegrees = 90.0;
  const CameraFrame f = cameraFrame(c, 2.0);
  // Row 0 is the top: its rays point up; the centre of a 2x1 image's left pixel points left.
  EXPECT_GT(pixelRay(f, 0, 0, 2, 2).y, 0.0);
  EXPECT_LT(pixelRay(f, 0, 1, 2, 2).y, 0.0);
  EXPECT_LT(pixelRay(f, 0, 0, 2, 2).x, 0.0);
  // A 90 degree vertical field of view: the top edge's ray is 45 degrees up.
  const glm::dvec3 top = pixelRay(f, 0, 0, 1, 1000000);
  EXPECT_NEAR(glm::degrees(std::atan2(top.y, -top.z)), 45.0, 1e-3);
  // Framing puts the whole box inside the view.
  const Camera framed = frameBox(glm::dvec3(-1, -2, -3), glm::dvec3(4, 5, 6), 40.0, 1.5);
  const CameraFrame ff = cameraFrame(framed, 1.5);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 p((corner & 1) ? 4 : -1, (corner & 2) ? 5 : -2, (corner & 4) ? 6 : -3);
    const glm::dvec3 v = p - ff.eye;
    const double z = glm::dot(v, ff.forward);
    ASSERT_GT(z, 0.0);
    const double x = glm::dot(v, glm::normalize(ff.right)) / z, y = glm::dot(v, glm::normalize(ff.up)) / z;
    EXPECT_LE(std::abs(x), glm::length(ff.right)) << corner;
    EXPECT_LE(std::abs(y), glm::length(ff.up)) << corner;
  }
  Camera bad = c;
  bad.up = glm::dvec3(0, 0, 1);
  EXPECT_THROW(cameraFrame(bad, 1.0), fcc::ValueError);
}

}  // namespace
}  // namespace fcc::render
