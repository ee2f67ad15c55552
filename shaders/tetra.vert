#version 450 core
// Projected tetrahedra (viewer/ProjectedTetrahedra.h): instance i draws tetrahedron order[i] as its four
// faces (12 vertices, no vertex buffer). Each vertex goes from index space to the pinhole camera of
// raycast.comp: a point at eye + a F + b R + c U (F unit; R, U scaled by the half field of view) is on
// the ray of ndc (b / a, -c / a), and window row y is the raycaster's pixel row y (row 0 at the top of
// the image), so both renderers cast the same rays.

struct Tetrahedron {
  vec4 vertex[4];  // index space; w unused
  vec4 plane[4];   // face i (opposite vertex i): outward unit normal, w = its offset (n . x on the face)
  vec4 field;      // the linear field: value = dot(field.xyz, x) + field.w
};
layout(std430, binding = 0) readonly buffer Tetrahedra { Tetrahedron tetrahedra[]; };
layout(std430, binding = 1) readonly buffer Order { uint order[]; };  // back to front

uniform mat4 uWorldFromIndex;
uniform vec3 uEye;      // world
uniform vec3 uForward;  // world, unit
uniform vec3 uRight;    // world, scaled by tan(fov/2) * aspect
uniform vec3 uUp;       // world, scaled by tan(fov/2)

flat out uint vTetrahedron;
flat out int vFace;

// The three vertices of face f (the one opposite vertex f).
const int kFaceVertices[12] = int[12](1, 2, 3, 0, 3, 2, 0, 1, 3, 0, 2, 1);

void main() {
  uint t = order[gl_InstanceID];
  vTetrahedron = t;
  vFace = gl_VertexID / 3;
  vec3 xyz = tetrahedra[t].vertex[kFaceVertices[gl_VertexID]].xyz;
  vec3 q = (uWorldFromIndex * vec4(xyz, 1.0)).xyz - uEye;
  float a = dot(q, uForward);
  float b = dot(q, uRight) / dot(uRight, uRight);
  float c = dot(q, uUp) / dot(uUp, uUp);
  // z = 0: no depth test, and w = a clips what lies behind the eye.
  gl_Position = vec4(b, -c, 0.0, a);
}
