// VdbLeafReader (io/VdbLeafReader.h): every leaf bit for bit against OpenVDB's full read, for float and
// Vec4f grids with every kind of inactive values, every compression and half storage; the topology it
// hands out; a seeded damage campaign (never a crash, only InputError); its error messages.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/LevelSetUtil.h>
#include <fcntl.h>
#include <sys/resource.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <random>
#include <set>
#include <tuple>

#include "SameVdbFiles.h"
#include "io/VdbLeafReader.h"
#include "sparse/Error.h"
#include "sparse/FccGrid.h"
#include "tests/tools/RunCommand.h"

namespace fcc::io {
namespace {

using openvdb::Coord;
using test::TempDir;
namespace vio = openvdb::io;

// ---------------------------------------------------------------------------------------------------------
// Grids

template <class T>
T scalarValue(float v, int) {
  return v;
}
template <>
openvdb::Vec4f scalarValue<openvdb::Vec4f>(float v, int salt) {
  return openvdb::Vec4f(v, v * 0.5f + float(salt), -v, 1.0f / (1.0f + std::abs(v)));
}

// A grid whose leaves hold every kind of inactive values io::writeCompressedValues distinguishes
// (compression metadata 0 to 6), a leaf with no active voxel (nothing stored when mask-compressed), one
// with every voxel active, leaves in several root children (negative coordinates too), and tiles at the
// root and both internal levels, active and inactive. Its class stays unknown, so zip stays on.
// `compact`: all in one root child (each root child costs OpenVDB about 1 MB to read: the damage campaign
// opens thousands).
template <class GridT>
typename GridT::Ptr craftedGrid(const std::string& name, const typename GridT::ValueType& background,
                                bool compact = false) {
  using V = typename GridT::ValueType;
  auto grid = GridT::create(background);
  grid->setName(name);
  grid->insertMeta("note", openvdb::StringMetadata("crafted for test_vdb_leaf_reader"));
  auto& tree = grid->tree();
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  const V minusBg = openvdb::math::negative(background);
  const V seven = scalarValue<V>(7.0f, 1), five = scalarValue<V>(5.0f, 2);
  // kind -> (active?, inactive value) per voxel
  auto fill = [&](const Coord& origin, int kind) {
    auto* leaf = tree.touchLeaf(origin);
    for (openvdb::Index n = 0; n < 512; ++n) {
      bool active = n % 3 == 0;
      V inactive = background;
      switch (kind) {
        case 0: break;                                                    // metadata 0
        case 1: inactive = minusBg; break;                                // 1
        case 2: inactive = seven; break;                                  // 2
        case 3: inactive = (n / 3) % 2 ? background : minusBg; break;     // 3
        case 4: inactive = (n / 5) % 2 ? background : seven; break;       // 4
        case 5: inactive = (n / 7) % 2 ? five : seven; break;             // 5
        case 6: inactive = scalarValue<V>(float(n % 4), 3); break;        // 6
        case 7: active = true; break;                                     // all active
        case 8: active = false; break;                                    // none active
        case 9: active = false; inactive = (n / 7) % 2 ? five : seven; break;
        case 10: active = n == 0 || n == 511; inactive = minusBg; break;
      }
      leaf->setValueOnly(n, active ? scalarValue<V>(u(rng), int(n)) : inactive);
      leaf->setActiveState(n, active);
    }
  };
  const Coord origins[] = {{0, 0, 0},     {8, 0, 0},       {0, 8, 16},     {-8, -16, 24}, {4096, 0, 8},
                           {-4096, 8, 0}, {128, 128, 128}, {0, 4096, -8},  {16, 16, 16},  {-1024, 512, 64},
                           {40, 48, 56}};
  int kind = 0;
  for (const Coord& o : origins) fill(compact ? Coord(o.x() & 4095, o.y() & 4095, o.z() & 4095) : o, kind++ % 11);
  tree.addTile(1, Coord(1024, 0, 0), scalarValue<V>(3.0f, 4), true);       // a 8^3 tile in a 16^3 node
  tree.addTile(1, Coord(1032, 0, 0), scalarValue<V>(9.0f, 5), false);      // inactive, not background
  tree.addTile(2, Coord(2048, 0, 0), scalarValue<V>(-4.0f, 6), true);      // a 128^3 tile in a 32^3 node
  if (!compact) tree.addTile(3, Coord(-8192, 0, 0), scalarValue<V>(6.0f, 7), true);  // a root tile
  return grid;
}

openvdb::FloatGrid::Ptr levelSet() {
  auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(/*radius=*/18.0f, openvdb::Vec3f(1.5f, -2.0f, 3.0f),
                                                                       /*voxelSize=*/1.0f, /*halfWidth=*/3.0f);
  grid->setName("levelset");
  return grid;
}

openvdb::FloatGrid::Ptr fogVolume() {
  auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(40.0f, openvdb::Vec3f(0.0f), 1.0f, 3.0f);
  openvdb::tools::sdfToFogVolume(*grid);
  grid->setName("fog");
  return grid;
}

void writeFile(const std::string& path, const openvdb::GridPtrVec& grids, uint32_t compression, bool half) {
  initializeVdb();
  for (const auto& g : grids) g->setSaveFloatAsHalf(half);
  vio::File file(path);
  file.setCompression(compression);
  file.write(grids);
  file.close();
}

openvdb::GridBase::Ptr readFully(const std::string& path, const std::string& name) {
  vio::File file(path);
  file.setCopyMaxBytes(0);
  file.open(/*delayLoad=*/false);
  auto grid = file.readGrid(name);
  file.close();
  return grid;
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(bytes.size()));
}

// ---------------------------------------------------------------------------------------------------------
// Comparison with OpenVDB's full read

template <class TreeT>
std::vector<std::tuple<Coord, int, std::string, bool>> tilesOf(const TreeT& tree) {
  using V = typename TreeT::ValueType;
  std::vector<std::tuple<Coord, int, std::string, bool>> out;
  auto it = tree.cbeginValueAll();
  it.setMaxDepth(TreeT::ValueAllCIter::LEAF_DEPTH - 1);  // never the leaves: ours have no buffers
  for (; it; ++it) {
    const V v = *it;
    out.emplace_back(it.getCoord(), it.getDepth(), std::string(reinterpret_cast<const char*>(&v), sizeof v), it.isValueOn());
  }
  return out;
}

// Which compression metadata bytes (0..6) the file's leaves of `reader` use.
std::set<int> metadataBytesUsed(const VdbLeafReader& reader, const std::string& bytes) {
  std::set<int> used;
  for (size_t i = 0; i < reader.leafCount(); ++i) used.insert(int(int8_t(bytes[reader.leafOffset(i) + 64])));
  return used;
}

template <class GridT>
void expectSameAsOpenVdb(const std::string& path, const std::string& name, bool half, uint32_t compression) {
  SCOPED_TRACE("grid " + name);
  using TreeT = typename GridT::TreeType;
  const auto full = openvdb::gridPtrCast<GridT>(readFully(path, name));
  ASSERT_TRUE(full);
  const VdbLeafReader reader(path, name, {});
  const auto ours = openvdb::gridPtrCast<GridT>(reader.grid());
  ASSERT_TRUE(ours);
  EXPECT_EQ(reader.gridName(), name);
  EXPECT_EQ(reader.gridType(), TreeT::treeType());
  EXPECT_EQ(reader.components(), (std::is_same_v<typename GridT::ValueType, float> ? 1 : 4));
  EXPECT_EQ(reader.storedAsHalf(), half);
  EXPECT_EQ(ours->saveFloatAsHalf(), half);
  // Archive drops zip for level sets and fog volumes.
  const bool noZip = full->getGridClass() == openvdb::GRID_LEVEL_SET || full->getGridClass() == openvdb::GRID_FOG_VOLUME;
  EXPECT_EQ(reader.compression(), noZip ? (compression & ~uint32_t(vio::COMPRESS_ZIP)) : compression);

  // Metadata, transform, background, tiles, leaf origins and masks.
  test::expectSameMetadata(*full, *ours);
  test::expectSameMetadata(*ours, *full);
  EXPECT_TRUE(full->transform() == ours->transform());
  const TreeT &a = full->tree(), &b = ours->tree();
  EXPECT_EQ(0, std::memcmp(&a.background(), &b.background(), sizeof(typename TreeT::ValueType)));
  EXPECT_TRUE(tilesOf(a) == tilesOf(b)) << "tiles differ";
  ASSERT_EQ(a.leafCount(), reader.leafCount());
  ASSERT_EQ(b.leafCount(), reader.leafCount());
  uint64_t recordBytes = 0;
  size_t i = 0;
  auto lb = b.cbeginLeaf();
  std::vector<float> values(512 * size_t(reader.components()));
  int differ = 0;
  for (auto la = a.cbeginLeaf(); la; ++la, ++lb, ++i) {
    ASSERT_TRUE(lb);
    ASSERT_EQ(la->origin(), lb->origin());
    ASSERT_EQ(reader.leafOrigin(i), la->origin());
    EXPECT_EQ(reader.leafIndexAt(la->origin()), std::optional<size_t>(i));
    EXPECT_TRUE(la->valueMask() == lb->valueMask()) << "mask of the leaf at " << la->origin();
    EXPECT_FALSE(lb->buffer().isOutOfCore());
    EXPECT_TRUE(lb->buffer().empty()) << "our topology's leaves hold no values";
    recordBytes += reader.leafBytes(i);
    EXPECT_LE(reader.leafBytes(i), VdbLeafReader::kMaxLeafBytes);
    std::fill(values.begin(), values.end(), std::nanf("1"));
    reader.readLeaf(i, values.data());
    if (std::memcmp(values.data(), la->buffer().data(), values.size() * sizeof(float)) != 0 && ++differ <= 3)
      ADD_FAILURE() << "values of the leaf at " << la->origin() << " (index " << i << ")";
  }
  EXPECT_EQ(differ, 0);
  EXPECT_EQ(recordBytes, reader.bufferEnd() - reader.bufferBegin()) << "the records tile the buffer section";
  EXPECT_FALSE(reader.leafIndexAt(Coord(1, 0, 0)));
  EXPECT_FALSE(reader.leafIndexAt(Coord(8000, 8, 8)));
  EXPECT_FALSE(reader.leafIndexAt(Coord(1 << 20, 0, 0)));

  if (compression & vio::COMPRESS_ACTIVE_MASK) {
    const std::set<int> used = metadataBytesUsed(reader, fileBytes(path));
    if (name == "crafted" || name == "crafted4") {
      EXPECT_EQ(used, (std::set<int>{0, 1, 2, 3, 4, 5, 6})) << "the crafted leaves cover every inactive-value kind";
    }
    if (name == "levelset") {
      EXPECT_TRUE(used.count(1) && used.count(3)) << "inside: -background";
    }
  }
}

struct Variant {
  uint32_t compression;
  bool half;
};

std::string variantName(const testing::TestParamInfo<Variant>& info) {
  const uint32_t c = info.param.compression;
  std::string s = c & vio::COMPRESS_BLOSC ? "Blosc" : c & vio::COMPRESS_ZIP ? "Zip" : "Uncompressed";
  s += c & vio::COMPRESS_ACTIVE_MASK ? "ActiveMask" : "NoActiveMask";
  return s + (info.param.half ? "Half" : "Float");
}

class LeafReaderVariants : public testing::TestWithParam<Variant> {};

TEST_P(LeafReaderVariants, EveryLeafBitForBitAsOpenVdbReadsIt) {
  const Variant v = GetParam();
  TempDir dir;
  const std::string path = dir / "grids.vdb";
  writeFile(path,
            {craftedGrid<openvdb::FloatGrid>("crafted", 2.5f), levelSet(), fogVolume(),
             craftedGrid<FccGrid>("crafted4", openvdb::Vec4f(0.5f, -1.0f, 2.0f, 0.0f))},
            v.compression, v.half);
  expectSameAsOpenVdb<openvdb::FloatGrid>(path, "crafted", v.half, v.compression);
  expectSameAsOpenVdb<openvdb::FloatGrid>(path, "levelset", v.half, v.compression);
  expectSameAsOpenVdb<openvdb::FloatGrid>(path, "fog", v.half, v.compression);
  expectSameAsOpenVdb<FccGrid>(path, "crafted4", v.half, v.compression);
}

constexpr uint32_t kMask = vio::COMPRESS_ACTIVE_MASK;
INSTANTIATE_TEST_SUITE_P(
    VdbLeafReader, LeafReaderVariants,
    testing::Values(Variant{vio::COMPRESS_BLOSC | kMask, false}, Variant{vio::COMPRESS_BLOSC | kMask, true},
                    Variant{vio::COMPRESS_ZIP | kMask, false}, Variant{vio::COMPRESS_ZIP | kMask, true},
                    Variant{kMask, false}, Variant{kMask, true},
                    Variant{vio::COMPRESS_BLOSC, false}, Variant{vio::COMPRESS_BLOSC, true},
                    Variant{vio::COMPRESS_ZIP, false}, Variant{vio::COMPRESS_NONE, true}),
    variantName);

// The grid picked by type when no name is given; the first of several; listGrids.
TEST(VdbLeafReader, PicksTheFirstGridOfTheTypesAndListsGrids) {
  TempDir dir;
  const std::string path = dir / "two.vdb";
  writeFile(path, {levelSet(), craftedGrid<FccGrid>("crafted4", openvdb::Vec4f(0.0f))}, vio::COMPRESS_BLOSC | kMask, false);
  EXPECT_EQ(VdbLeafReader(path, "", {}).gridName(), "levelset");
  EXPECT_EQ(VdbLeafReader(path, "", {"Tree_float_5_4_3"}).gridName(), "levelset");
  const VdbLeafReader vec4(path, "", {kFccTreeTypeName});
  EXPECT_EQ(vec4.gridName(), "crafted4");
  EXPECT_EQ(vec4.components(), 4);
  const auto grids = VdbLeafReader::listGrids(path);
  ASSERT_EQ(grids.size(), 2u);
  EXPECT_EQ(grids[0].name, "levelset");
  EXPECT_EQ(grids[0].type, "Tree_float_5_4_3");
  EXPECT_EQ(grids[1].name, "crafted4");
  EXPECT_EQ(grids[1].type, kFccTreeTypeName);
}

// Grids without leaves: one with a tile only, one empty.
TEST(VdbLeafReader, OpensGridsWithoutLeaves) {
  TempDir dir;
  const std::string path = dir / "empty.vdb";
  auto tiles = openvdb::FloatGrid::create(1.0f);
  tiles->setName("tiles");
  tiles->tree().addTile(2, Coord(128, 0, 0), 5.0f, true);
  auto empty = FccGrid::create(openvdb::Vec4f(0.0f));
  empty->setName("empty");
  writeFile(path, {tiles, empty}, vio::COMPRESS_BLOSC | kMask, true);
  const VdbLeafReader a(path, "tiles", {}), b(path, "empty", {});
  EXPECT_EQ(a.leafCount(), 0u);
  EXPECT_EQ(b.leafCount(), 0u);
  EXPECT_EQ(a.bufferBegin(), a.bufferEnd());
  EXPECT_EQ(openvdb::gridPtrCast<openvdb::FloatGrid>(a.grid())->tree().getValue(Coord(130, 1, 2)), 5.0f);
  EXPECT_FALSE(a.leafIndexAt(Coord(0, 0, 0)));
}

// Any thread reads any leaf: all at once, in parallel, twice over.
TEST(VdbLeafReader, ReadsLeavesFromManyThreads) {
  TempDir dir;
  const std::string path = dir / "ls.vdb";
  writeFile(path, {levelSet()}, vio::COMPRESS_BLOSC | kMask, false);
  const auto full = openvdb::gridPtrCast<openvdb::FloatGrid>(readFully(path, "levelset"));
  std::vector<const openvdb::FloatTree::LeafNodeType*> leaves;
  for (auto it = full->tree().cbeginLeaf(); it; ++it) leaves.push_back(&*it);
  const VdbLeafReader reader(path, "levelset", {});
  ASSERT_EQ(reader.leafCount(), leaves.size());
  std::atomic<int> differ{0};
  tbb::parallel_for(size_t(0), 2 * leaves.size(), [&](size_t k) {
    const size_t i = (k * 7919) % leaves.size();
    float values[512];
    reader.readLeaf(i, values);
    if (std::memcmp(values, leaves[i]->buffer().data(), sizeof values) != 0) ++differ;
  });
  EXPECT_EQ(differ.load(), 0);
}

// ---------------------------------------------------------------------------------------------------------
// Damage

// Every byte of the file from `from` on, or in [from, to), may be damaged; opening and reading every
// leaf of both grids must then either work or throw InputError naming the file in one line.
struct Outcome {
  int opened = 0, refused = 0, leavesRead = 0, leavesRefused = 0;
};

void openAndReadAll(const std::string& path, const std::string& grid, Outcome& o) {
  auto checkMessage = [&](const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind(path + ": ", 0), 0u) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  };
  std::unique_ptr<VdbLeafReader> reader;
  try {
    reader = std::make_unique<VdbLeafReader>(path, grid, std::vector<std::string>{});
  } catch (const InputError& e) {
    checkMessage(e);
    ++o.refused;
    return;
  }
  ++o.opened;
  std::vector<float> values(512 * size_t(reader->components()));
  for (size_t i = 0; i < reader->leafCount(); ++i) {
    try {
      reader->readLeaf(i, values.data());
      ++o.leavesRead;
    } catch (const InputError& e) {
      checkMessage(e);
      EXPECT_NE(std::string(e.what()).find(" is damaged: "), std::string::npos) << e.what();
      ++o.leavesRefused;
    }
  }
}

