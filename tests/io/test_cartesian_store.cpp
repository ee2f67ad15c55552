// The Cartesian brick store (direct rendering of float grids, issue 17) against OpenVDB's own reads: every
// point of a brick's block, and the per-brick ranges, for a level set (interior tiles, exterior background)
// and a fog volume (interior tiles of 1); a damaged leaf read as the background; the ranges kept in the
// user cache (io/CartesianRangeCache.h), and that cache file's reader alone (what fuzzing found in it,
// the fuzz corpus's verdicts).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>

#include <openvdb/io/File.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/LevelSetUtil.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <set>
#include <vector>

#include "LeafDamage.h"
#include "io/CartesianBrickStore.h"
#include "io/CartesianRangeCache.h"
#include "io/VdbFile.h"
#include "sparse/Error.h"
#include "tests/PrivateUserCache.h"
#include "tests/tools/RunCommand.h"

namespace fcc::io {
namespace {

using Store = CartesianBrickStore;

std::string writeGrid(const test::TempDir& dir, const std::string& name, openvdb::FloatGrid::Ptr grid) {
  initializeVdb();
  const std::string path = dir / (name + ".vdb");
  grid->setName(name);
  openvdb::io::File file(path);
  file.write({grid});
  file.close();
  return path;
}

void expectBlocksAndRangesMatch(const std::string& path, const openvdb::FloatGrid& grid) {
  const Store store(path);
  EXPECT_EQ(store.background(), grid.background());
  ASSERT_FALSE(store.activeBrickBox().empty());
  const auto ranges = store.computeBrickRanges();
  ASSERT_FALSE(ranges.empty());
  std::set<std::tuple<int, int, int>> listed;
  for (const auto& r : ranges) listed.insert({r.brick.x, r.brick.y, r.brick.z});
  const auto accessor = grid.getConstAccessor();
  std::vector<float> block(Store::kBlockPoints);
  int checked = 0, listedBackgroundOnly = 0;
  // Every brick of the active box and one layer around it.
  const openvdb::CoordBBox box = store.activeBrickBox();
  for (int bz = box.min().z() - 1; bz <= box.max().z() + 1; ++bz)
    for (int by = box.min().y() - 1; by <= box.max().y() + 1; ++by)
      for (int bx = box.min().x() - 1; bx <= box.max().x() + 1; ++bx) {
        const glm::ivec3 brick(bx, by, bz);
        store.readBlock(brick, block.data());
        bool allBackground = true;
        float lo = block[0], hi = block[0];
        for (int z = 0; z < Store::kBlockDim; ++z)
          for (int y = 0; y < Store::kBlockDim; ++y)
            for (int x = 0; x < Store::kBlockDim; ++x) {
              const openvdb::Coord p(16 * bx - 2 + x, 16 * by - 2 + y, 16 * bz - 2 + z);
              const float v = block[(z * Store::kBlockDim + y) * Store::kBlockDim + x];
              ASSERT_EQ(v, accessor.getValue(p)) << "brick (" << bx << ", " << by << ", " << bz << ") point " << p;
              allBackground = allBackground && v == grid.background();
              lo = std::min(lo, v);
              hi = std::max(hi, v);
            }
        const bool inList = listed.count({bx, by, bz}) > 0;
        // Conservative: a brick whose block holds anything but the background is listed (the ranges are
        // made of whole leaves, so a few bricks next to data are listed too).
        if (!allBackground) {
          EXPECT_TRUE(inList) << "brick (" << bx << ", " << by << ", " << bz << ")";
        }
        listedBackgroundOnly += inList && allBackground;
        if (inList) {
          const auto& r = *std::find_if(ranges.begin(), ranges.end(), [&](const auto& e) { return e.brick == brick; });
          EXPECT_LE(r.lo, lo);
          EXPECT_GE(r.hi, hi);
        }
        ++checked;
      }
  EXPECT_GT(checked, 27);
  // Most listed bricks do hold data.
  EXPECT_LT(listedBackgroundOnly, int(ranges.size()) / 2) << listedBackgroundOnly << " of " << ranges.size();
}

TEST(CartesianBrickStore, LevelSetBlocksAndRangesMatchOpenVdb) {
  test::TempDir dir;
  auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(21.0f, openvdb::Vec3f(1.5f, -2.0f, 3.0f), 1.0f, 3.0f);
  const std::string path = writeGrid(dir, "ls", grid);
  EXPECT_TRUE(Store(path).levelSet());
  expectBlocksAndRangesMatch(path, *grid);
}

TEST(CartesianBrickStore, FogVolumeWithInteriorTilesMatchesOpenVdb) {
  test::TempDir dir;
  auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(30.0f, openvdb::Vec3f(0.0f), 1.0f, 3.0f);
  openvdb::tools::sdfToFogVolume(*grid);
  const std::string path = writeGrid(dir, "fog", grid);
  EXPECT_FALSE(Store(path).levelSet());
  expectBlocksAndRangesMatch(path, *grid);
}

TEST(CartesianBrickStore, NotAFloatGridIsOneLine) {
  test::TempDir dir;
  const std::string path = dir / "v.vdb";
  initializeVdb();
  auto grid = openvdb::Vec3SGrid::create();
  grid->setName("v");
  openvdb::io::File file(path);
  file.write({grid});
  file.close();
  try {
    Store store(path);
    FAIL() << "opened";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

// A dense fog-like grid on [0, 48)^3 (every leaf present), values z + x / 64 (all below the background).
openvdb::FloatGrid::Ptr denseGrid(float background) {
  auto grid = openvdb::FloatGrid::create(background);
  auto accessor = grid->getAccessor();
  for (int z = 0; z < 48; ++z)
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 48; ++x) accessor.setValue(openvdb::Coord(x, y, z), float(z) + float(x) / 64.0f);
  return grid;
}

// A leaf whose bytes are damaged is never trusted and never fails a read: it reads as the background
// in every block and box that holds it (its own brick's and its neighbours'), the ranges hold the
// background where the blocks do, every other point reads as stored, and the damage is recorded once,
// naming the file and the leaf.
TEST(CartesianBrickStore, DamagedLeafReadsAsTheBackgroundAndIsRecordedOnce) {
  test::TempDir dir;
  const float background = 100.0f;
  auto grid = denseGrid(background);
  const std::string path = writeGrid(dir, "dense", grid);
  const openvdb::Coord damagedOrigin(16, 8, 24);
  test::damageLeafValues(path, {"Tree_float_5_4_3"}, damagedOrigin);
  const openvdb::CoordBBox damagedBox(damagedOrigin, damagedOrigin.offsetBy(7));

  const Store store(path);
  EXPECT_EQ(store.damage().count, 0u) << "opening reads no leaf";
  const auto ranges = store.computeBrickRanges();
  const Damage damage = store.damage();
  EXPECT_EQ(damage.count, 1u);
  EXPECT_EQ(damage.unit, "leaf");
  EXPECT_EQ(damagedCountText(damage), "1 damaged leaf");
  EXPECT_NE(damage.first.find(path), std::string::npos) << damage.first;
  EXPECT_NE(damage.first.find("leaf at (16, 8, 24) is damaged"), std::string::npos) << damage.first;
  ASSERT_EQ(damage.messages.size(), 1u);

  const auto accessor = grid->getConstAccessor();
  std::vector<float> block(Store::kBlockPoints);
  int damagedPoints = 0;
  // Every brick whose block holds a point of the damaged leaf (leaf 2 b + {-1 .. 2} of brick b).
  for (int bz = 1; bz <= 2; ++bz)
    for (int by = 0; by <= 1; ++by)
      for (int bx = 0; bx <= 1; ++bx) {
        const glm::ivec3 brick(bx, by, bz);
        store.readBlock(brick, block.data());
        float lo = INFINITY, hi = -INFINITY;
        for (int z = 0; z < Store::kBlockDim; ++z)
          for (int y = 0; y < Store::kBlockDim; ++y)
            for (int x = 0; x < Store::kBlockDim; ++x) {
              const openvdb::Coord p(16 * bx - 2 + x, 16 * by - 2 + y, 16 * bz - 2 + z);
              const float v = block[(z * Store::kBlockDim + y) * Store::kBlockDim + x];
              const bool damaged = damagedBox.isInside(p);
              damagedPoints += damaged;
              ASSERT_EQ(v, damaged ? background : accessor.getValue(p)) << "brick " << brick.x << brick.y << brick.z << " point " << p;
              lo = std::min(lo, v);
              hi = std::max(hi, v);
            }
        const auto r = std::find_if(ranges.begin(), ranges.end(), [&](const auto& e) { return e.brick == brick; });
        ASSERT_NE(r, ranges.end()) << "brick " << brick.x << brick.y << brick.z;
        EXPECT_LE(r->lo, lo);
        EXPECT_GE(r->hi, hi) << "the range must hold the background the block now holds";
      }
  // Per axis the leaf's 8 points in one block and 2 in the other: (8 + 2)^3 over the eight blocks.
  EXPECT_EQ(damagedPoints, 1000);
  EXPECT_EQ(store.damage().count, 1u) << "each damaged leaf is recorded once";
}

// The user cache folder of one test: FCCVDB_CACHE_DIR, and FCCVDB_CACHE_MAX_MIB (unset unless given),
// set while it lives; then both as they were (the process's private folder, tests/PrivateUserCache.h).
struct ScopedCache {
  test::TempDir dir;
  test::ScopedEnv cacheDir{"FCCVDB_CACHE_DIR", (dir / "cache").c_str()};
  test::ScopedEnv maxMiB;  // unset unless given
  explicit ScopedCache(const char* maxMiBValue = nullptr) : maxMiB("FCCVDB_CACHE_MAX_MIB", maxMiBValue) {}
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir.path / "cache", ec)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }
};

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}
void writeAll(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// Bit for bit the same ranges, in the same order.
void expectSameRanges(const std::vector<Store::BrickRange>& a, const std::vector<Store::BrickRange>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].brick, b[i].brick) << i;
    ASSERT_EQ(std::memcmp(&a[i].lo, &b[i].lo, sizeof(float)), 0) << i;
    ASSERT_EQ(std::memcmp(&a[i].hi, &b[i].hi, sizeof(float)), 0) << i;
  }
}

