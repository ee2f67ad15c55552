// fccvdb info FILE.vdb: what an FCC .vdb holds.
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "Command.h"
#include "JsonText.h"
#include "io/VdbFile.h"
#include "sparse/BoundsHierarchy.h"
#include "sparse/Error.h"
#include "sparse/FccGrid.h"

namespace fcc::cli {
namespace {

// What the bounds hierarchy says, for an isovalue or none.
struct BoundsSummary {
  bool present = false;
  BoundsHierarchy::Counts total, kept;
  std::optional<float> iso;
};

BoundsSummary summarizeBounds(const BoundsGrid::Ptr& bounds, std::optional<float> iso) {
  BoundsSummary b;
  b.iso = iso;
  if (!bounds) return b;
  b.present = true;
  const BoundsHierarchy hierarchy(*bounds);
  b.total = hierarchy.total();
  if (iso) b.kept = hierarchy.kept(*iso);
  return b;
}

std::string boundsJson(const BoundsSummary& b) {
  if (!b.present) return "null";
  char buf[512];
  std::snprintf(buf, sizeof buf, "{\"bricks\": %llu, \"nodes1\": %llu, \"nodes2\": %llu",
                (unsigned long long)b.total.bricks, (unsigned long long)b.total.nodes1, (unsigned long long)b.total.nodes2);
  std::string out = buf;
  if (b.iso) {
    std::snprintf(buf, sizeof buf, ", \"iso\": %s, \"bricks_kept\": %llu, \"nodes1_kept\": %llu, \"nodes2_kept\": %llu",
                  jsonNumber(*b.iso).c_str(), (unsigned long long)b.kept.bricks, (unsigned long long)b.kept.nodes1,
                  (unsigned long long)b.kept.nodes2);
    out += buf;
  }
  return out + "}";
}

double percent(uint64_t part, uint64_t whole) { return whole ? 100.0 * double(part) / double(whole) : 0.0; }

struct Summary {
  std::string name, lattice, values, gridClass;
  openvdb::CoordBBox siteBox;  // in the lattice's index space
  uint64_t samples = 0, bricks = 0, bytes = 0, tiles = 0;
  double min = 0, max = 0;     // range of the stored values
  openvdb::Vec3d voxelSize;
  std::vector<std::pair<std::string, std::string>> metadata;
};

Summary summarize(const FccGrid& grid) {
  Summary s;
  s.name = grid.getName();
  s.lattice = "fcc";
  s.values = storesSamples(grid) ? kValuesSamples : kValuesCoefficients;
  s.gridClass = openvdb::GridBase::gridClassToString(grid.getGridClass());
  const openvdb::CoordBBox packed = grid.evalActiveVoxelBoundingBox();
  s.siteBox = openvdb::CoordBBox(openvdb::Coord(packed.min().asVec3i() * 2), openvdb::Coord(packed.max().asVec3i() * 2 + openvdb::Vec3i(1)));
  s.samples = grid.activeVoxelCount() * 4;
  s.bricks = grid.tree().leafCount();
  s.tiles = grid.tree().activeTileCount();
  // Decoded size of the active data: a brick is a full 8^3 block of Vec4f, a tile one value.
  s.bytes = s.bricks * FccTree::LeafNodeType::SIZE * sizeof(openvdb::Vec4f) + s.tiles * sizeof(openvdb::Vec4f);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (auto it = grid.cbeginValueOn(); it; ++it)
    for (int c = 0; c < 4; ++c) lo = std::min(lo, double((*it)[c])), hi = std::max(hi, double((*it)[c]));
  s.min = s.samples ? lo : grid.background()[0];
  s.max = s.samples ? hi : grid.background()[0];
  s.voxelSize = grid.voxelSize();
  for (auto it = grid.beginMeta(); it != grid.endMeta(); ++it) s.metadata.emplace_back(it->first, it->second->str());
  return s;
}

}  // namespace

Command addInfoCommand(CLI::App& parent) {
  struct Args {
    std::string file, grid;
    bool json = false;
    float iso = 0.0f;
  };
  auto args = std::make_shared<Args>();
  CLI::App* app = parent.add_subcommand("info", "Describe the FCC grids of a .vdb file");
  app->add_option("FILE", args->file, "FCC .vdb file")->required();
  app->add_option("--grid", args->grid, "The FCC grid to describe (default: the first)");
  auto* isoOption = app->add_option("--iso", args->iso, "Isovalue: how many bricks and internal nodes of the bounds hierarchy it leaves active");
  app->add_flag("--json", args->json, "One JSON object (keys: file, grid, lattice, values, dims, samples, bricks, bytes, min, max, metadata, bounds: {bricks, nodes1, nodes2[, iso, bricks_kept, nodes1_kept, nodes2_kept]} or null)");
  return {app, [args, isoOption]() {
            std::optional<float> iso;
            if (isoOption->count() > 0) {
              if (!std::isfinite(args->iso)) throw ValueError("--iso must be a finite number, got " + isoOption->as<std::string>());
              iso = args->iso;
            }
            const io::FccWithBounds file = io::readFccGridWithBounds(args->file, args->grid);
            const FccGrid::Ptr grid = file.grid;
            const Summary s = summarize(*grid);
            const BoundsSummary b = summarizeBounds(file.bounds, iso);
            const openvdb::Coord dims = s.siteBox.dim();
            if (args->json) {
              std::string meta;
              for (const auto& [k, v] : s.metadata) meta += (meta.empty() ? "" : ", ") + jsonString(k) + ": " + jsonString(v);
              std::printf("{\"file\": %s, \"grid\": %s, \"lattice\": %s, \"values\": %s, \"class\": %s, "
                          "\"dims\": [%d, %d, %d], \"samples\": %llu, \"bricks\": %llu, \"tiles\": %llu, "
                          "\"bytes\": %llu, \"min\": %s, \"max\": %s, \"voxel_size\": [%s, %s, %s], \"metadata\": {%s}, "
                          "\"bounds\": %s}\n",
                          jsonString(args->file).c_str(), jsonString(s.name).c_str(), jsonString(s.lattice).c_str(),
                          jsonString(s.values).c_str(), jsonString(s.gridClass).c_str(), dims.x(), dims.y(), dims.z(),
                          (unsigned long long)s.samples, (unsigned long long)s.bricks, (unsigned long long)s.tiles,
                          (unsigned long long)s.bytes, jsonNumber(s.min).c_str(), jsonNumber(s.max).c_str(),
                          jsonNumber(s.voxelSize.x()).c_str(), jsonNumber(s.voxelSize.y()).c_str(),
                          jsonNumber(s.voxelSize.z()).c_str(), meta.c_str(), boundsJson(b).c_str());
              return 0;
            }
            std::printf("file:      %s\n", args->file.c_str());
            std::printf("grid:      %s (%s, %s)\n", s.name.c_str(), s.lattice.c_str(), s.gridClass.c_str());
            std::printf("values:    %s\n", s.values.c_str());
            std::printf("dims:      %d x %d x %d lattice points (FCC sites are those with an even coordinate sum)\n",
                        dims.x(), dims.y(), dims.z());
            std::printf("voxel:     %g x %g x %g world units\n", s.voxelSize.x(), s.voxelSize.y(), s.voxelSize.z());
            std::printf("samples:   %llu active\n", (unsigned long long)s.samples);
            std::printf("bricks:    %llu (8^3 packed voxels each), %llu active tiles\n", (unsigned long long)s.bricks,
                        (unsigned long long)s.tiles);
            std::printf("bytes:     %llu decoded\n", (unsigned long long)s.bytes);
            std::printf("range:     %.9g .. %.9g (stored values)\n", s.min, s.max);
            if (!b.present) {
              std::printf("bounds:    none (written before bounds existed; convert again to add them)\n");
            } else {
              std::printf("bounds:    %llu bricks where the spline varies, in %llu level-1 and %llu level-2 nodes\n",
                          (unsigned long long)b.total.bricks, (unsigned long long)b.total.nodes1,
                          (unsigned long long)b.total.nodes2);
              if (b.iso)
                std::printf("iso %.9g: keeps %llu bricks (%.1f%%), %llu level-1 nodes (%.1f%%), %llu level-2 nodes (%.1f%%)\n",
                            double(*b.iso), (unsigned long long)b.kept.bricks, percent(b.kept.bricks, b.total.bricks),
                            (unsigned long long)b.kept.nodes1, percent(b.kept.nodes1, b.total.nodes1),
                            (unsigned long long)b.kept.nodes2, percent(b.kept.nodes2, b.total.nodes2));
            }
            for (const auto& [k, v] : s.metadata) std::printf("meta:      %s = %s\n", k.c_str(), v.c_str());
            return 0;
          }};
}

}  // namespace fcc::cli