enum class Damage { BitFlips, Truncation, Overwrite };

struct Region {
  uint64_t begin, end;
};

// `trials` damaged copies of `bytes`, each with one kind of damage at offsets drawn from `regions`.
Outcome damageCampaign(const std::string& bytes, const std::vector<Region>& regions, Damage damage, int trials,
                       uint32_t seed, const std::string& path) {
  std::mt19937_64 rng(seed);
  Outcome o;
  uint64_t total = 0;
  for (const Region& r : regions) total += r.end - r.begin;
  auto offset = [&] {
    uint64_t k = std::uniform_int_distribution<uint64_t>(0, total - 1)(rng);
    for (const Region& r : regions) {
      if (k < r.end - r.begin) return r.begin + k;
      k -= r.end - r.begin;
    }
    return regions.back().end - 1;
  };
  for (int t = 0; t < trials; ++t) {
    std::string damaged = bytes;
    switch (damage) {
      case Damage::BitFlips: {
        const int flips = 1 + int(rng() % 4);
        for (int f = 0; f < flips; ++f) damaged[offset()] ^= char(1u << (rng() % 8));
        break;
      }
      case Damage::Truncation:
        damaged.resize(offset());
        break;
      case Damage::Overwrite: {
        const uint64_t at = offset();
        for (uint64_t k = at; k < std::min<uint64_t>(at + 32, damaged.size()); ++k) damaged[k] = char(rng());
        break;
      }
    }
    writeBytes(path, damaged);
    try {
      openAndReadAll(path, "crafted", o);
      openAndReadAll(path, "crafted4", o);
    } catch (const std::exception& e) {
      ADD_FAILURE() << "trial " << t << ": " << typeid(e).name() << ": " << e.what();
    }
  }
  return o;
}

