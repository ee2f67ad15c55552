// The FCC dataset as an OpenVDB grid: a sparse Vec4f tree over packed voxels (sparse/Lattice.h), whose
// transform maps the lattice's index space (the Cartesian embedding) to world space.
#pragma once

#include <openvdb/openvdb.h>

#include <string>

namespace fcc {

using FccTree = openvdb::tree::Tree4<openvdb::Vec4f, 5, 4, 3>::Type;
using FccGrid = openvdb::Grid<FccTree>;

// The type name OpenVDB (and NanoVDB's converter) use for this tree.
inline constexpr const char* kFccTreeTypeName = "Tree_vec4s_5_4_3";

// openvdb::initialize() plus registration of FccGrid and BoundsGrid (sparse/BrickBounds.h); safe to
// call more than once.
void initializeVdb();

// Metadata keys on an FCC grid.
namespace meta {
inline constexpr const char* kLattice = "lattice";             // "fcc"
inline constexpr const char* kValues = "fcc_values";           // "coefficients" or "samples"
inline constexpr const char* kSourceFile = "fcc_source_file";
inline constexpr const char* kSourceGrid = "fcc_source_grid";
inline constexpr const char* kMode = "fcc_mode";               // "subsample", "resample", "synth:<kind>"
inline constexpr const char* kSampleMin = "fcc_sample_min";    // range of the samples (before prefilter)
inline constexpr const char* kSampleMax = "fcc_sample_max";
// The level-of-detail pyramid (docs/FORMAT.md, io/FccPyramid.h). On level 0 (the full-resolution grid):
inline constexpr const char* kLodLevels = "fcc_lod_levels";    // int: levels in the file, level 0 included
// On level k >= 1 (grid `<level 0's name>.lod<k>`):
inline constexpr const char* kLodLevel = "fcc_lod_level";      // int: k
inline constexpr const char* kLodOf = "fcc_lod_of";            // string: level 0's grid name
inline constexpr const char* kLodSpacing = "fcc_lod_spacing";  // double: 2^k, level 0's lattice spacings
}  // namespace meta

// The grid name of pyramid level `level` (>= 1) of FCC grid `base`: "<base>.lod<level>".
inline std::string lodGridName(const std::string& base, int level) { return base + ".lod" + std::to_string(level); }

// True if `name` is a pyramid level's ("<anything>.lod<digits>"): readers that pick "the first FCC grid"
// skip these, so a file opens at level 0 whatever order its grids are in.
inline bool isLodGridName(const std::string& name) {
  const size_t dot = name.rfind(".lod");
  if (dot == std::string::npos || dot == 0 || dot + 4 == name.size()) return false;
  for (size_t i = dot + 4; i < name.size(); ++i)
    if (name[i] < '0' || name[i] > '9') return false;
  return true;
}

inline constexpr const char* kValuesCoefficients = "coefficients";
inline constexpr const char* kValuesSamples = "samples";

bool isFccGrid(const openvdb::GridBase& grid);

// What `convert` and `synth` record on the grid they write.
struct FccProvenance {
  bool coefficients = true;  // values are prefiltered coefficients (else raw samples)
  std::string sourceFile;
  std::string sourceGrid;
  std::string mode;
  float sampleMin = 0.0f, sampleMax = 0.0f;
  bool levelSet = false;
};
void setFccMetadata(FccGrid& grid, const FccProvenance& provenance);

// True if the grid stores raw samples (converted with --no-prefilter) rather than coefficients.
bool storesSamples(const openvdb::GridBase& grid);

}  // namespace fcc

// Half-float storage of Vec4 values: without these, setSaveFloatAsHalf silently keeps full floats for
// Vec4 grids (io::RealToHalf has no Vec4 specialisation in OpenVDB 10). Every translation unit that
// instantiates Vec4 grid I/O includes this header.
namespace openvdb {
OPENVDB_USE_VERSION_NAMESPACE
namespace OPENVDB_VERSION_NAME {
namespace io {
template <>
struct RealToHalf<Vec4s> {
  enum { isReal = true };
  using HalfT = Vec4H;
  static HalfT convert(const Vec4s& val) { return HalfT(val); }
};
template <>
struct RealToHalf<Vec4d> {
  enum { isReal = true };
  using HalfT = Vec4H;
  static HalfT convert(const Vec4d& val) { return HalfT(Vec4s(val)); }
};
}  // namespace io
}  // namespace OPENVDB_VERSION_NAME
}  // namespace openvdb
