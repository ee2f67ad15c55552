// Dialect.h — the macro block that lets one source of mathematics compile as C++17, OpenCL C 1.2 and
// GLSL 4.50 (in the spirit of NanoVDB's PNanoVDB.h). Every shared math header (FccSpline.h, the
// reconstructions in sparse/recon/) includes it first.
//
// The including file picks the dialect: C++ is detected by __cplusplus (include <glm/glm.hpp> and <cmath>
// first), OpenCL C by __OPENCL_VERSION__, GLSL by `#define FCC_GLSL 1` before the include. Below this
// block the headers use no pointers and no dialect-only syntax: what differs is spelled by these macros.
// C++ puts the shared functions in namespace fcc::spline (FCC_NAMESPACE_BEGIN/END; empty elsewhere).
#ifndef FCC_DIALECT_H
#define FCC_DIALECT_H

#if defined(__cplusplus)
#define FCC_CPP 1
#define FCC_FUNC inline
#define FCC_VEC3 glm::vec3
#define FCC_IVEC3 glm::ivec3
#define FCC_VEC2 glm::vec2
#define FCC_VEC4 glm::vec4
#define FCC_MAKE_VEC3(x, y, z) glm::vec3(x, y, z)
#define FCC_MAKE_IVEC3(x, y, z) glm::ivec3(x, y, z)
#define FCC_MAKE_VEC2(x, y) glm::vec2(x, y)
#define FCC_MAKE_VEC4(x, y, z, w) glm::vec4(x, y, z, w)
#define FCC_FLOOR3(v) glm::floor(v)
#define FCC_ABS(x) std::abs(x)
#define FCC_IVEC3_FROM_VEC3(v) glm::ivec3(v)
#define FCC_VEC3_FROM_IVEC3(v) glm::vec3(v)
#define FCC_CONST_INT_ARRAY(name, n) static constexpr int name[n] =
#define FCC_ARRAY_OPEN(T, n) {
#define FCC_ARRAY_CLOSE }
#define FCC_STRUCT_BEGIN(name) struct name {
#define FCC_STRUCT_END(name) };
#define FCC_FLOAT(x) static_cast<float>(x)
#define FCC_INT(x) static_cast<int>(x)
#define FCC_NAMESPACE_BEGIN \
  namespace fcc {         \
  namespace spline {      \
  using glm::max;         \
  using glm::min;         \
  using std::ceil;        \
  using std::floor;       \
  using std::sqrt;
#define FCC_NAMESPACE_END \
  }                       \
  }
#elif defined(__OPENCL_VERSION__)
#define FCC_OPENCL 1
#define FCC_FUNC
#define FCC_VEC3 float3
#define FCC_IVEC3 int3
#define FCC_VEC2 float2
#define FCC_VEC4 float4
#define FCC_MAKE_VEC3(x, y, z) ((float3)((x), (y), (z)))
#define FCC_MAKE_IVEC3(x, y, z) ((int3)((x), (y), (z)))
#define FCC_MAKE_VEC2(x, y) ((float2)((x), (y)))
#define FCC_MAKE_VEC4(x, y, z, w) ((float4)((x), (y), (z), (w)))
#define FCC_FLOOR3(v) floor(v)
#define FCC_ABS(x) fabs(x)
#define FCC_IVEC3_FROM_VEC3(v) convert_int3(v)
#define FCC_VEC3_FROM_IVEC3(v) convert_float3(v)
#define FCC_CONST_INT_ARRAY(name, n) __constant int name[n] =
#define FCC_ARRAY_OPEN(T, n) {
#define FCC_ARRAY_CLOSE }
#define FCC_STRUCT_BEGIN(name) typedef struct name {
#define FCC_STRUCT_END(name) } name;
#define FCC_NAMESPACE_BEGIN
#define FCC_NAMESPACE_END
#define FCC_FLOAT(x) ((float)(x))
#define FCC_INT(x) ((int)(x))
#elif defined(FCC_GLSL)
#define FCC_FUNC
#define FCC_VEC3 vec3
#define FCC_IVEC3 ivec3
#define FCC_VEC2 vec2
#define FCC_VEC4 vec4
#define FCC_MAKE_VEC3(x, y, z) vec3(x, y, z)
#define FCC_MAKE_IVEC3(x, y, z) ivec3(x, y, z)
#define FCC_MAKE_VEC2(x, y) vec2(x, y)
#define FCC_MAKE_VEC4(x, y, z, w) vec4(x, y, z, w)
#define FCC_FLOOR3(v) floor(v)
#define FCC_ABS(x) abs(x)
#define FCC_IVEC3_FROM_VEC3(v) ivec3(v)
#define FCC_VEC3_FROM_IVEC3(v) vec3(v)
#define FCC_CONST_INT_ARRAY(name, n) const int name[n] =
#define FCC_ARRAY_OPEN(T, n) T[n](
#define FCC_ARRAY_CLOSE )
#define FCC_STRUCT_BEGIN(name) struct name {
#define FCC_STRUCT_END(name) };
#define FCC_NAMESPACE_BEGIN
#define FCC_NAMESPACE_END
#define FCC_FLOAT(x) float(x)
#define FCC_INT(x) int(x)
#else
#error "Dialect.h: unknown dialect (C++, OpenCL C, or define FCC_GLSL for GLSL)"
#endif

#endif  // FCC_DIALECT_H