struct DamageCase {
  const char* name;
  uint32_t compression;
  bool half;
};

class LeafReaderDamage : public testing::TestWithParam<DamageCase> {};

// The buffer sections (parsed only by us), and separately the header and grid descriptors (ours too);
// the metadata, transform and topology between them are parsed by OpenVDB and left alone.
TEST_P(LeafReaderDamage, OnlyInputErrorsNeverACrash) {
  const DamageCase c = GetParam();
  TempDir dir;
  // The damaged copies are rewritten a thousand times: in memory (tmpfs) where there is one.
  const bool shm = ::access("/dev/shm", W_OK) == 0;
  const std::string original = dir / "original.vdb",
                    path = shm ? "/dev/shm/fcc_leaf_reader_" + std::to_string(::getpid()) + "_" + c.name + ".vdb"
                               : dir / "damaged.vdb";
  struct Remove {
    std::string path;
    ~Remove() { std::filesystem::remove(path); }
  } remove{path};
  writeFile(original,
            {craftedGrid<openvdb::FloatGrid>("crafted", 2.5f, /*compact=*/true),
             craftedGrid<FccGrid>("crafted4", openvdb::Vec4f(0.5f, -1, 2, 0), /*compact=*/true)},
            c.compression, c.half);
  const std::string bytes = fileBytes(original);
  const VdbLeafReader first(original, "crafted", {}), second(original, "crafted4", {});
  const std::vector<Region> buffers{{first.bufferBegin(), first.bufferEnd()}, {second.bufferBegin(), second.bufferEnd()}};
  // The header, file metadata and first descriptor; the second descriptor (at the first grid's end).
  const std::vector<Region> header{{0, first.gridBegin()}, {first.bufferEnd(), second.gridBegin()}};
  // The heads of the leaf records (mask, metadata byte, inactive values, selection mask, size, blosc header).
  std::vector<Region> heads;
  for (const VdbLeafReader* r : {&first, &second})
    for (size_t i = 0; i < r->leafCount(); ++i)
      heads.push_back({r->leafOffset(i), r->leafOffset(i) + std::min<uint64_t>(r->leafBytes(i), 100)});
  // FCC_LEAF_READER_DAMAGE_SCALE=N runs N times the trials (for a longer run, e.g. under ASan).
  const char* scaleText = std::getenv("FCC_LEAF_READER_DAMAGE_SCALE");
  const int scale = std::max(1, scaleText ? std::atoi(scaleText) : 1);
  int refusedAny = 0;
  uint32_t seed = 1;
  for (const auto& [regions, regionName] :
       {std::pair{buffers, "buffers"}, std::pair{heads, "record heads"}, std::pair{header, "header"}})
    for (const Damage d : {Damage::BitFlips, Damage::Overwrite, Damage::Truncation}) {
      SCOPED_TRACE(std::string(regionName) + " damage " + std::to_string(int(d)));
      const int trials = (d == Damage::Truncation ? 30 : 100) * scale;
      const Outcome o = damageCampaign(bytes, regions, d, trials, seed++, path);
      std::printf("%s, %s damage %d: %d opened, %d refused; %d leaves read, %d refused\n", c.name, regionName, int(d),
                  o.opened, o.refused, o.leavesRead, o.leavesRefused);
      EXPECT_EQ(o.opened + o.refused, 2 * trials);
      refusedAny += o.refused + o.leavesRefused;
      if (d == Damage::Truncation) {
        EXPECT_EQ(o.opened, 0) << "a truncated file never opens";
      }
    }
  EXPECT_GT(refusedAny, 0);
}

