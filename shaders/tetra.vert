#version 450 core
// Projected tetrahedra (viewer/ProjectedTetrahedra.h): vertices 12 i .. 12 i + 11 of one draw are
// tetrahedron order[i]'s four faces (no vertex buffer; as fast as an instance a tetrahedron on the H100,
// docs/BENCHMARKS.md, session 30). A face no ray enters through (the eye clearly on the inner side of
// its plane) is dropped here, before rasterization, where tetra.frag would discard every fragment of
// it: about half of all faces. Each vertex goes from index space to the pinhole camera of
// raycast.comp: a point at eye + a F + b R + c U (F unit; R, U scaled by the half field of view) is on
// the ray of ndc (b / a, -c / a), and window row y is the raycaster's pixel row y (row 0 at the top of
// the image), so both renderers cast the same rays.

struct Tetrahedron {
  vec4 vertex[4];  // index space; w: the value there (unused here)
  vec4 plane[4];   // face i (opposite vertex i): outward unit normal, w = its offset (n . x on the face)
  vec4 field;      // the linear field: value = dot(field.xyz, x) + field.w
};
layout(std430, binding = 0) readonly buffer Tetrahedra { Tetrahedron tetrahedra[]; };
layout(std430, binding = 1) readonly buffer Order { uint order[]; };  // back to front

uniform mat4 uWorldFromIndex;
uniform vec3 uEyeIndex;  // the eye in index space (the host's, as its sort uses it)
uniform int uCullFaces;  // 0: every face rasterized, tetra.frag's test alone decides (the tests' reference)
uniform vec3 uEye;      // world
uniform vec3 uForward;  // world, unit
uniform vec3 uRight;    // world, scaled by tan(fov/2) * aspect
uniform vec3 uUp;       // world, scaled by tan(fov/2)

flat out uint vTetrahedron;
flat out int vFace;

// The three vertices of face f (the one opposite vertex f).
const int kFaceVertices[12] = int[12](1, 2, 3, 0, 3, 2, 0, 1, 3, 0, 2, 1);

// Whether no ray from the eye o enters tetrahedron t through face f, with a margin: tetra.frag takes a
// face's fragment where the ray's direction d has dot(n, d) < 0 (the eye outside the tetrahedron); a
// ray that meets the face's plane in front of the eye has dot(n, d) of the sign of w - dot(n, o), so
// with the eye on the inner side of the plane by more than the margin no fragment passes, whatever
// the rounding of d (relative 1e-6 against the margin's 1e-4 of the distance) and of dot(n, o) - w
// here (about 1e-7 of |o|: the margin has 1e-4 of it). With the eye inside the tetrahedron or near
// it, tetra.frag takes the faces the rays leave through: nothing is dropped.
bool noRayEnters(uint t, int f, vec3 o) {
  // BCC tetrahedra are less than 4 index units across.
  float margin = 1e-4 * (4.0 + distance(o, tetrahedra[t].vertex[0].xyz) + length(o));
  bool eyeClearlyOutside = false;
  for (int k = 0; k < 4; ++k)
    eyeClearlyOutside = eyeClearlyOutside || dot(tetrahedra[t].plane[k].xyz, o) - tetrahedra[t].plane[k].w > margin;
  return eyeClearlyOutside && dot(tetrahedra[t].plane[f].xyz, o) - tetrahedra[t].plane[f].w < -margin;
}

void main() {
  uint t = order[gl_VertexID / 12];
  int corner = gl_VertexID % 12;
  vTetrahedron = t;
  vFace = corner / 3;
  if (uCullFaces != 0 && noRayEnters(t, vFace, uEyeIndex)) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the clip volume, as the face's other two corners
    return;
  }
  vec3 xyz = tetrahedra[t].vertex[kFaceVertices[corner]].xyz;
  vec3 q = (uWorldFromIndex * vec4(xyz, 1.0)).xyz - uEye;
  float a = dot(q, uForward);
  float b = dot(q, uRight) / dot(uRight, uRight);
  float c = dot(q, uUp) / dot(uUp, uUp);
  // z = 0: no depth test, and w = a clips what lies behind the eye.
  gl_Position = vec4(b, -c, 0.0, a);
}
