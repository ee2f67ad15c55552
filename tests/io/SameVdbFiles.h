// Whether two .vdb files written by fccvdb hold the same FCC grid and bounds grid: the same bytes but
// for the random UUID in the header, and, for readable diagnostics, the same metadata, transforms,
// tiles, leaf masks and leaf values bit for bit.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "io/VdbFile.h"

namespace fcc::test {

// The file's bytes with its UUID (a random tag OpenVDB writes into every header) blanked.
inline std::string bytesWithoutUuid(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  openvdb::io::File file(path);
  file.open(false);
  const std::string uuid = file.getUniqueTag();
  file.close();
  const size_t at = bytes.find(uuid);
  if (!uuid.empty() && at != std::string::npos) bytes.replace(at, uuid.size(), std::string(uuid.size(), '-'));
  return bytes;
}

inline void expectSameMetadata(const openvdb::GridBase& a, const openvdb::GridBase& b) {
  EXPECT_EQ(a.metaCount(), b.metaCount());
  for (auto it = a.beginMeta(); it != a.endMeta(); ++it) {
    const openvdb::Metadata::ConstPtr other = b[it->first];
    ASSERT_TRUE(other) << "metadata " << it->first << " missing";
    EXPECT_EQ(it->second->typeName(), other->typeName()) << it->first;
    EXPECT_EQ(it->second->str(), other->str()) << it->first;
  }
}

template <class TreeT>
void expectSameTrees(const TreeT& a, const TreeT& b) {
  using Value = typename TreeT::ValueType;
  auto bits = [](const Value& v) { return std::string(reinterpret_cast<const char*>(&v), sizeof v); };
  EXPECT_EQ(bits(a.background()), bits(b.background()));
  // Tiles at every level: position, level, value bits, active state.
  auto tiles = [&](const TreeT& t) {
    std::vector<std::tuple<openvdb::Coord, int, std::string, bool>> out;
    auto it = t.cbeginValueAll();
    it.setMaxDepth(TreeT::ValueAllCIter::LEAF_DEPTH - 1);
    for (; it; ++it) out.emplace_back(it.getCoord(), it.getDepth(), bits(*it), it.isValueOn());
    return out;
  };
  EXPECT_TRUE(tiles(a) == tiles(b)) << "tiles differ";
  ASSERT_EQ(a.leafCount(), b.leafCount());
  int differ = 0;
  auto lb = b.cbeginLeaf();
  for (auto la = a.cbeginLeaf(); la; ++la, ++lb) {
    ASSERT_TRUE(lb);
    ASSERT_EQ(la->origin(), lb->origin());
    EXPECT_TRUE(la->valueMask() == lb->valueMask()) << "mask of the leaf at " << la->origin();
    if (std::memcmp(la->buffer().data(), lb->buffer().data(), sizeof(Value) * TreeT::LeafNodeType::SIZE) != 0 && ++differ < 5)
      ADD_FAILURE() << "values of the leaf at " << la->origin();
  }
  EXPECT_EQ(differ, 0);
}

// The FCC grid and bounds grid of two files, and their bytes.
inline void expectSameFccFiles(const std::string& expectedPath, const std::string& actualPath) {
  const io::FccWithBounds expected = io::readFccGridWithBounds(expectedPath), actual = io::readFccGridWithBounds(actualPath);
  ASSERT_TRUE(expected.bounds && actual.bounds);
  EXPECT_EQ(expected.grid->getName(), actual.grid->getName());
  EXPECT_EQ(expected.grid->saveFloatAsHalf(), actual.grid->saveFloatAsHalf());
  expectSameMetadata(*expected.grid, *actual.grid);
  EXPECT_TRUE(*expected.grid->transformPtr() == *actual.grid->transformPtr());
  expectSameTrees(expected.grid->tree(), actual.grid->tree());
  EXPECT_EQ(expected.bounds->getName(), actual.bounds->getName());
  expectSameMetadata(*expected.bounds, *actual.bounds);
  EXPECT_TRUE(*expected.bounds->transformPtr() == *actual.bounds->transformPtr());
  expectSameTrees(expected.bounds->tree(), actual.bounds->tree());
  EXPECT_TRUE(bytesWithoutUuid(expectedPath) == bytesWithoutUuid(actualPath)) << "the files' bytes differ";
}

}  // namespace fcc::test