INSTANTIATE_TEST_SUITE_P(VdbLeafReader, LeafReaderDamage,
                         testing::Values(DamageCase{"Blosc", vio::COMPRESS_BLOSC | kMask, false},
                                         DamageCase{"ZipHalf", vio::COMPRESS_ZIP | kMask, true},
                                         DamageCase{"Uncompressed", vio::COMPRESS_NONE, false}),
                         [](const testing::TestParamInfo<DamageCase>& info) { return std::string(info.param.name); });

// Damage after opening: a file truncated, or a leaf's bytes changed, under an open reader.
TEST(VdbLeafReader, NoticesAFileChangedAfterOpening) {
  TempDir dir;
  const std::string path = dir / "ls.vdb";
  writeFile(path, {levelSet()}, vio::COMPRESS_BLOSC | kMask, false);
  const auto full = openvdb::gridPtrCast<openvdb::FloatGrid>(readFully(path, "levelset"));
  const VdbLeafReader reader(path, "levelset", {});
  ASSERT_GT(reader.leafCount(), 10u);
  const size_t overwritten = 3;
  {
    std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
    char mask[4];
    f.seekg(std::streamoff(reader.leafOffset(overwritten)));
    f.read(mask, 4);
    for (char& b : mask) b = char(~b);
    f.seekp(std::streamoff(reader.leafOffset(overwritten)));
    f.write(mask, 4);  // its value mask, inverted
  }
  const size_t cut = reader.leafCount() / 2;
  std::filesystem::resize_file(path, reader.leafOffset(cut) + reader.leafBytes(cut) / 2);
  size_t i = 0;
  float values[512];
  for (auto it = full->tree().cbeginLeaf(); it; ++it, ++i) {
    if (i == overwritten || i >= cut) {
      try {
        reader.readLeaf(i, values);
        ADD_FAILURE() << "leaf " << i << " read";
      } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()).find(path + ": leaf at ("), 0u) << e.what();
        EXPECT_NE(std::string(e.what()).find(" is damaged: "), std::string::npos) << e.what();
      }
    } else {
      reader.readLeaf(i, values);
      EXPECT_EQ(0, std::memcmp(values, it->buffer().data(), sizeof values)) << "leaf " << i;
    }
  }
}