// A level set with leaves and interior tiles, written as `name`.
std::string writeSphere(const test::TempDir& dir, const std::string& name, float radius) {
  return writeGrid(dir, name, openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(radius, openvdb::Vec3f(1.5f, -2.0f, 3.0f), 1.0f, 3.0f));
}

// The second open of a grid reads its ranges from the user cache: the same ranges bit for bit, and no
// leaf read — not even once the leaves are damaged behind the cache's back (same size and modification
// time: the cache cannot know, and the damage is met only when a brick is decoded).
TEST(CartesianBrickStore, SecondOpenReadsTheRangesFromTheUserCacheAndNoLeaf) {
  const ScopedCache cache;
  test::TempDir dir;
  const std::string path = writeSphere(dir, "ls", 21.0f);
  std::vector<Store::BrickRange> first;
  {
    const Store store(path, "", /*cacheRanges=*/true);
    first = store.brickRanges();
    EXPECT_EQ(store.rangesFrom(), Store::RangesFrom::Leaves);
    EXPECT_GT(store.leavesRead(), 0u);
    expectSameRanges(first, store.computeBrickRanges());
    EXPECT_TRUE(std::filesystem::exists(store.rangeCacheFile())) << store.rangeCacheFile();
    EXPECT_EQ(std::filesystem::path(store.rangeCacheFile()).parent_path(), cache.dir.path / "cache");
  }
  ASSERT_EQ(cache.files().size(), 1u);
  EXPECT_EQ(cache.files()[0].rfind("ls.vdb-", 0), 0u) << cache.files()[0];
  {
    const Store store(path, "", true);
    expectSameRanges(store.brickRanges(), first);
    EXPECT_EQ(store.rangesFrom(), Store::RangesFrom::Cache);
    EXPECT_EQ(store.leavesRead(), 0u) << "the ranges came from the leaves again";
  }
  // Damage a leaf in place, keeping the size and the modification time.
  struct stat before {};
  ASSERT_EQ(::stat(path.c_str(), &before), 0);
  openvdb::Coord someLeaf;
  {
    const VdbLeafReader reader(path, "", {"Tree_float_5_4_3"});
    someLeaf = reader.leafOrigin(reader.leafCount() / 2);
  }
  test::damageLeafValues(path, {"Tree_float_5_4_3"}, someLeaf);
  {
    const Store check(path);  // the damage is real: the leaves' pass meets it
    check.computeBrickRanges();
    ASSERT_EQ(check.damage().count, 1u);
  }
  const timespec times[2] = {before.st_atim, before.st_mtim};
  ASSERT_EQ(::utimensat(AT_FDCWD, path.c_str(), times, 0), 0);
  {
    const Store store(path, "", true);
    expectSameRanges(store.brickRanges(), first);
    EXPECT_EQ(store.rangesFrom(), Store::RangesFrom::Cache);
    EXPECT_EQ(store.damage().count, 0u) << "a leaf was read for the ranges";
    EXPECT_EQ(store.leavesRead(), 0u);
  }
}

