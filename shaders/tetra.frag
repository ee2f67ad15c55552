#version 450 core
// Projected tetrahedra (viewer/ProjectedTetrahedra.h): a fragment of a tetrahedron's face integrates
// the pixel's ray through the tetrahedron if the face is a front face for that ray (the ray enters the
// tetrahedron there). A convex body's front faces tile its projection, and OpenGL's rasterization
// rules give a pixel whose centre lies on an edge two triangles share to exactly one of them, so each
// ray is counted once per tetrahedron, with no crack along the edges (deciding the entry face from the
// planes' t instead loses pixels near edges to rounding). Then: entry and exit from the four face
// planes, the linear field at both, and dvr.glsl's integration of that segment with the transfer
// table (the same sub-steps and compositing the raycaster's DVR uses). The output is the segment's
// premultiplied colour and opacity, blended back to front ("over": ONE, ONE_MINUS_SRC_ALPHA) in the
// order the host sorted the tetrahedra.
#define FCC_GLSL 1
#define FCC_MODE_DVR 1
#include "ReconCommon.h"

struct Tetrahedron {
  vec4 vertex[4];
  vec4 plane[4];
  vec4 field;
};
layout(std430, binding = 0) readonly buffer Tetrahedra { Tetrahedron tetrahedra[]; };

uniform ivec2 uResolution;
uniform vec3 uEye;
uniform vec3 uForward;
uniform vec3 uRight;
uniform vec3 uUp;
uniform mat4 uIndexFromWorld;
uniform mat3 uNormalFromIndex;  // dvr.glsl's shading: world gradient from index-space gradient
uniform vec3 uLightDir;         // dvr.glsl's shading: world, unit, towards the directional light

#include "dvr.glsl"

flat in uint vTetrahedron;
flat in int vFace;
layout(location = 0) out vec4 fragColor;

#if FCC_DVR_SHADING
vec3 gTetGradient;  // the linear field's gradient: constant in a tetrahedron
vec3 dvrGradient(ivec3 cell, vec3 xyz) { return gTetGradient; }
#endif

void main() {
  // The raycaster's ray through this pixel's centre (raycast.comp's main).
  vec2 pixel = gl_FragCoord.xy - 0.5;
  vec2 ndc = (pixel + 0.5) / vec2(uResolution) * 2.0 - 1.0;
  vec3 dirWorld = normalize(uForward + ndc.x * uRight - ndc.y * uUp);
  vec3 o = (uIndexFromWorld * vec4(uEye, 1.0)).xyz;
  vec3 d = mat3(uIndexFromWorld) * dirWorld;
  Tetrahedron tet = tetrahedra[vTetrahedron];
  // Only this face's fragments of rays that enter through it (d against its outward normal); with the
  // eye inside the tetrahedron, whose entering faces lie behind it (clipped), the face each ray leaves
  // through instead, from t = 0.
  bool eyeInside = true;
  for (int f = 0; f < 4; ++f) eyeInside = eyeInside && dot(tet.plane[f].xyz, o) <= tet.plane[f].w;
  float faceDen = dot(tet.plane[vFace].xyz, d);
  if (eyeInside ? !(faceDen > 0.0) : !(faceDen < 0.0)) discard;
  // Entering planes (d against the outward normal) raise tIn, leaving ones lower tOut.
  float tIn = 0.0, tOut = 1.0 / 0.0;
  for (int f = 0; f < 4; ++f) {
    vec3 n = tet.plane[f].xyz;
    float den = dot(n, d), t = (tet.plane[f].w - dot(n, o)) / den;
    if (den < 0.0) tIn = max(tIn, t);
    else if (den > 0.0) tOut = min(tOut, t);
  }
  if (!(tOut > tIn)) discard;
  float vIn = dot(tet.field.xyz, o + tIn * d) + tet.field.w;
  float vOut = dot(tet.field.xyz, o + tOut * d) + tet.field.w;
  DvrState st;
  st.color = vec3(0.0);
  st.transmittance = 1.0;
  st.depthHalf = 1.0 / 0.0;
#if FCC_DVR_SHADING
  gTetGradient = tet.field.xyz;
  dvrBeginRay(dirWorld);
  dvrBeginCell(ivec3(0), o, d);
#endif
  dvrSegment3(fcc_linear_as_bernstein3(vIn, vOut), tIn, tOut, st);
  fragColor = vec4(st.color, 1.0 - st.transmittance);
}
