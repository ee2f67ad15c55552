#version 450 core
// viewer/Presenter: one instance per rectangle of the window to draw the image into, as a triangle
// strip of four vertices. Rectangles are [x0, x1) x [y0, y1) in pixels with rows from the top, as
// the raycaster's images. Instance 0 may be united with the surface rectangle the raycasting passes
// leave in their results buffer (viewer/Raycaster.h, passResults()), so drawing needs no read-back.
// Everything is clipped to uClip. The rectangle is read as a uniform block, bound to the buffer's
// first bytes: OpenGL 4.5 need not offer storage blocks to vertex shaders.
#define FCC_MAX_PRESENT_RECTS 16

layout(std140, binding = 0) uniform PassResults {  // std140 packs these scalars as raycast.comp does
  uint requestCount;
  int surfaceMinX, surfaceMinY, surfaceMaxX, surfaceMaxY;  // last < first: no surface
};

uniform ivec4 uRects[FCC_MAX_PRESENT_RECTS];
uniform int uUniteSurface;  // 1: instance 0 also covers the surface rectangle of PassResults
uniform ivec4 uClip;
uniform ivec2 uSize;        // the image (and the framebuffer area drawn to) in pixels

bool isEmpty(ivec4 r) { return r.x >= r.z || r.y >= r.w; }

void main() {
  ivec4 r = uRects[gl_InstanceID];
  if (gl_InstanceID == 0 && uUniteSurface != 0 && surfaceMaxX >= surfaceMinX) {
    ivec4 s = ivec4(surfaceMinX, surfaceMinY, surfaceMaxX + 1, surfaceMaxY + 1);
    r = isEmpty(r) ? s : ivec4(min(r.xy, s.xy), max(r.zw, s.zw));
  }
  r = ivec4(max(r.xy, uClip.xy), min(r.zw, uClip.zw));
  if (isEmpty(r)) r = ivec4(0);  // no area: nothing rasterised
  ivec2 corner = ivec2((gl_VertexID & 1) != 0 ? r.z : r.x, (gl_VertexID & 2) != 0 ? r.w : r.y);
  // Pixel edges land on pixel edges: exactly the pixels inside are drawn.
  vec2 ndc = vec2(2.0 * float(corner.x) / float(uSize.x) - 1.0, 1.0 - 2.0 * float(corner.y) / float(uSize.y));
  gl_Position = vec4(ndc, 0.0, 1.0);
}