// A cache file that is truncated, garbled or empty, or of another key, is no cache: the ranges are
// computed from the leaves (the same ranges) and the file is written again, whole, so the next open
// reads it. Never a throw.
TEST(CartesianBrickStore, DamagedRangeCacheFileIsRecomputedAndRewritten) {
  const ScopedCache cache;
  test::TempDir dir;
  const std::string path = writeSphere(dir, "ls", 21.0f);
  std::vector<Store::BrickRange> reference;
  std::string file, good;
  {
    const Store store(path, "", true);
    reference = store.brickRanges();
    file = store.rangeCacheFile();
    good = readAll(file);
  }
  ASSERT_GT(good.size(), 64u);
  const std::vector<std::pair<std::string, std::string>> damages = {
      {"empty", std::string()},
      {"truncated in the records", good.substr(0, good.size() / 2)},
      {"truncated in the checksum", good.substr(0, good.size() - 3)},
      {"one more byte", good + "x"},
      {"a record's bit flipped", [&] { std::string b = good; b[b.size() - 20] ^= 0x10; return b; }()},
      {"the key's bit flipped", [&] { std::string b = good; b[20] ^= 0x01; return b; }()},
      {"the count made huge", [&] {
         std::string b = good;
         const std::size_t keyBytes = std::size_t(uint8_t(b[12])) | std::size_t(uint8_t(b[13])) << 8;
         b[16 + keyBytes + 7] = char(0x7f);
         return b;
       }()},
      {"another magic", "FCCRNG9\n" + good.substr(8)},
      {"garbage", std::string(good.size(), '\xa5')},
  };
  for (const auto& [what, bytes] : damages) {
    SCOPED_TRACE(what);
    writeAll(file, bytes);
    {
      const Store store(path, "", true);
      expectSameRanges(store.brickRanges(), reference);
      EXPECT_EQ(store.rangesFrom(), Store::RangesFrom::Leaves);
    }
    EXPECT_EQ(readAll(file), good) << "the cache file is written again, whole";
    const Store again(path, "", true);
    again.brickRanges();
    EXPECT_EQ(again.rangesFrom(), Store::RangesFrom::Cache);
  }
}

