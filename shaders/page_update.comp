#version 450 core
// Writes the page-table entries a pass's uploads changed (viewer/Raycaster.cpp): one invocation a
// (index, value) pair, so a pass writes a few kilobytes instead of the whole table (8 MiB for blobs
// 2048^3, written after every pass before).
layout(local_size_x = 64) in;

layout(std430, binding = 1) writeonly buffer PageTable { uint pageEntries[]; };
layout(std430, binding = 11) readonly buffer Changes { uvec2 changes[]; };  // (index, value)
uniform uint uCount;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) return;
  pageEntries[changes[i].x] = changes[i].y;
}