// A leaf whose record head is damaged (its compression metadata byte out of range, as one flipped byte
// makes it) hides its own size, but not the next leaf's record, which starts with that leaf's value mask:
// the file opens, exactly that leaf is damaged, and every other reads as OpenVDB reads it. The first,
// a middle and the last leaf (whose record ends the section), blosc and zip, a float level set and a
// four-channel grid of incompressible values (records of up to 8 KiB, the whole largest one searched).
template <class GridT>
void expectOneDamagedLeafPerDamagedHead(const TempDir& dir, const typename GridT::Ptr& grid) {
  constexpr size_t kFloats = 512 * sizeof(typename GridT::ValueType) / sizeof(float);
  for (const uint32_t compression : {vio::COMPRESS_BLOSC | kMask, vio::COMPRESS_ZIP | kMask}) {
    const std::string path = dir / "clean.vdb";
    writeFile(path, {grid}, compression, false);
    const auto full = openvdb::gridPtrCast<GridT>(readFully(path, grid->getName()));
    const VdbLeafReader clean(path, grid->getName(), {});
    ASSERT_GT(clean.leafCount(), 10u);
    const std::string bytes = fileBytes(path);
    for (const size_t target : {size_t(0), clean.leafCount() / 2, clean.leafCount() - 1}) {
      SCOPED_TRACE(grid->getName() + ", compression " + std::to_string(compression) + ", leaf " + std::to_string(target));
      std::string damagedBytes = bytes;
      damagedBytes[size_t(clean.leafOffset(target)) + 64] = char(0xe5);  // the metadata byte after the mask
      const std::string damagedPath = dir / "damaged.vdb";
      writeBytes(damagedPath, damagedBytes);
      const VdbLeafReader reader(damagedPath, grid->getName(), {});
      ASSERT_EQ(reader.leafCount(), clean.leafCount());
      EXPECT_EQ(reader.damagedAtOpen(), 1u);
      size_t i = 0;
      std::vector<float> values(kFloats);
      for (auto it = full->tree().cbeginLeaf(); it; ++it, ++i) {
        EXPECT_EQ(reader.leafOffset(i), clean.leafOffset(i)) << "leaf " << i;
        if (i == target) {
          try {
            reader.readLeaf(i, values.data());
            ADD_FAILURE() << "the damaged leaf read";
          } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("is damaged: compression metadata -27 (valid: 0 to 6)"), std::string::npos)
                << e.what();
          }
          continue;
        }
        reader.readLeaf(i, values.data());
        EXPECT_EQ(0, std::memcmp(values.data(), it->buffer().data(), kFloats * sizeof(float))) << "leaf " << i;
      }
    }
  }
}