// Another source is another key: a file rewritten (other values, other size), or one whose modification
// time alone changed, is read from its leaves again; so is another grid of the same file.
TEST(CartesianBrickStore, ChangedSourceInvalidatesTheCachedRanges) {
  const ScopedCache cache;
  test::TempDir dir;
  const std::string path = writeSphere(dir, "ls", 21.0f);
  std::vector<Store::BrickRange> small;
  {
    const Store store(path, "", true);
    small = store.brickRanges();
  }
  // Rewritten: a larger sphere under the same name.
  writeSphere(dir, "ls", 27.0f);
  std::vector<Store::BrickRange> large;
  {
    const Store store(path, "", true);
    large = store.brickRanges();
    EXPECT_EQ(store.rangesFrom(), Store::RangesFrom::Leaves) << "the old file's ranges were used";
    EXPECT_GT(large.size(), small.size());
    expectSameRanges(large, store.computeBrickRanges());
  }
  // Only the modification time.
  struct stat st {};
  ASSERT_EQ(::stat(path.c_str(), &st), 0);
  timespec times[2] = {st.st_atim, st.st_mtim};
  times[1].tv_sec -= 100;
  ASSERT_EQ(::utimensat(AT_FDCWD, path.c_str(), times, 0), 0);
  {
    const Store store(path, "", true);
    expectSameRanges(store.brickRanges(), large);
    EXPECT_EQ(store.rangesFrom(), Store::RangesFrom::Leaves) << "a changed modification time must invalidate";
  }
  {
    const Store store(path, "", true);
    store.brickRanges();
    EXPECT_EQ(store.rangesFrom(), Store::RangesFrom::Cache);
  }
}

