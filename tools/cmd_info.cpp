// fccvdb info FILE.vdb: what an FCC .vdb holds, from its topology, bounds grid and metadata alone (no
// brick is read); --check reads every brick and names the damaged ones.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>

#include "Command.h"
#include "JsonText.h"
#include "SourceFlags.h"
#include "RenderFlags.h"
#include <tbb/parallel_for.h>

#include "io/BrickStore.h"
#include "io/ConversionCache.h"
#include "io/DefaultIsovalue.h"
#include "io/VdbLeafReader.h"
#include "sparse/BoundsHierarchy.h"
#include "sparse/Error.h"
#include "sparse/FccGrid.h"
#include "sparse/SampleHistogram.h"
#include "RenderData.h"
#include "sparse/BccGrids.h"
#include "viewer/BccBrickSource.h"

namespace fcc::cli {
namespace {

// An FCC .vdb, or a .vdb whose grid list cannot be read: BrickStore then names what is wrong with it,
// as for any damaged FCC file (no conversion is tried).
bool holdsFccGridOrUnreadable(const std::string& path) {
  try {
    return io::holdsFccGrid(path);
  } catch (const Error&) {
    return true;
  }
}

// What the bounds hierarchy says, for an isovalue or none.
struct BoundsSummary {
  bool present = false;
  BoundsHierarchy::Counts total, kept;
  std::optional<float> iso;
};

BoundsSummary summarizeBounds(const BoundsGrid* bounds, std::optional<float> iso) {
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

// `"check": {"bricks_damaged": N, "damaged": [...]}` after --check, else nothing.
std::string checkJson(const std::optional<io::BrickStore::Damage>& damage) {
  if (!damage) return "";
  std::string list;
  for (const std::string& m : damage->messages) list += (list.empty() ? "" : ", ") + jsonString(m);
  return ", \"check\": {\"bricks_damaged\": " + std::to_string(damage->count) + ", \"damaged\": [" + list + "]}";
}

double percent(uint64_t part, uint64_t whole) { return whole ? 100.0 * double(part) / double(whole) : 0.0; }

// The percentiles info reports of the samples (from the histogram the file records).
constexpr double kPercentiles[] = {1, 5, 25, 50, 75, 95, 99};

// `{"1": v, "5": v, ...}`, or null without a histogram.
std::string percentilesJson(const std::optional<SampleSummary>& samples) {
  if (!samples || samples->histogram.empty()) return "null";
  std::string out;
  for (const double p : kPercentiles)
    out += (out.empty() ? "{" : ", ") + jsonString(std::to_string(int(p))) + ": " + jsonNumber(samplePercentile(*samples, p));
  return out + "}";
}

struct Summary {
  std::string name, lattice, values, gridClass;
  openvdb::CoordBBox siteBox;  // in the lattice's index space
  uint64_t samples = 0, bricks = 0, bytes = 0, tiles = 0;
  double min = 0, max = 0;                // the range the surface can take: the hull of the bounds
  bool rangeFromBounds = false;           // else the samples' range (metadata), a file without bounds
  std::optional<SampleSummary> data;      // the data: the samples' range and histogram (metadata)
  io::IsoChoice suggested;                // the isovalue render/view use without --iso
  openvdb::Vec3d voxelSize;
  std::vector<std::pair<std::string, std::string>> metadata;
};

Summary summarize(const io::BrickStore& store) {
  const FccGrid& grid = store.index();  // topology only: masks and tiles
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
  s.data = recordedSamples(grid);
  s.suggested = io::defaultIsovalue(store);
  s.rangeFromBounds = store.boundsFromFile();
  s.min = store.valueMin();  // the bounds' hull, or the recorded sample range without bounds
  s.max = store.valueMax();
  s.voxelSize = grid.voxelSize();
  for (auto it = grid.beginMeta(); it != grid.endMeta(); ++it) s.metadata.emplace_back(it->first, it->second->str());
  return s;
}

// One level of the pyramid (docs/FORMAT.md): level 0 is the grid itself.
struct LevelSummary {
  int level = 0;
  std::string grid;
  double spacing = 1.0;  // in level 0's lattice spacings
  uint64_t bricks = 0, boundsBricks = 0;
  openvdb::Vec3d voxelSize;
};

// Level 0 and the levels "<grid>.lod1", "<grid>.lod2", ... the file holds, each opened (guarded) for its
// topology and bounds; no brick is read.
std::vector<LevelSummary> summarizeLevels(const std::string& file, const io::BrickStore& level0) {
  std::vector<LevelSummary> levels;
  auto add = [&](const io::BrickStore& store, int k) {
    LevelSummary l;
    l.level = k;
    l.grid = store.index().getName();
    l.spacing = double(uint64_t(1) << k);
    l.bricks = store.index().tree().leafCount();
    l.boundsBricks = store.boundsFromFile() ? store.bounds().activeVoxelCount() : 0;
    l.voxelSize = store.index().voxelSize();
    levels.push_back(l);
  };
  add(level0, 0);
  std::vector<std::string> names;
  for (const io::VdbGridEntry& g : io::VdbLeafReader::listGrids(file)) names.push_back(g.name);
  for (int k = 1;; ++k) {
    const std::string name = lodGridName(level0.index().getName(), k);
    if (std::find(names.begin(), names.end(), name) == names.end()) break;
    add(io::BrickStore(file, name, /*forRendering=*/false), k);
  }
  return levels;
}

std::string levelsJson(const std::vector<LevelSummary>& levels) {
  std::string out;
  for (const LevelSummary& l : levels) {
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "{\"level\": %d, \"grid\": %s, \"spacing\": %s, \"bricks\": %llu, \"bounds_bricks\": %llu, "
                  "\"voxel_size\": [%s, %s, %s]}",
                  l.level, jsonString(l.grid).c_str(), jsonNumber(l.spacing).c_str(), (unsigned long long)l.bricks,
                  (unsigned long long)l.boundsBricks, jsonNumber(l.voxelSize.x()).c_str(),
                  jsonNumber(l.voxelSize.y()).c_str(), jsonNumber(l.voxelSize.z()).c_str());
    out += (out.empty() ? "" : ", ") + std::string(buf);
  }
  return "[" + out + "]";
}

// Reads every brick (in parallel); returns the damage found.
io::BrickStore::Damage checkBricks(const io::BrickStore& store) {
  std::vector<glm::ivec3> bricks;
  for (auto it = store.index().tree().cbeginLeaf(); it; ++it) {
    const openvdb::Coord b = it->origin() >> 3;
    bricks.emplace_back(b.x(), b.y(), b.z());
  }
  tbb::parallel_for(tbb::blocked_range<size_t>(0, bricks.size(), 64), [&](const tbb::blocked_range<size_t>& r) {
    io::BrickValues values;
    for (size_t i = r.begin(); i != r.end(); ++i) store.readBrick(bricks[i], values);
  });
  return store.damage();
}

}  // namespace

// A BCC dataset (viewer/BccBrickSource.h): what its two coset grids hold, from their topology and one
// pass over their leaves for the bricks' ranges (the ranges the renderer uses).
int describeBccDataset(const std::string& file, bool json) {
  const Lattice bcc = Lattice::Bcc;
  const render::BccBrickSource source(file, findReconstruction(kDefaultBccReconstruction));
  glm::dvec3 lo, hi;
  source.worldBounds(lo, hi);
  const glm::dvec3 spacing(glm::length(glm::dvec3(source.worldFromIndex()[0])), glm::length(glm::dvec3(source.worldFromIndex()[1])),
                           glm::length(glm::dvec3(source.worldFromIndex()[2])));
  if (json) {
    const auto triple = [](const glm::dvec3& v) { return "[" + jsonNumber(v.x) + ", " + jsonNumber(v.y) + ", " + jsonNumber(v.z) + "]"; };
    std::string names;
    for (const ReconstructionInfo& r : reconstructionInfos())
      if (r.lattice == bcc) names += (names.empty() ? "" : ", ") + jsonString(std::string(r.name));
    std::printf("{\"file\": %s, \"lattice\": \"bcc\", \"grids\": [%s, %s], \"bricks\": %llu, \"min\": %s, \"max\": %s, "
                "\"background\": %s, \"index_spacing\": %s, \"world_bounds\": {\"min\": %s, \"max\": %s}, "
                "\"reconstructions\": [%s]}\n",
                jsonString(file).c_str(), jsonString(kBccPrimaryGridName).c_str(), jsonString(kBccSecondaryGridName).c_str(),
                (unsigned long long)source.varyingBrickCount(), jsonNumber(source.valueMin()).c_str(),
                jsonNumber(source.valueMax()).c_str(), jsonNumber(source.background()).c_str(), triple(spacing).c_str(),
                triple(lo).c_str(), triple(hi).c_str(), names.c_str());
    return 0;
  }
  std::printf("file:          %s\n", file.c_str());
  std::printf("lattice:       bcc (grids %s and %s: the two cosets, docs/FORMAT.md)\n", kBccPrimaryGridName, kBccSecondaryGridName);
  std::printf("index spacing: %g x %g x %g world units (sites: index points with all coordinates even or all odd)\n",
              spacing.x, spacing.y, spacing.z);
  std::printf("bricks:        %llu of 16^3 index units where the data may vary\n", (unsigned long long)source.varyingBrickCount());
  std::printf("value range:   %.9g .. %.9g (the samples; every BCC scheme stays within them)\n", double(source.valueMin()),
              double(source.valueMax()));
  std::printf("background:    %g\n", double(source.background()));
  std::printf("world bounds:  (%g, %g, %g) .. (%g, %g, %g)\n", lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
  std::printf("render with:   --reconstruction %s (default %s)\n", reconstructionNames(&bcc).c_str(), kDefaultBccReconstruction);
  return 0;
}

Command addInfoCommand(CLI::App& parent) {
  struct Args {
    std::string file, grid;
    bool json = false, check = false, noCache = false;
    float iso = 0.0f;
    SourceFlags source;
  };
  auto args = std::make_shared<Args>();
  CLI::App* app = parent.add_subcommand("info", "Describe the FCC grids of a .vdb file (or a BCC dataset's cosets); any other "
                                                "input as render draws it: converted to FCC once and cached");
  app->add_option("FILE", args->file,
                  "FCC .vdb file, or anything convert takes (a Cartesian .vdb, NRRD, NIfTI, raw with --dims/--type): "
                  "converted as render converts it, into the same cache (--no-cache: a temporary file)")
      ->required();
  addRawFlags(*app, args->source);
  app->add_flag("--no-cache", args->noCache, "Convert a Cartesian FILE into a temporary file instead of the user cache");
  app->add_option("--grid", args->grid, "The FCC grid to describe (default: level 0, the first FCC grid that is not a pyramid level `NAME.lodK`)");
  auto* isoOption = app->add_option("--iso", args->iso, "Isovalue: how many bricks and internal nodes of the bounds hierarchy it leaves active");
  app->add_flag("--check", args->check, "Read every brick and name the damaged ones (exit 1 if any is)");
  app->add_flag("--json", args->json,
                "One JSON object (keys: file, converted (the FCC file drawn for a Cartesian FILE, or null), grid, lattice, values, class, dims (of the active box), samples, bricks, "
                "tiles, bytes, min, max (the range the surface can take), range_from, sample_min, sample_max (the "
                "data's range), percentiles ({\"1\": v, ... \"99\": v} or null), suggested_iso, suggested_iso_basis, "
                "voxel_size, world_bounds: {min: [x, y, z], max: [x, y, z]} (the active data's box in world space, "
                "what the default camera frames), metadata, bounds: {bricks, nodes1, nodes2[, iso, bricks_kept, "
                "nodes1_kept, nodes2_kept]} or null, levels: [{level, grid, spacing, bricks, bounds_bricks, voxel_size}] "
                "(the level-of-detail pyramid, level 0 first; one entry without a pyramid))");
  return {app, [args, isoOption]() {
            if (render::holdsBccGrids(args->file)) {
              if (args->check || isoOption->count() > 0 || !args->grid.empty())
                throw ValueError("--check, --iso and --grid describe FCC grids; " + args->file + " holds a BCC dataset");
              return describeBccDataset(args->file, args->json);
            }
            std::optional<float> iso;
            if (isoOption->count() > 0) {
              if (!std::isfinite(args->iso)) throw ValueError("--iso must be a finite number, got " + isoOption->as<std::string>());
              iso = args->iso;
            }
            // Not an FCC file: described as render would draw it (the conversion render makes and caches).
            std::unique_ptr<io::FccInput> converted;
            rawLayoutFromFlags(args->source, args->file);  // refuses raw flags for an input that is not raw
            if (std::filesystem::exists(args->file) && !holdsFccGridOrUnreadable(args->file))
              converted = openFccInput(args->file, args->source, args->grid, !args->noCache, /*quiet=*/false);
            const std::string fccPath = converted ? converted->path() : args->file;
            const io::BrickStore store(fccPath, converted ? std::string() : args->grid, /*forRendering=*/false);
            // As render says it: an isovalue no surface can take keeps no brick (stderr: JSON stays clean).
            if (iso) warnIfIsoOutside(*iso, store);
            const Summary s = summarize(store);
            const BoundsSummary b =
                summarizeBounds(store.boundsFromFile() ? &store.bounds() : nullptr, iso);
            std::optional<io::BrickStore::Damage> damage;
            if (args->check) damage = checkBricks(store);
            const std::vector<LevelSummary> levels = summarizeLevels(fccPath, store);
            const openvdb::Coord dims = s.siteBox.dim();
            if (args->json) {
              glm::dvec3 worldLo, worldHi;
              store.worldBounds(worldLo, worldHi);
              const auto triple = [](const glm::dvec3& v) {
                return "[" + jsonNumber(v.x) + ", " + jsonNumber(v.y) + ", " + jsonNumber(v.z) + "]";
              };
              const std::string worldBounds = "{\"min\": " + triple(worldLo) + ", \"max\": " + triple(worldHi) + "}";
              std::string meta;
              for (const auto& [k, v] : s.metadata) meta += (meta.empty() ? "" : ", ") + jsonString(k) + ": " + jsonString(v);
              std::printf("{\"file\": %s, \"converted\": %s, \"grid\": %s, \"lattice\": %s, \"values\": %s, \"class\": %s, "
                          "\"dims\": [%d, %d, %d], \"samples\": %llu, \"bricks\": %llu, \"tiles\": %llu, "
                          "\"bytes\": %llu, \"min\": %s, \"max\": %s, \"range_from\": %s, \"sample_min\": %s, "
                          "\"sample_max\": %s, \"percentiles\": %s, \"suggested_iso\": %s, \"suggested_iso_basis\": %s, "
                          "\"voxel_size\": [%s, %s, %s], \"world_bounds\": %s, \"metadata\": {%s}, \"bounds\": %s, \"levels\": %s%s}\n",
                          jsonString(args->file).c_str(), converted ? jsonString(fccPath).c_str() : "null", jsonString(s.name).c_str(), jsonString(s.lattice).c_str(),
                          jsonString(s.values).c_str(), jsonString(s.gridClass).c_str(), dims.x(), dims.y(), dims.z(),
                          (unsigned long long)s.samples, (unsigned long long)s.bricks, (unsigned long long)s.tiles,
                          (unsigned long long)s.bytes, jsonNumber(s.min).c_str(), jsonNumber(s.max).c_str(),
                          jsonString(s.rangeFromBounds ? "bounds" : "samples").c_str(),
                          s.data ? jsonNumber(s.data->min).c_str() : "null",
                          s.data ? jsonNumber(s.data->max).c_str() : "null", percentilesJson(s.data).c_str(),
                          jsonNumber(s.suggested.value).c_str(), jsonString(s.suggested.basis).c_str(),
                          jsonNumber(s.voxelSize.x()).c_str(),
                          jsonNumber(s.voxelSize.y()).c_str(), jsonNumber(s.voxelSize.z()).c_str(),
                          worldBounds.c_str(), meta.c_str(),
                          boundsJson(b).c_str(), levelsJson(levels).c_str(), checkJson(damage).c_str());
              return damage && damage->count > 0 ? 1 : 0;
            }
            std::printf("file:          %s\n", args->file.c_str());
            if (converted) std::printf("converted:     %s (the FCC file render and view draw for it)\n", fccPath.c_str());
            std::printf("grid:          %s (%s, %s)\n", s.name.c_str(), s.lattice.c_str(), s.gridClass.c_str());
            std::printf("values:        %s\n", s.values.c_str());
            // Not the input's size: inactive background is not stored, and the prefilter spreads the data by
            // one site (so up to a packed voxel) beyond the input's.
            std::printf("dims:          %d x %d x %d lattice points: the box of the active (stored) data, from (%d, %d, %d) "
                        "to (%d, %d, %d) (FCC sites are its points with an even coordinate sum)\n",
                        dims.x(), dims.y(), dims.z(), s.siteBox.min().x(), s.siteBox.min().y(), s.siteBox.min().z(),
                        s.siteBox.max().x(), s.siteBox.max().y(), s.siteBox.max().z());
            std::printf("voxel:         %g x %g x %g world units\n", s.voxelSize.x(), s.voxelSize.y(), s.voxelSize.z());
            std::printf("samples:       %llu stored values (4 per active packed voxel)\n", (unsigned long long)s.samples);
            std::printf("bricks:        %llu (8^3 packed voxels each), %llu active tiles\n", (unsigned long long)s.bricks,
                        (unsigned long long)s.tiles);
            std::printf("bytes:         %llu decoded\n", (unsigned long long)s.bytes);
            // Two ranges, named the same everywhere (the viewer's panel too): the data's and the surface's.
            if (s.data)
              std::printf("data range:    %.9g .. %.9g (the samples, before the prefilter; fcc_sample_min/max)\n",
                          s.data->min, s.data->max);
            if (s.rangeFromBounds)
              std::printf("surface range: %.9g .. %.9g (the values the spline takes, so the isovalues with a surface: "
                          "the hull of the bounds)\n",
                          s.min, s.max);
            else
              std::printf("surface range: %.9g .. %.9g (taken from the data range: the file has no bounds)\n", s.min, s.max);
            if (s.data && !s.data->histogram.empty()) {
              std::string line;
              for (const double p : kPercentiles) {
                char item[64];
                std::snprintf(item, sizeof item, "%s%g%%: %.6g", line.empty() ? "" : ", ", p, samplePercentile(*s.data, p));
                line += item;
              }
              const double background = percent(s.data->histogram[size_t(s.data->binOf(store.background()))],
                                                s.data->total());
              std::printf("percentiles:   %s (of the samples; %.1f%% of them lie in the background's bin, %g)\n",
                          line.c_str(), background, double(store.background()));
            } else {
              std::printf("percentiles:   none (the file records no histogram of its samples; convert it again)\n");
            }
            std::printf("suggested iso: %.6g (%s; render, view and bench render use it without --iso)\n",
                        double(s.suggested.value), s.suggested.basis.c_str());
            if (!b.present) {
              std::printf("bounds:        none (written before bounds existed; convert again to add them)\n");
            } else {
              std::printf("bounds:        %llu bricks where the spline varies, in %llu level-1 and %llu level-2 nodes\n",
                          (unsigned long long)b.total.bricks, (unsigned long long)b.total.nodes1,
                          (unsigned long long)b.total.nodes2);
              if (b.iso)
                std::printf("iso %.9g: keeps %llu bricks (%.1f%%), %llu level-1 nodes (%.1f%%), %llu level-2 nodes (%.1f%%)\n",
                            double(*b.iso), (unsigned long long)b.kept.bricks, percent(b.kept.bricks, b.total.bricks),
                            (unsigned long long)b.kept.nodes1, percent(b.kept.nodes1, b.total.nodes1),
                            (unsigned long long)b.kept.nodes2, percent(b.kept.nodes2, b.total.nodes2));
            }
            if (levels.size() == 1) {
              std::printf("levels:        1 (no level-of-detail pyramid; `fccvdb pyramid FILE` adds one)\n");
            } else {
              std::printf("levels:        %zu (the level-of-detail pyramid)\n", levels.size());
              for (const LevelSummary& l : levels)
                std::printf("  level %-2d     %s: spacing %g (voxel %g world units), %llu bricks, bounds: %llu bricks\n",
                            l.level, l.grid.c_str(), l.spacing, l.voxelSize.x(), (unsigned long long)l.bricks,
                            (unsigned long long)l.boundsBricks);
            }
            for (const auto& [k, v] : s.metadata) {
              if (k == meta::kSampleHistogram && s.data && !s.data->histogram.empty())  // a long list: --json has it whole
                std::printf("meta:          %s = (%zu counts over the data range; --json lists them)\n", k.c_str(),
                            s.data->histogram.size());
              else
                std::printf("meta:          %s = %s\n", k.c_str(), v.c_str());
            }
            if (damage) {
              std::printf("check:         %llu bricks read, %llu damaged\n", (unsigned long long)s.bricks,
                          (unsigned long long)damage->count);
              for (const std::string& m : damage->messages) std::printf("damaged:       %s\n", m.c_str());
              if (damage->count > 0) {
                std::fprintf(stderr, "fccvdb: %s: %llu damaged bricks (first: %s)\n", args->file.c_str(),
                             (unsigned long long)damage->count, damage->first.c_str());
                return 1;
              }
            }
            return 0;
          }};
}

}  // namespace fcc::cli