TEST(VdbLeafReader, ADamagedRecordHeadIsOneDamagedLeaf) {
  TempDir dir;
  expectOneDamagedLeafPerDamagedHead<openvdb::FloatGrid>(dir, levelSet());
  expectOneDamagedLeafPerDamagedHead<FccGrid>(dir, craftedGrid<FccGrid>("crafted4", openvdb::Vec4f(0.0f)));
}

// ---------------------------------------------------------------------------------------------------------
// Error messages

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    return e.what();
  }
  return "(no InputError)";
}

TEST(VdbLeafReader, SaysWhatIsWrong) {
  TempDir dir;
  const std::string path = dir / "two.vdb";
  writeFile(path, {craftedGrid<openvdb::FloatGrid>("crafted", 1.0f), craftedGrid<FccGrid>("crafted4", openvdb::Vec4f(0.0f))},
            vio::COMPRESS_BLOSC | kMask, false);
  using testing::HasSubstr;
  using testing::StartsWith;

  const std::string missing = errorOf([&] { VdbLeafReader(path, "density", {}); });
  EXPECT_THAT(missing, StartsWith(path + ": no grid named \"density\""));
  EXPECT_THAT(missing, HasSubstr("grids: \"crafted\" (Tree_float_5_4_3), \"crafted4\" (Tree_vec4s_5_4_3)"));

  EXPECT_THAT(errorOf([&] { VdbLeafReader(path, "crafted", {kFccTreeTypeName}); }),
              StartsWith(path + ": grid \"crafted\" is a Tree_float_5_4_3 grid; valid here: Tree_vec4s_5_4_3"));

  const std::string floatOnly = dir / "float.vdb";
  writeFile(floatOnly, {levelSet()}, vio::COMPRESS_BLOSC | kMask, true);
  EXPECT_THAT(errorOf([&] { VdbLeafReader(floatOnly, "", {kFccTreeTypeName}); }),
              StartsWith(floatOnly + ": holds no grid of type Tree_vec4s_5_4_3 (grids: \"levelset\" (Tree_float_5_4_3, half))"));

  const std::string text = dir / "notes.vdb";
  std::ofstream(text) << "these are not voxels\n";
  EXPECT_THAT(errorOf([&] { VdbLeafReader(text, "", {}); }), StartsWith(text + ": not an OpenVDB file"));
  const std::string empty = dir / "empty.vdb";
  std::ofstream{empty};
  EXPECT_THAT(errorOf([&] { VdbLeafReader(empty, "", {}); }), StartsWith(empty + ": not an OpenVDB file"));
  EXPECT_THAT(errorOf([&] { VdbLeafReader(dir / "absent.vdb", "", {}); }), StartsWith(dir / "absent.vdb" + ": cannot open"));
  // Cut short inside the second grid: its descriptor is whole, its end past the file's.
  const std::string whole = fileBytes(path);
  const std::string cut = dir / "cut.vdb";
  writeBytes(cut, whole.substr(0, whole.size() - 10));
  EXPECT_THAT(errorOf([&] { VdbLeafReader(cut, "crafted4", {}); }),
              StartsWith(cut + ": truncated: grid \"crafted4\" ends at byte " + std::to_string(whole.size()) +
                         ", but the file has " + std::to_string(whole.size() - 10) + " bytes"));

  // The file format version, right after the magic number.
  for (const uint32_t version : {221u, 225u}) {
    std::string bytes = fileBytes(path);
    std::memcpy(bytes.data() + 8, &version, 4);
    const std::string other = dir / ("v" + std::to_string(version) + ".vdb");
    writeBytes(other, bytes);
    EXPECT_THAT(errorOf([&] { VdbLeafReader(other, "", {}); }),
                StartsWith(other + ": OpenVDB file format version " + std::to_string(version) +
                           " is not supported (valid: 222 to 224"));
  }

  // A grid written as an instance of another (sharing its tree).
  const std::string instanced = dir / "instanced.vdb";
  auto parent = levelSet();
  auto instance = parent->copy();  // shares the tree
  instance->setName("instance");
  writeFile(instanced, {parent, instance}, vio::COMPRESS_BLOSC | kMask, false);
  EXPECT_THAT(errorOf([&] { VdbLeafReader(instanced, "instance", {}); }),
              StartsWith(instanced + ": grid \"instance\" is an instance of grid \"levelset\""));
  EXPECT_EQ(VdbLeafReader(instanced, "levelset", {}).gridName(), "levelset");

  EXPECT_THROW(VdbLeafReader(path, "", {"Tree_int32_5_4_3"}), ValueError);
}