// Without caching (`--no-cache`) nothing is read from or written to the folder; a file whose leaves
// showed damage keeps no ranges there (each open meets and reports the damage again); the folder is
// bounded, least recently used out, with the conversions.
TEST(CartesianBrickStore, NoCacheDamagedFilesAndTheFolderBound) {
  {
    const ScopedCache cache;
    test::TempDir dir;
    const std::string path = writeSphere(dir, "ls", 21.0f);
    const Store store(path);
    EXPECT_FALSE(store.brickRanges().empty());
    EXPECT_EQ(store.rangeCacheFile(), "");
    EXPECT_TRUE(cache.files().empty());
  }
  {
    const ScopedCache cache;
    test::TempDir dir;
    auto grid = denseGrid(100.0f);
    const std::string path = writeGrid(dir, "dense", grid);
    test::damageLeafValues(path, {"Tree_float_5_4_3"}, openvdb::Coord(16, 8, 24));
    for (int open = 0; open < 2; ++open) {
      const Store store(path, "", true);
      store.brickRanges();
      EXPECT_EQ(store.rangesFrom(), Store::RangesFrom::Leaves);
      EXPECT_EQ(store.damage().count, 1u) << "open " << open;
    }
    EXPECT_TRUE(cache.files().empty());
  }
  {
    const ScopedCache cache("0");  // every file but the one just written goes
    test::TempDir dir;
    const std::string a = writeSphere(dir, "a", 21.0f), b = writeSphere(dir, "b", 21.0f);
    Store(a, "", true).brickRanges();
    ASSERT_EQ(cache.files().size(), 1u);
    EXPECT_EQ(cache.files()[0].rfind("a.vdb-", 0), 0u);
    Store(b, "", true).brickRanges();
    ASSERT_EQ(cache.files().size(), 1u);
    EXPECT_EQ(cache.files()[0].rfind("b.vdb-", 0), 0u) << "the least recently used file was kept";
  }
}

// ---------------------------------------------------------------------------------------------------------
// The range cache's reader alone (io/CartesianRangeCache.h), and what fuzz_cartesian_range_cache found in it.

uint64_t fnv1a(const std::string& bytes, std::size_t size) {
  uint64_t h = 1469598103934665603ull;
  for (std::size_t i = 0; i < size; ++i) {
    h ^= static_cast<unsigned char>(bytes[i]);
    h *= 1099511628211ull;
  }
  return h;
}
// The file's trailing checksum made right again after an edit.
void reseal(std::string& bytes) {
  const uint64_t sum = fnv1a(bytes, bytes.size() - sizeof(uint64_t));
  std::memcpy(bytes.data() + bytes.size() - sizeof(uint64_t), &sum, sizeof sum);
}

// A box as wide as a sparse grid's can be (leaves near -2^31 and 2^31: 2^28 bricks an axis) holds more
// bricks than 64 bits count. The reader's bound on the records multiplied the extents as int64: undefined
// behaviour (fuzz_cartesian_range_cache, UBSan's signed overflow), which here wrapped to 0 bricks, so a
// valid file under such a box was never read. The bound saturates now.
TEST(CartesianRangeCache, ABoxWhoseVolumeOverflows64BitsStillReadsItsRanges) {
  test::TempDir dir;
  const std::string file = dir / "wide.ccranges", key = "FCCRNG1\nwide";
  constexpr int kFar = 1 << 27;
  const std::vector<CartesianBrickRange> ranges = {{glm::ivec3(-kFar), -1.0f, 0.5f}, {glm::ivec3(kFar - 1), 2.0f, 3.0f}};
  writeCartesianRangeCache(file, key, ranges);
  const int kMin = std::numeric_limits<int>::min(), kMax = std::numeric_limits<int>::max();
  for (const auto& [lo, hi] : {std::pair(glm::ivec3(-kFar), glm::ivec3(kFar - 1)), std::pair(glm::ivec3(kMin), glm::ivec3(kMax))}) {
    SCOPED_TRACE(hi.x);
    const auto read = readCartesianRangeCache(file, key, lo, hi);
    ASSERT_TRUE(read.has_value()) << "a valid file was refused";
    ASSERT_EQ(read->size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
      EXPECT_EQ((*read)[i].brick, ranges[i].brick);
      EXPECT_EQ((*read)[i].lo, ranges[i].lo);
      EXPECT_EQ((*read)[i].hi, ranges[i].hi);
    }
  }
}

