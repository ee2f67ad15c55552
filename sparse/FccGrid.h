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
}  // namespace meta

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