// ---------------------------------------------------------------------------------------------------------
// Found by fuzz_vdb_leaf_reader (docs/RELIABILITY.md): OpenVDB's readTopology trusts sizes, origins and masks
// (a raw block larger than the node's buffer, a compressed size it allocates, a root child at an origin
// already taken, leaked, or at one no tree has); its MetaMap throws its own exceptions. Each is now an
// InputError naming the file before OpenVDB reads anything.

// Where the topology of a float grid with background `bg` and `children` root children (no root tiles)
// starts in `bytes`: the buffer count 1, the background, 0 tiles, then the child count.
size_t topologyAt(const std::string& bytes, float bg, uint32_t children) {
  std::string head(16, '\0');
  const int32_t one = 1;
  std::memcpy(&head[0], &one, 4);
  std::memcpy(&head[4], &bg, 4);
  std::memcpy(&head[12], &children, 4);
  const size_t at = bytes.find(head);
  EXPECT_NE(at, std::string::npos);
  EXPECT_EQ(bytes.find(head, at + 1), std::string::npos);
  return at;
}

TEST(VdbLeafReader, RefusesTopologyOpenVdbWouldTrust) {
  TempDir dir;
  const std::string path = dir / "two_children.vdb";
  const float bg = 2.75f;
  auto grid = openvdb::FloatGrid::create(bg);
  grid->setName("g");
  grid->tree().setValue(Coord(1, 2, 3), 1.0f);
  grid->tree().setValue(Coord(4096 + 1, 2, 3), 1.0f);
  // Zip without the active mask: the 32^3 nodes' tile values, all 32768 of them, are zip data.
  writeFile(path, {grid}, vio::COMPRESS_ZIP, false);
  const std::string original = fileBytes(path);
  const size_t topo = topologyAt(original, bg, 2);
  const size_t child0 = topo + 16;                   // origin of the first root child
  const size_t masks0 = child0 + 12;                 // its child mask, then its value mask (4096 bytes each)
  const size_t values0 = masks0 + 2 * 4096;          // its tile values: metadata byte, then (zip) the size
  ASSERT_EQ(original[values0], char(vio::NO_MASK_AND_ALL_VALS));
  using testing::HasSubstr;
  auto damaged = [&](const std::function<void(std::string&)>& damage) {
    std::string bytes = original;
    damage(bytes);
    const std::string out = dir / "damaged.vdb";
    writeBytes(out, bytes);
    return errorOf([&] { VdbLeafReader(out, "g", {}); });
  };
  auto put = [](std::string& bytes, size_t at, auto value) { std::memcpy(&bytes[at], &value, sizeof value); };

  // A raw block ("size" -N) larger than the node's values: OpenVDB copied it into the node's buffer.
  EXPECT_THAT(damaged([&](std::string& b) { put(b, values0 + 1, int64_t(-(1 << 20))); }),
              HasSubstr("the 32^3 node at (0, 0, 0): its tile values: raw values of 1048576 bytes"));
  // A compressed size of 2^40: OpenVDB allocated it.
  EXPECT_THAT(damaged([&](std::string& b) { put(b, values0 + 1, int64_t(1) << 40); }),
              HasSubstr("its tile values: zip data of 1099511627776 bytes"));
  // Zip data that does not inflate: OpenVDB threw after allocating the node (leaked).
  EXPECT_THAT(damaged([&](std::string& b) {
                int64_t size;
                std::memcpy(&size, &b[values0 + 1], 8);
                ASSERT_GT(size, 2);
                b[values0 + 1 + 8 + 2] ^= 0x55;
              }),
              HasSubstr("its tile values: its zip data does not inflate"));
  // Both root children at one origin: OpenVDB kept the second, leaking the first.
  EXPECT_THAT(damaged([&](std::string& b) {
                const size_t child1 = b.find(std::string("\x00\x10\0\0\0\0\0\0\0\0\0\0", 12), values0);  // (4096, 0, 0)
                ASSERT_NE(child1, std::string::npos);
                put(b, child1, int32_t(0));
              }),
              HasSubstr("its root holds two nodes at (0, 0, 0)"));
  EXPECT_THAT(damaged([&](std::string& b) { put(b, child0, int32_t(8)); }),
              HasSubstr("a root child at (8, 0, 0) is not at a multiple of 4096"));
  // A bit on in both masks: the child pointer would be read as an active tile's value.
  EXPECT_THAT(damaged([&](std::string& b) { b[masks0 + 4096] = b[masks0]; }),
              HasSubstr("the 32^3 node at (0, 0, 0): a child is also an active tile"));
}

TEST(VdbLeafReader, MetadataOpenVdbRefusesIsAnInputError) {
  TempDir dir;
  const std::string path = dir / "meta.vdb";
  auto grid = levelSet();
  grid->insertMeta("aa", openvdb::StringMetadata("text"));
  grid->insertMeta("ab", openvdb::FloatMetadata(1.0f));
  writeFile(path, {grid}, vio::COMPRESS_BLOSC | kMask, false);
  std::string bytes = fileBytes(path);
  const size_t ab = bytes.find(std::string("\x02\x00\x00\x00" "ab", 6));
  ASSERT_NE(ab, std::string::npos);
  bytes[ab + 5] = 'a';  // "aa" twice, a string and a float: OpenVDB's MetaMap threw its TypeError
  writeBytes(path, bytes);
  EXPECT_THAT(errorOf([&] { VdbLeafReader(path, "levelset", {}); }),
              testing::HasSubstr(": metadata \"aa\" (float) is refused: "));
}