// Under a box of 2^63 - 2^42 bricks (no overflow there), a count of 2^62 + 2 records makes 20 (2^62 + 2)
// bytes, which is 40 modulo 2^64: the two records the file holds. The size check passed, and the
// reader asked std::vector for 2^62 records, which threw std::length_error out of a reader that promises
// never to throw. The count is checked against the bytes there are now.
TEST(CartesianRangeCache, ACountWhoseBytesWrapAroundIsNoCacheAndNoThrow) {
  test::TempDir dir;
  const std::string file = dir / "wrap.ccranges", key = "FCCRNG1\nwrap";
  const glm::ivec3 lo(0), hi((1 << 21) - 1, (1 << 21) - 1, (1 << 21) - 2);
  writeCartesianRangeCache(file, key, {{glm::ivec3(0, 0, 0), 0.0f, 1.0f}, {glm::ivec3(1, 0, 0), 0.0f, 2.0f}});
  ASSERT_TRUE(readCartesianRangeCache(file, key, lo, hi).has_value());
  std::string bytes = readAll(file);
  const uint64_t count = (uint64_t(1) << 62) + 2;
  std::memcpy(bytes.data() + 16 + key.size(), &count, sizeof count);
  reseal(bytes);
  writeAll(file, bytes);
  std::optional<std::vector<CartesianBrickRange>> read;
  EXPECT_NO_THROW(read = readCartesianRangeCache(file, key, lo, hi));
  EXPECT_FALSE(read.has_value());
}

// lo <= hi is the contract, and a NaN breaks it without failing `lo > hi`: the leaves' pass never writes
// a NaN (std::min and std::max pass over them), so a file holding one is damaged. Infinite ends are
// ranges like any other.
TEST(CartesianRangeCache, ANanRangeIsNoCache) {
  test::TempDir dir;
  const std::string file = dir / "nan.ccranges", key = "FCCRNG1\nnan";
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const glm::ivec3 lo(0), hi(3);
  for (const auto& [a, b] : {std::pair(nan, 1.0f), std::pair(0.0f, nan), std::pair(nan, nan)}) {
    writeCartesianRangeCache(file, key, {{glm::ivec3(0), 0.0f, 1.0f}, {glm::ivec3(1, 0, 0), a, b}});
    EXPECT_FALSE(readCartesianRangeCache(file, key, lo, hi).has_value()) << a << " " << b;
  }
  writeCartesianRangeCache(file, key, {{glm::ivec3(0), -inf, inf}});
  EXPECT_TRUE(readCartesianRangeCache(file, key, lo, hi).has_value());
  // The empty range (+inf, -inf) — what the leaves' pass gives a brick of NaNs alone — reads as written;
  // any other inverted range is damage.
  writeCartesianRangeCache(file, key, {{glm::ivec3(0), inf, -inf}});
  const auto empty = readCartesianRangeCache(file, key, lo, hi);
  ASSERT_TRUE(empty.has_value());
  EXPECT_EQ(empty->at(0).lo, inf);
  EXPECT_EQ(empty->at(0).hi, -inf);
  for (const auto& [a, b] : {std::pair(1.0f, 0.0f), std::pair(inf, 0.0f), std::pair(0.0f, -inf), std::pair(inf, inf - inf)}) {
    writeCartesianRangeCache(file, key, {{glm::ivec3(0), a, b}});
    EXPECT_FALSE(readCartesianRangeCache(file, key, lo, hi).has_value()) << a << " " << b;
  }
}

// A grid whose brick 0 holds NaNs alone: its range is the empty one, and the second open reads the
// ranges from the cache (until session 16 the reader refused that range, so every open computed the
// ranges from the leaves and wrote the file again).
TEST(CartesianBrickStore, ABrickOfNansAloneIsCachedLikeAnyOther) {
  const ScopedCache cache;
  test::TempDir dir;
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  // Brick 0's block (sites -2 .. 17 on each axis) lies in the leaves at -8, 0, 8, 16: all NaN.
  for (int x = -8; x <= 16; x += 8)
    for (int y = -8; y <= 16; y += 8)
      for (int z = -8; z <= 16; z += 8)
        grid->tree().touchLeaf(openvdb::Coord(x, y, z))->fill(std::numeric_limits<float>::quiet_NaN());
  grid->tree().touchLeaf(openvdb::Coord(64, 0, 0))->fill(2.0f);
  const std::string path = writeGrid(dir, "nans", grid);
  std::vector<Store::BrickRange> first;
  {
    const Store store(path, "", /*cacheRanges=*/true);
    first = store.brickRanges();
    EXPECT_EQ(store.rangesFrom(), Store::RangesFrom::Leaves);
  }
  const auto nanBrick = std::find_if(first.begin(), first.end(), [](const Store::BrickRange& r) { return r.brick == glm::ivec3(0); });
  ASSERT_NE(nanBrick, first.end());
  EXPECT_EQ(nanBrick->lo, std::numeric_limits<float>::infinity());
  EXPECT_EQ(nanBrick->hi, -std::numeric_limits<float>::infinity());
  {
    const Store store(path, "", true);
    expectSameRanges(store.brickRanges(), first);
    EXPECT_EQ(store.rangesFrom(), Store::RangesFrom::Cache) << "the ranges were computed again";
    EXPECT_EQ(store.leavesRead(), 0u);
  }
}

// Every input of the fuzz target's corpus (tests/fuzz/corpus/cartesian_range_cache: the seeds
// make_seeds.py writes, and the inputs that found a bug, regress_*), read as fuzz_cartesian_range_cache
// reads it — 25 bytes of box and flags, then the file — in this (gcc, unsanitized) build: the valid
// seeds are read, every bad_* and regress_* input is no cache, none throws.
TEST(CartesianRangeCache, FuzzCorpusInputsGetTheirVerdicts) {
  // The key of fuzz_cartesian_range_cache.cpp (and make_seeds.py).
  const std::string key = "FCCRNG1\n/data/volume.vdb\n123456 1700000000.123456789\ndensity\n"
                          "bricks 16, blocks from -2 of 20 points, leaf slabs 2";
  const std::filesystem::path corpus = std::filesystem::path(FCC_SOURCE_DIR) / "tests/fuzz/corpus/cartesian_range_cache";
  test::TempDir dir;
  int valid = 0, refused = 0, regressions = 0;
  for (const auto& entry : std::filesystem::directory_iterator(corpus)) {
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    const std::string input = readAll(entry.path().string());
    ASSERT_GE(input.size(), 25u);
    int32_t box[6];
    std::memcpy(box, input.data(), sizeof box);
    std::string bytes = input.substr(25);
    if ((input[24] & 1) && bytes.size() >= sizeof(uint64_t)) reseal(bytes);
    const std::string file = dir / "volume.vdb-0123456789abcdef.ccranges";
    writeAll(file, bytes);
    std::optional<std::vector<CartesianBrickRange>> read;
    EXPECT_NO_THROW(read = readCartesianRangeCache(file, key, glm::ivec3(box[0], box[1], box[2]), glm::ivec3(box[3], box[4], box[5])));
    const bool bad = name.rfind("bad_", 0) == 0 || name.rfind("regress_", 0) == 0;
    EXPECT_EQ(read.has_value(), !bad);
    valid += !bad;
    refused += bad;
    regressions += name.rfind("regress_", 0) == 0;
  }
  EXPECT_GE(valid, 5);
  EXPECT_GE(refused, 10);
  EXPECT_GE(regressions, 1);
}

}  // namespace
}  // namespace fcc::io