// The grid's metadata says "is_saved_as_half_float" too; OpenVDB read the topology by it, the walk of the
// topology by the descriptor ("_HalfFloat"). The descriptor decides: the file reads as written.
TEST(VdbLeafReader, HalfFlagInMetadataDoesNotOverrideTheDescriptor) {
  TempDir dir;
  const std::string path = dir / "half.vdb";
  writeFile(path, {craftedGrid<openvdb::FloatGrid>("crafted", 2.5f, /*compact=*/true)}, vio::COMPRESS_ZIP, true);
  std::string bytes = fileBytes(path);
  const std::string flag = std::string("is_saved_as_half_float") + std::string("\x04\0\0\0bool\x01\0\0\0\x01", 13);
  const size_t at = bytes.find(flag);
  ASSERT_NE(at, std::string::npos);
  bytes[at + flag.size() - 1] = 0;  // the metadata now says full floats
  const std::string patched = dir / "patched.vdb";
  writeBytes(patched, bytes);
  const VdbLeafReader original(path, "crafted", {}), reader(patched, "crafted", {});
  EXPECT_TRUE(reader.storedAsHalf());
  ASSERT_EQ(reader.leafCount(), original.leafCount());
  float a[512], b[512];
  for (size_t i = 0; i < reader.leafCount(); ++i) {
    original.readLeaf(i, a);
    reader.readLeaf(i, b);
    EXPECT_EQ(0, std::memcmp(a, b, sizeof a)) << "leaf " << i;
  }
}

// The inputs fuzz_vdb_leaf_reader found, kept in its corpus: each opens or is refused with InputError.
TEST(VdbLeafReader, FuzzRegressionInputsAreRefused) {
  const std::filesystem::path corpus = std::filesystem::path(FCC_SOURCE_DIR) / "tests/fuzz/corpus/vdb_leaf_reader";
  int seen = 0;
  for (const auto& entry : std::filesystem::directory_iterator(corpus)) {
    if (entry.path().filename().string().rfind("regress_", 0) != 0) continue;
    ++seen;
    SCOPED_TRACE(entry.path().string());
    Outcome o;
    for (const auto& g : VdbLeafReader::listGrids(entry.path().string())) openAndReadAll(entry.path().string(), g.name, o);
    EXPECT_GT(o.refused, 0);
  }
  EXPECT_GE(seen, 3);
}

// ---------------------------------------------------------------------------------------------------------
// Open time of a large file (run by hand: --gtest_also_run_disabled_tests). The file is made once in
// /tmp: a level-set sphere of radius 1500 voxels, half width 3 (about a million leaves).

long peakRssMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024;
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Drops the file's pages from the page cache (this file only), for a cold open.
void evictFromPageCache(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  ASSERT_GE(fd, 0);
  ::fdatasync(fd);
  ::posix_fadvise(fd, 0, 0, POSIX_FADV_DONTNEED);
  ::close(fd);
}

TEST(VdbLeafReader, DISABLED_OpenTimeOfAMillionLeaves) {
  const std::string path = "/tmp/fcc_leaf_reader_sphere1500.vdb";
  if (!std::filesystem::exists(path)) {
    const auto t0 = std::chrono::steady_clock::now();
    auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1500.0f, openvdb::Vec3f(0.0f), 1.0f, 3.0f);
    grid->setName("sphere");
    writeFile(path, {grid}, vio::COMPRESS_BLOSC | kMask, false);
    std::printf("made %s in %.1f s\n", path.c_str(), secondsSince(t0));
  }
  const double mb = double(std::filesystem::file_size(path)) / 1e6;
  for (const bool cold : {true, false}) {
    if (cold) evictFromPageCache(path);
    const auto t0 = std::chrono::steady_clock::now();
    const VdbLeafReader reader(path, "", {});
    const double open = secondsSince(t0);
    std::printf("%s open (%s): %zu leaves, %.0f MB: %.2f s; peak RSS %ld MiB\n", cold ? "cold" : "warm", path.c_str(),
                reader.leafCount(), mb, open, peakRssMiB());
    if (!cold) {
      std::vector<float> values(512);
      const auto t1 = std::chrono::steady_clock::now();
      for (size_t i = 0; i < reader.leafCount(); ++i) reader.readLeaf(i, values.data());
      const double read = secondsSince(t1);
      std::printf("every leaf read serially: %.2f s (%.2f us a leaf)\n", read, 1e6 * read / double(reader.leafCount()));
    }
  }
  // For comparison: OpenVDB's own topology-only open (delayed loading: maps the file).
  evictFromPageCache(path);
  const auto t0 = std::chrono::steady_clock::now();
  vio::File file(path);
  file.setCopyMaxBytes(0);
  file.open(/*delayLoad=*/true);
  const auto grid = file.readGrid("sphere");
  std::printf("OpenVDB delayed-load open + readGrid (cold): %.2f s; peak RSS %ld MiB\n", secondsSince(t0), peakRssMiB());
}

}  // namespace
}  // namespace fcc::io
