#version 450 core
// The brick-paged isosurface raycaster: one invocation per pixel, one pass per dispatch.
//
// Rays walk the bricks of the page table (skipping whole nodes and bricks whose bounds exclude the
// isovalue), then the unit cells of a resident brick (march_fcc.glsl or march_cc.glsl, by the
// reconstruction FCC_RECON: sparse/ReconDispatch.h's ids); in a piece whose Bernstein/BB-coefficients
// straddle the isovalue the first root of its polynomial along the ray is found exactly. A ray that reaches a brick not resident in the pool requests it (and a
// few bricks beyond it), saves where it stopped, and resumes there in the next pass, so a frame whose
// working set exceeds the pool completes in several passes. Headers are inlined by fcc_embed.
#define FCC_GLSL 1
// A measurement knob (docs/RENDERER.md), NVIDIA only: 1 writes the warp slot on its SM, the SM and the
// slots an SM has (GL_NV_shader_thread_group) as the colour (opacity 1) of each pixel whose ray ends in
// this pass (DVR; the isosurface where it hits), so the image's largest slot + 1 is the most warps an SM
// held at once (the occupancy the program's registers allow).
#ifndef FCC_WARP_PROBE
#define FCC_WARP_PROBE 0
#endif
#if FCC_WARP_PROBE
#extension GL_NV_shader_thread_group : require
#endif
// A measurement knob (docs/RENDERER.md), DVR's flat walk (FCC_DVR_FLAT) only: 1 writes, instead of
// light, each ray's SM clock cycles (GL_ARB_shader_clock) by phase, summed over its passes: R the
// rounds' finds (the cell walk to the next cell to integrate), G integrateCell's chord set-up, gather
// and piece in Taylor form, B the rest of integrateCell (the sub-step rule and the sub-steps, or a
// whole integrateCellPieces), and the EXR's Z everything else (the brick walk, the ray's set-up and
// its end). Opacity and stopping are as without it. Where a whole phase waits, for memory or for a
// dependent chain, shows here; what the profilers that do not see GL compute would tell. 2: R the
// finds and the chord's set-up up to the gather, G the gather until its 19 values are there, B the
// piece's arithmetic, the rule and the sub-steps, Z as with 1 (other FCC_DVR_CLOCK values: as 1).
#ifndef FCC_DVR_CLOCK
#define FCC_DVR_CLOCK 0
#endif
#if FCC_DVR_CLOCK
#extension GL_ARB_shader_clock : require
#endif
// Only the chosen reconstruction's header is compiled (in the march file): the ids, the spline's types
// that pool.glsl gathers in, and the pool.
#include "ReconIds.h"
#include "FccSpline.h"
#include "pool.glsl"

#ifndef FCC_RECON
#define FCC_RECON FCC_RECON_BOXSPLINE
#endif
// 1: direct volume rendering (dvr.glsl) instead of the isosurface.
#ifndef FCC_MODE_DVR
#define FCC_MODE_DVR 0
#endif
// DVR's cell walk in a brick (dvrRound): 1, a round steps through cells to the next one the transfer
// function does not map to zero, then integrates it; 0, a round takes one cell, integrated if it is
// not zero, as the isosurface's walk does (a measurement knob, docs/RENDERER.md: the H200 ran ML 8%
// faster with 1, the engine CT the same).
#ifndef FCC_DVR_FIND_THEN_INTEGRATE
#define FCC_DVR_FIND_THEN_INTEGRATE 1
#endif
// 1: the DVR walk without the cells' integration (a stand-in absorption instead; wrong images): the
// walk's own cost, a measurement knob (docs/RENDERER.md).
#ifndef FCC_DVR_WALK_ONLY
#define FCC_DVR_WALK_ONLY 0
#endif
// 1: several isosurfaces (or a translucent one), composited front to back (surfaces.glsl).
#ifndef FCC_MULTI_ISO
#define FCC_MULTI_ISO 0
#endif

// 1: level of detail (docs/RENDERER.md): each brick drawn from the finest resident pyramid level no
// finer than the level it wants; a coarser one drawn in its place makes the ray provisional.
// The single opaque isosurface only.
#ifndef FCC_LOD
#define FCC_LOD 0
#endif
// 1: DVR's brick walk and cell walk in one loop (main, without levels of detail): a ray that finishes
// its brick takes its next brick while the warp's others still walk theirs. 0: a loop of bricks, each
// walked to its end (marchBrick). A measurement knob (docs/RENDERER.md): the H200 ran ML 17 % and the
// engine CT 12 % faster with 1.
#ifndef FCC_DVR_FLAT_WALK
#define FCC_DVR_FLAT_WALK 1
#endif
// 1 (with FCC_DVR_FLAT): an iteration of the flat walk first takes the brick steps a ray needs, in a
// loop of their own, then a round, so that rays between bricks join the warp's round in the same
// iteration instead of each brick step taking one (the rays' work and images the same); 0: an
// iteration is a round or a brick step. A measurement knob (docs/RENDERER.md).
#ifndef FCC_DVR_BRICKS_FIRST
#define FCC_DVR_BRICKS_FIRST 0
#endif
#if FCC_MODE_DVR && FCC_DVR_FLAT_WALK && !FCC_LOD
#define FCC_DVR_FLAT 1
#else
#define FCC_DVR_FLAT 0
#endif

// The work group: pixels per group in x and y (RenderOptions::workGroup defines them).
#ifndef FCC_GROUP_X
#define FCC_GROUP_X 8
#define FCC_GROUP_Y 8
#endif
layout(local_size_x = FCC_GROUP_X, local_size_y = FCC_GROUP_Y) in;

// A measurement knob (docs/RENDERER.md): FCC_OCCUPANCY_PAD floats of shared memory a work group holds
// and touches, to lower how many groups an SM runs at once (how much the frame depends on occupancy).
#ifndef FCC_OCCUPANCY_PAD
#define FCC_OCCUPANCY_PAD 0
#endif
#if FCC_OCCUPANCY_PAD > 0
shared float gOccupancyPad[FCC_OCCUPANCY_PAD];
#endif

layout(std430, binding = 1) readonly buffer PageTable { uint pageEntries[]; };
// Per node of 16^3 bricks (relative to uBrickMin): 0 if no brick in it needs evaluation.
layout(std430, binding = 2) readonly buffer NodeTable { uint nodeEntries[]; };
// What a pass tells the host, read back in one copy: the count of bricks requested this pass; the
// pixels that show the surface (DVR: any opacity, a waiting ray's too), over every pass of this view (first and last column and row: the
// viewer draws only what changed, see viewer/RedrawTracker.h); then the requested bricks' indices
// (bit 31 set for look-ahead requests). Coherent: noteSurfacePixel reads what other groups wrote.
layout(std430, binding = 3) coherent buffer Requests {
  uint requestCount;
  int surfaceMinX, surfaceMinY, surfaceMaxX, surfaceMaxY;
  uint requests[];
};
// One bit per brick: requested already this pass.
layout(std430, binding = 4) buffer RequestBits { uint requestBits[]; };
// Per slot: the last pass that read it (for least-recently-used eviction).
layout(std430, binding = 5) buffer SlotUse { uint slotLastUse[]; };
layout(std430, binding = 6) readonly buffer SlotBounds { vec2 slotBounds[]; };  // see pool.glsl

#if FCC_MODE_DVR || FCC_MULTI_ISO
// Read back where a ray resumes: the colour so far, and in the normal's x the transmittance so far.
layout(binding = 0, rgba32f) uniform image2D uColor;        // premultiplied colour, alpha the opacity
layout(binding = 1, rgba32f) uniform image2D uNormalDepth;  // 0 (transmittance while waiting), depth at opacity 0.5
                                                            // (several surfaces: the first crossing's normal, depth)
#else
layout(binding = 0, rgba32f) uniform writeonly image2D uColor;        // premultiplied shaded colour
layout(binding = 1, rgba32f) uniform writeonly image2D uNormalDepth;  // unit gradient (world), depth
#endif
layout(binding = 2, r32f) uniform image2D uResume;                    // t to resume from; < 0: done
#if FCC_MULTI_ISO
layout(binding = 3, r32f) uniform image2D uTransmittance;  // while waiting: the transmittance left, exactly
#endif

uniform ivec2 uResolution;
uniform vec3 uEye;            // world
uniform vec3 uForward;        // world, unit
uniform vec3 uRight;          // world, scaled by tan(fov/2) * aspect
uniform vec3 uUp;             // world, scaled by tan(fov/2)
uniform mat4 uIndexFromWorld;
uniform mat3 uNormalFromIndex;  // world gradient from index-space gradient: transpose of indexFromWorld
uniform float uIso;
uniform ivec3 uBrickMin;
uniform ivec3 uBrickDims;
uniform ivec3 uNodeDims;
uniform uint uPass;
uniform int uFirstPass;
uniform int uFirstColumn;     // columns left of it are covered (the viewer's opaque panel): no rays
uniform int uColumnOffset;    // the dispatch's first column: uFirstColumn rounded down to a group       // 1: every ray starts at the eye (uResume holds an older frame's values)
uniform uint uRequestCapacity;
uniform int uLookahead;       // bricks requested past the first missing one
uniform int uSkipEmpty;       // 0: evaluate every resident brick (for measuring the skipping)
uniform int uFiniteDifferenceNormals;  // 1: central differences of the value (the paper's Table 5 baseline)
uniform vec3 uSurfaceColor;
uniform vec3 uLightDir;       // world, unit, towards the light
uniform vec3 uClipLo;         // the clipping box, world space (+-1e30: none); rays are cut to it
uniform vec3 uClipHi;

#if FCC_LOD
// Level k of the pyramid: its box of bricks (its own brick coordinates: level 0's brick b lies in level
// k's brick b >> k, since level k's index space is level 0's scaled by 2^-k), its nodes, where its
// entries start in the page and node tables, and 2^-k (exact in float: o, d and the brick faces
// scaled by it keep every t of the march the same numbers).
#define FCC_MAX_LEVELS 16
uniform int uLevelCount;
uniform ivec3 uLevelBrickMin[FCC_MAX_LEVELS];
uniform ivec3 uLevelBrickDims[FCC_MAX_LEVELS];
uniform ivec3 uLevelNodeDims[FCC_MAX_LEVELS];
uniform uint uLevelPageOffset[FCC_MAX_LEVELS];
uniform uint uLevelNodeOffset[FCC_MAX_LEVELS];
uniform float uLevelScale[FCC_MAX_LEVELS];  // 2^-k
uniform float uLevelSize[FCC_MAX_LEVELS];   // 2^k
uniform float uLodBias;     // added to log2 of a brick's pixels per voxel (the user's and the raised one)
uniform float uPixelAngle;  // a pixel's height at unit distance from the eye: 2 tan(fov / 2) / height
// Per level: the pixels whose final hit was drawn from it (the frame's level mix).
layout(std430, binding = 8) buffer LevelHits { uint levelHits[]; };
// Per slot: the last pass that drew from it for a ray that wanted its level (slotLastUse also counts
// uploads, for eviction), and the last that drew from it as a coarser stand-in.
layout(std430, binding = 9) buffer SlotDrawn { uint slotDrawnPass[]; };
layout(std430, binding = 10) buffer SlotStandIn { uint slotStandInPass[]; };
// Where a provisional ray resumes, what the march carried there: (prevLevel + 1) * 3 + prevSign + 1,
// so that the resumed march is the very march a ray drawing the wanted levels throughout makes.
layout(binding = 4, r32f) uniform image2D uResumeState;

#endif

const uint kSkip = 0xFFFFFFFFu;
const uint kMissing = 0xFFFFFFFEu;
const float kBrickSites = 16.0;

#if FCC_LOD
// The level level-0 brick b wants: the coarsest whose voxel is no larger than a pixel at the brick's
// centre (index space distance times the pixel's angle is a pixel in index units, which is a level-0
// voxel), plus the bias. One value per brick and eye, whatever the pixel.
int wantedLevel(ivec3 b, vec3 o) {
  float pixelsInVoxels = length((vec3(b) + 0.5) * kBrickSites - o) * uPixelAngle;
  int level = int(floor(log2(max(pixelsInVoxels, 1e-30)) + uLodBias));
  return clamp(level, 0, uLevelCount - 1);
}
#endif

// 1: request() reads a brick's bit before its atomic (test and test-and-set); 0: the atomic alone. The
// same requests either way; a measurement knob (FCCVDB_SHADER_DEFINES, docs/RENDERER.md).
#ifndef FCC_REQUEST_TEST_FIRST
#define FCC_REQUEST_TEST_FIRST 1
#endif

void request(uint brickIndex, bool lookahead) {
  uint bit = 1u << (brickIndex & 31u);
  // Test, then test-and-set: most rays that miss a brick find it requested already, and the atomic of
  // each of them would queue on one word (a streaming pass's 2 M rays on a few thousand bricks). A
  // stale read only costs the atomic, which decides.
#if FCC_REQUEST_TEST_FIRST
  if ((requestBits[brickIndex >> 5] & bit) != 0u) return;
#endif
  uint old = atomicOr(requestBits[brickIndex >> 5], bit);
  if ((old & bit) != 0u) return;
  uint at = atomicAdd(requestCount, 1u);
  if (at < uRequestCapacity) requests[at] = brickIndex | (lookahead ? 0x80000000u : 0u);
}

// Grows the surface rectangle to hold `pixel`. Reads first: the rectangle only grows, so a stale read
// costs at most an atomic that changes nothing, and most pixels are inside it already (an atomic per
// pixel would queue every hit pixel of the frame on these four words).
void noteSurfacePixel(ivec2 pixel) {
  if (pixel.x < surfaceMinX) atomicMin(surfaceMinX, pixel.x);
  if (pixel.y < surfaceMinY) atomicMin(surfaceMinY, pixel.y);
  if (pixel.x > surfaceMaxX) atomicMax(surfaceMaxX, pixel.x);
  if (pixel.y > surfaceMaxY) atomicMax(surfaceMaxY, pixel.y);
}

// Slab test of the ray against a box; returns (tNear, tFar).
vec2 clipBox(vec3 o, vec3 invD, vec3 lo, vec3 hi) {
  vec3 ta = (lo - o) * invD, tb = (hi - o) * invD;
  vec3 tmin = min(ta, tb), tmax = max(ta, tb);
  return vec2(max(max(tmin.x, tmin.y), tmin.z), min(min(tmax.x, tmax.y), tmax.z));
}

struct Hit {
  float t;
  vec3 gradient;  // index space
};

#if FCC_MODE_DVR
#include "dvr.glsl"
#endif

// valueAt, hitInCell(b, cell, o, d, t0, t1, prevSign, hit) (the first hit inside one unit cell of a
// resident brick; the box spline's is written into marchBrick), and for DVR integrateCell(cell, o, d,
// t0, t1, state): one per lattice (FCC, CC, BCC), FCC_RECON says which.
// Read by both the CC and the BCC march: included here, outside their branches, because fcc_embed
// inlines a header once, where it first appears (inside the first branch, it would be missing from the
// second).
#include "CcTrilinear.h"
#if FCC_RECON == FCC_RECON_BOXSPLINE
#include "march_fcc.glsl"
#elif FCC_RECON == FCC_RECON_TRILINEAR || FCC_RECON == FCC_RECON_TRICUBIC || FCC_RECON == FCC_RECON_TYPE6
#include "march_cc.glsl"
#else
#include "march_bcc.glsl"
#endif

// Central differences of the reconstruction's value, six evaluations; the points are kept inside the
// brick (whose halo is what the pool holds).
vec3 finiteDifferenceGradient(vec3 xyz, ivec3 brick) {
  const float h = 0.125;
  vec3 lo = vec3(brick * 16) + h, hi = vec3(brick * 16 + 16) - h;
  vec3 p = clamp(xyz, lo, hi);
  return vec3(valueAt(p + vec3(h, 0, 0)) - valueAt(p - vec3(h, 0, 0)),
              valueAt(p + vec3(0, h, 0)) - valueAt(p - vec3(0, h, 0)),
              valueAt(p + vec3(0, 0, h)) - valueAt(p - vec3(0, 0, h))) / (2.0 * h);
}

#if FCC_MULTI_ISO
#include "surfaces.glsl"
#endif

#if FCC_MODE_DVR
// DVR's walk through the unit cells of one resident brick, a round at a time (dvrRound): each round
// first steps (cheaply: the DDA and the cell's slot bounds) to the next cell the transfer function does
// not map to zero, then integrates it (dear), so that the rays of a warp integrate together rather
// than each waiting while the others integrate the cells it skips (FCC_DVR_FIND_THEN_INTEGRATE; with 0
// a round takes one cell).
const int kDvrFindCells = FCC_DVR_FIND_THEN_INTEGRATE != 0 ? 64 : 1;
// The most rounds a brick takes: a ray crosses at most 46 of its cells, and a cell takes a second round
// where its entry piece is gathered first (march_fcc.glsl), at most every other cell.
const int kDvrBrickRounds = 96;
// Only what the walk changes or cannot derive: the steps' signs and lengths are the ray's (sign(d),
// |1/d|), the brick's last cell its first + 15.
struct DvrCellWalk {
  ivec3 cell, cellLo;
  vec3 tMax;
  float tCell, tb;
  uint boundsBase;
  bool done;
};

// The walk of brick b (resident in `slot`) between ta and tb; selects the slot for coefficientAt.
DvrCellWalk dvrBeginBrick(ivec3 b, uint slot, vec3 o, vec3 d, vec3 invD, float ta, float tb) {
  selectSlot(slot, b);
  DvrCellWalk w;
  w.boundsBase = slot * uint(kSlotVoxels);
  w.cellLo = b * 16;
  // The starting cell: where the ray is just past ta (clamped: rounding may put it a hair outside).
  vec3 pStart = o + min(ta + 1e-4 * (tb - ta), 0.5 * (ta + tb)) * d;
  w.cell = clamp(ivec3(floor(pStart)), w.cellLo, w.cellLo + 15);
  w.tMax = (vec3(w.cell) + vec3(greaterThan(d, vec3(0.0))) - o) * invD;
  w.tCell = ta;
  w.tb = tb;
  w.done = false;
  // Nothing carries into a brick: its cells are integrated the same whatever was resident before it
  // (the image does not depend on the cache), and the face jumps' sites stay inside the slot.
  gDvrCarry.state = kDvrCarryNone;
  return w;
}

// Steps the walk past its current cell, which the ray (direction d; invD its 1 / d, through a pyramid
// level the level's scaled one, as dvrBeginBrick had it) leaves at tExit through the face normal to
// `axis`; true once the brick is crossed.
bool dvrStep(inout DvrCellWalk w, vec3 d, vec3 invD, float tExit, int axis) {
  if (tExit >= w.tb) return true;
  // Never backwards: a start cell clamped into the brick can have a face behind the ray.
  w.tCell = max(w.tCell, tExit);
  if (axis == 0) {
    w.cell.x += int(sign(d.x));
    w.tMax.x += abs(invD.x);
  } else if (axis == 1) {
    w.cell.y += int(sign(d.y));
    w.tMax.y += abs(invD.y);
  } else {
    w.cell.z += int(sign(d.z));
    w.tMax.z += abs(invD.z);
  }
  return any(lessThan(w.cell, w.cellLo)) || any(greaterThan(w.cell, w.cellLo + 15));
}

// One round of the walk; true once the ray is opaque enough to stop. w.done once the brick is crossed.
// The walk stays on the cell it finds until integrateCell is done with it: a round that only gathered
// the cell's entry piece (gDvrCarry's kDvrCarryEntry) leaves it for the next round to find again.
bool dvrRound(inout DvrCellWalk w, vec3 o, vec3 d, vec3 invD, inout DvrState st) {
  dvrClock(3, st);
  bool have = false;
  ivec3 found;
  float foundT0 = 0.0, foundT1 = 0.0;
  int foundAxis = 0;
  for (int iter = 0; iter < kDvrFindCells; ++iter) {
    float tExit = min(min(min(w.tMax.x, w.tMax.y), w.tMax.z), w.tb);
    ivec3 voxel = (w.cell - w.cellLo) >> 1;
    vec2 cellBounds = slotBounds[w.boundsBase + uint((voxel.z * 8 + voxel.y) * 8 + voxel.x)];
    bool integrate = tExit > w.tCell && !(uSkipEmpty != 0 && tfZeroOn(cellBounds.x, cellBounds.y));
    // The axis the walk steps along next: the face the ray leaves the cell through.
    int axis = w.tMax.x <= w.tMax.y && w.tMax.x <= w.tMax.z ? 0 : (w.tMax.y <= w.tMax.z ? 1 : 2);
    if (integrate) {
      have = true;
      found = w.cell;
      foundT0 = w.tCell;
      foundT1 = tExit;
      foundAxis = axis;
      gDvrCellBounds = cellBounds;
      break;
    }
#if FCC_DVR_COUNT == 1
    st.color.r += 1.0;
#endif
    gDvrCarry.state = kDvrCarryNone;  // a cell passed over: nothing carries past it
    if (dvrStep(w, d, invD, tExit, axis)) {
      w.done = true;
      break;
    }
  }
#if FCC_DVR_CLOCK != 2
  dvrClock(0, st);
#endif
  if (!have) return false;
#if FCC_DVR_WALK_ONLY
  st.transmittance *= 1.0 - 1e-3 * (foundT1 - foundT0);
  bool stop = st.transmittance <= uStopTransmittance;
#else
#if FCC_DVR_COUNT == 1
  if (gDvrCarry.state != kDvrCarryEntry) st.color.rg += 1.0;  // a cell's second round is not counted again
#elif FCC_DVR_COUNT == 2
  st.color.r += 1.0;
#endif
  gDvrExitAxis = foundAxis;
  gDvrBrickCellLo = w.cellLo;
  bool stop = integrateCell(found, o, d, foundT0, foundT1, st);
  if (!(st.transmittance == -1.0)) dvrClock(2, st);  // (a branch on the result: the stamp waits for it)
#endif
#if FCC_DVR_COUNT == 2
  if (gDvrCarry.state == kDvrCarryEntry) st.color.b += 1.0;
  else st.color.g += 1.0;
#endif
  if (gDvrCarry.state != kDvrCarryEntry && dvrStep(w, d, invD, foundT1, foundAxis)) w.done = true;
  return stop;
}
#endif

// The first hit in the resident brick b between ta and tb, walking its unit cells (those whose slot
// bounds exclude the isovalue are passed over). prevSign: the sign of s - iso where the ray reaches
// ta (-1 negative, +1 not, 0 unknown), updated to where it leaves. For DVR: the emission and
// absorption of the cells whose bounds the transfer function does not map to zero, in rounds
// (dvrRound); true once the ray is opaque enough to stop (st: what the ray has accumulated).
#if FCC_MODE_DVR
bool marchBrick(ivec3 b, uint slot, vec3 o, vec3 d, vec3 invD, float ta, float tb, inout DvrState st) {
  DvrCellWalk walk = dvrBeginBrick(b, slot, o, d, invD, ta, tb);
  for (int r = 0; r < kDvrBrickRounds && !walk.done; ++r)
    if (dvrRound(walk, o, d, invD, st)) return true;
  return false;
}
#else
bool marchBrick(ivec3 b, uint slot, vec3 o, vec3 d, vec3 invD, float ta, float tb, inout int prevSign, inout Hit hit) {
  selectSlot(slot, b);
  uint boundsBase = slot * uint(kSlotVoxels);
  ivec3 cellLo = b * 16, cellHi = cellLo + 15;
  float tm = 0.5 * (ta + tb);
  // The starting cell: where the ray is just past ta (clamped: rounding may put it a hair outside).
  vec3 pStart = o + min(ta + 1e-4 * (tb - ta), tm) * d;
  ivec3 cell = clamp(ivec3(floor(pStart)), cellLo, cellHi);
  ivec3 stepDir = ivec3(sign(d));
  vec3 nextBoundary = vec3(cell) + vec3(greaterThan(d, vec3(0.0)));
  vec3 tMax = (nextBoundary - o) * invD;
  vec3 tDelta = abs(invD);
  float tCell = ta;
  for (int iter = 0; iter < 64; ++iter) {
    float tExit = min(min(min(tMax.x, tMax.y), tMax.z), tb);
    ivec3 voxel = (cell - cellLo) >> 1;
    uint voxelEntry = boundsBase + uint((voxel.z * 8 + voxel.y) * 8 + voxel.x);
    vec2 cellBounds = slotBounds[voxelEntry];
    if (tExit > tCell && uSkipEmpty != 0 && !(cellBounds.x <= uIso && uIso <= cellBounds.y)) {
      prevSign = cellBounds.x > uIso ? 1 : -1;
    } else if (tExit > tCell) {
#if FCC_RECON == FCC_RECON_BOXSPLINE
      // The box spline's cell (its pieces, the cubic along the ray in each, sparse/FccRay.h), written
      // here rather than called as march_cc.glsl's hitInCell is: as a function the H200 ran it 8%
      // (512^2) to 13% (1080p) slower (NVIDIA's compiler did not inline it; docs/BENCHMARKS.md).
      vec4 splits = fcc_cell_splits(cell, o, d, tCell, tExit);
      float s0 = tCell;
      // Up to five sub-segments, one per piece the ray passes (in practice at most three).
      for (int k = 0; k < 5 && s0 < tExit; ++k) {
        float s1 = k == 0 ? splits.x : (k == 1 ? splits.y : (k == 2 ? splits.z : (k == 3 ? splits.w : tExit)));
        if (s1 <= s0) continue;
        // Kept inside this cell, so the stencil stays inside the slot's halo whatever the rounding.
        FccFrame frame = fcc_locate(clamp(o + (0.5 * (s0 + s1)) * d, vec3(cell), vec3(cell + 1)));
        FccSamples samples = gatherStencil(frame);
        FccCubic cubic = fcc_cubic(samples, frame.type);
        FccRange range = fcc_cubic_range(cubic);
        if (!(range.lo <= uIso && uIso <= range.hi)) {
          prevSign = range.lo > uIso ? 1 : -1;
        } else {
          vec4 bz = fcc_segment_bernstein(cubic, frame, o, d, s0, s1, uIso);
          float u = fcc_first_root_after(bz, prevSign);
          prevSign = bz.w < 0.0 ? -1 : 1;
          if (u >= 0.0) {
            hit.t = s0 + u * (s1 - s0);
            vec3 xyz = o + hit.t * d;
            if (uFiniteDifferenceNormals != 0) {
              hit.gradient = finiteDifferenceGradient(xyz, b);
            } else {
              // The gradient of this piece's polynomial at the hit, with the stencil already read:
              // locating the rounded hit point anew could pick a cell outside the slot's halo.
              frame.q = vec3(frame.axis) * (xyz - vec3(frame.origin));
              hit.gradient = fcc_gradient(samples, frame);
            }
            return true;
          }
        }
        s0 = s1;
      }
#else
      if (hitInCell(b, cell, o, d, tCell, tExit, prevSign, hit)) return true;
#endif
    }
    if (tExit >= tb) break;
    // Never backwards: a start cell clamped into the brick can have a face behind the ray.
    tCell = max(tCell, tExit);
    if (tMax.x <= tMax.y && tMax.x <= tMax.z) {
      cell.x += stepDir.x;
      tMax.x += tDelta.x;
    } else if (tMax.y <= tMax.z) {
      cell.y += stepDir.y;
      tMax.y += tDelta.y;
    } else {
      cell.z += stepDir.z;
      tMax.z += tDelta.z;
    }
    if (any(lessThan(cell, cellLo)) || any(greaterThan(cell, cellHi))) break;
  }
  return false;
}
#endif

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy) + ivec2(uColumnOffset, 0);
#if FCC_OCCUPANCY_PAD > 0
  gOccupancyPad[gl_LocalInvocationIndex % uint(FCC_OCCUPANCY_PAD)] = float(pixel.x);
#endif
  if (any(greaterThanEqual(pixel, uResolution)) || pixel.x < uFirstColumn) return;
  // The first pass writes every pixel's resume value (below), so the image needs no clearing.
  float tResume = uFirstPass != 0 ? 0.0 : imageLoad(uResume, pixel).x;
  if (tResume < 0.0) return;

  // Pinhole camera, rays through pixel centres, row 0 at the top.
  vec2 ndc = (vec2(pixel) + 0.5) / vec2(uResolution) * 2.0 - 1.0;
  vec3 dirWorld = normalize(uForward + ndc.x * uRight - ndc.y * uUp);
  // Index space: the same parameter t measures world distance along the unit world direction.
  vec3 o = (uIndexFromWorld * vec4(uEye, 1.0)).xyz;
  vec3 d = mat3(uIndexFromWorld) * dirWorld;
  // No zero components: keeps the slab and DDA arithmetic free of 0 * inf.
  const float kTiny = 1e-20;
  d = vec3(abs(d.x) < kTiny ? kTiny : d.x, abs(d.y) < kTiny ? kTiny : d.y, abs(d.z) < kTiny ? kTiny : d.z);
  vec3 invD = 1.0 / d;

  vec3 boxLo = vec3(uBrickMin) * kBrickSites, boxHi = vec3(uBrickMin + uBrickDims) * kBrickSites;
  vec2 span = clipBox(o, invD, boxLo, boxHi);
  // The clipping box in world space, where t is the distance along the unit direction too.
  vec3 dClip = vec3(abs(dirWorld.x) < kTiny ? kTiny : dirWorld.x, abs(dirWorld.y) < kTiny ? kTiny : dirWorld.y,
                    abs(dirWorld.z) < kTiny ? kTiny : dirWorld.z);
  vec2 clip = clipBox(uEye, 1.0 / dClip, uClipLo, uClipHi);
  float t = max(max(max(span.x, clip.x), 0.0), tResume);
  float tEnd = min(span.y, clip.y);
  bool found = false;
  bool stopped = false;
  int lookahead = uLookahead;
  int prevSign = 0;  // sign of s - iso where the last marched brick ended (0: unknown)
  Hit hit;
  hit.t = 0.0;
  hit.gradient = vec3(0.0);
#if FCC_MODE_DVR
  dvrBeginRay(dirWorld);
  DvrState st;
  if (uFirstPass != 0) {
    st.color = vec3(0.0);
    st.transmittance = 1.0;
    st.depthHalf = 1.0 / 0.0;
  } else {  // what the ray had when it stopped for a brick: kept exactly, so the image is the same
    st.color = imageLoad(uColor, pixel).rgb;
    vec4 nd = imageLoad(uNormalDepth, pixel);
    st.transmittance = nd.x;
    st.depthHalf = nd.w;
  }
#if FCC_DVR_CLOCK
  if (uFirstPass != 0) st.depthHalf = 0.0;  // the cycles outside the phases, not a depth
  gDvrClockMark = clock2x32ARB().x;
#endif
#endif

#if FCC_MULTI_ISO
  gDirWorld = dirWorld;
  SurfaceState st;
  st.side = ivec4(0);
  if (uFirstPass != 0) {
    st.color = vec3(0.0);
    st.transmittance = 1.0;
    st.normal = vec3(0.0);
    st.depth = 1.0 / 0.0;
  } else {  // what the ray had composited when it stopped for a brick, exactly
    st.color = imageLoad(uColor, pixel).rgb;
    st.transmittance = imageLoad(uTransmittance, pixel).x;
    vec4 nd = imageLoad(uNormalDepth, pixel);
    st.normal = nd.xyz;
    st.depth = nd.w;
  }
#endif

#if FCC_LOD
  // The same brick DDA over level 0's bricks; each brick is drawn from the finest level at or above
  // the one it wants whose page entry is not missing (a coarser level's brick covers 2^k level-0
  // bricks per axis; it is marched over this brick's stretch of the ray only, in its own index space,
  // with the same t). Drawing a coarser level than wanted makes the ray provisional: it shows what it
  // found and resumes from the first such brick once the wanted one is resident. A ray stops and
  // waits, as without levels, only where no level is resident (the coarsest is kept resident).
  // DVR draws each brick from the level it wants and waits for it, as without levels: what a ray
  // integrated cannot be taken back, so no coarser level stands in (the image is the same whatever
  // the pool held, as the full-resolution frame's is).
  int guard = 0;
  int prevLevel = -1;          // the level the last marched stretch was drawn from
  if (uFirstPass == 0) {
    int state = int(imageLoad(uResumeState, pixel).x);
    prevLevel = state / 3 - 1;
    prevSign = state % 3 - 1;
  }
  float tProvisional = -1.0;   // where the ray first drew a coarser level than wanted (< 0: nowhere)
  float stateProvisional = 1.0;  // uResumeState's value there
  int hitLevel = 0;
  int requestsLeft = 1 + uLookahead;  // a drawing ray's requests for the levels it wants
  while (t < tEnd && guard < 4096) {
    ++guard;
    vec3 p = o + t * d;
    ivec3 b = clamp(ivec3(floor(p / kBrickSites)), uBrickMin, uBrickMin + uBrickDims - 1);
    vec3 tFar = (vec3(b) * kBrickSites + vec3(greaterThan(d, vec3(0.0))) * kBrickSites - o) * invD;
    b += ivec3(lessThanEqual(tFar, vec3(t))) * ivec3(sign(d));
    if (any(lessThan(b, uBrickMin)) || any(greaterThanEqual(b, uBrickMin + uBrickDims))) break;
    int want = wantedLevel(b, o);
    ivec3 bw = b >> want;
    ivec3 relw = bw - uLevelBrickMin[want];
    bool insideWanted = !(any(lessThan(relw, ivec3(0))) || any(greaterThanEqual(relw, uLevelBrickDims[want])));
    if (uSkipEmpty != 0 && insideWanted) {
      ivec3 node = relw >> 4;
      ivec3 nd = uLevelNodeDims[want];
      if (nodeEntries[uLevelNodeOffset[want] + uint((node.z * nd.y + node.y) * nd.x + node.x)] == 0u) {
        // The wanted level has nothing to draw in this node (level 0: exactly the march without levels).
        float size = uLevelSize[want];
        vec3 nodeLo = vec3(uLevelBrickMin[want] + node * 16) * (kBrickSites * size);
        float tExitNode = clipBox(o, invD, nodeLo, nodeLo + 16.0 * kBrickSites * size).y;
        t = tExitNode > t ? tExitNode : t + 1e-5 * abs(t) + 1e-6;  // the nudge only guards progress
        prevSign = 0;
        continue;
      }
    }
    vec3 brickLo = vec3(b) * kBrickSites;
    float tExitBrick = min(clipBox(o, invD, brickLo, brickLo + kBrickSites).y, tEnd);
    // The finest level at or above `want` whose entry is known; missing finer ones are requested.
    uint entry = kMissing;
    int level = want;
#if FCC_MODE_DVR
    int lastLevel = want;  // no stand-ins
#else
    int lastLevel = uLevelCount - 1;
#endif
    for (int k = want; k <= lastLevel; ++k) {
      level = k;
      ivec3 rk = (b >> k) - uLevelBrickMin[k];
      ivec3 dims = uLevelBrickDims[k];
      if (any(lessThan(rk, ivec3(0))) || any(greaterThanEqual(rk, dims))) {
        entry = kSkip;  // outside the level's box: nothing varies there
        break;
      }
      uint index = uLevelPageOffset[k] + uint((rk.z * dims.y + rk.y) * dims.x + rk.x);
      entry = pageEntries[index];
      if (entry != kMissing) break;
      if (stopped || requestsLeft > 0) request(index, stopped || k != want);
      if (!stopped) --requestsLeft;
    }
    if (entry == kMissing) {  // no level resident: wait, as a ray without levels does
      if (!stopped) {
        stopped = true;
        imageStore(uResume, pixel, vec4(tProvisional >= 0.0 ? tProvisional : t));
        // Resumed at a stop, the march starts afresh (as without levels); at a provisional point, as it was.
        imageStore(uResumeState, pixel, vec4(tProvisional >= 0.0 ? stateProvisional : 1.0));
      } else if (--lookahead < 0) {
        break;
      }
    } else if (!stopped) {
      if (level > want && tProvisional < 0.0) {
        tProvisional = t;
        stateProvisional = float((prevLevel + 1) * 3 + prevSign + 1);
      }
      if (entry == kSkip) {
        prevSign = 0;
        prevLevel = -1;
      } else {
        slotLastUse[entry] = uPass;
        if (tProvisional < 0.0) slotDrawnPass[entry] = uPass;
        else slotStandInPass[entry] = uPass;
        if (level != prevLevel) prevSign = 0;  // another level is another spline
        prevLevel = level;
        // Level 0 marches with o, d and invD themselves: scaled by 1 they would be the same numbers, but
        // the compiler may fuse the scaling into the march's arithmetic and round otherwise.
        vec3 oLevel = o, dLevel = d, invDLevel = invD;
        if (level != 0) {
          oLevel = o * uLevelScale[level];
          dLevel = d * uLevelScale[level];
          invDLevel = invD * uLevelSize[level];
        }
#if FCC_MODE_DVR
#if FCC_DVR_SHADING
        gDvrLevelScale = uLevelScale[level];
#endif
        if (marchBrick(b >> level, entry, oLevel, dLevel, invDLevel, t, tExitBrick, st)) {
          found = true;  // opaque enough: nothing behind is integrated or requested
          break;
        }
#else
        if (marchBrick(b >> level, entry, oLevel, dLevel, invDLevel, t, tExitBrick, prevSign, hit)) {
          found = true;
          hitLevel = level;
          break;
        }
#endif
      }
    }
    t = tExitBrick > t ? tExitBrick : t + 1e-5 * abs(t) + 1e-6;
  }
#else
  // Brick DDA (re-seeded after every node skip).
  int guard = 0;
#if FCC_DVR_FLAT
  // DVR walks bricks and cells in this one loop: an iteration is a round of the resident brick's cell
  // walk (dvrRound) or a step to the next brick, so a ray that finishes its brick does not wait for
  // the warp's others to finish theirs (FCC_DVR_FLAT_WALK).
  bool inBrick = false;
  DvrCellWalk walk;
  int rounds = 0;
#endif
  while (t < tEnd && guard < 4096) {
#if FCC_DVR_FLAT && FCC_DVR_COUNT == 3
    st.color.b += 1.0;
#endif
#if FCC_DVR_FLAT && !FCC_DVR_BRICKS_FIRST
    if (inBrick) {
#if FCC_DVR_COUNT == 3
      st.color.r += 1.0;
#endif
      if (dvrRound(walk, o, d, invD, st)) {
        found = true;  // opaque enough: nothing behind is integrated or requested
        break;
      }
      if (walk.done || ++rounds >= kDvrBrickRounds) {
        inBrick = false;
        t = walk.tb > t ? walk.tb : t + 1e-5 * abs(t) + 1e-6;
      }
      continue;
    }
#endif
#if FCC_DVR_FLAT && FCC_DVR_BRICKS_FIRST
    while (!inBrick && t < tEnd && guard < 4096) {
#endif
    ++guard;
#if FCC_DVR_FLAT && FCC_DVR_COUNT == 3
    st.color.g += 1.0;
#endif
    vec3 p = o + t * d;
    ivec3 b = clamp(ivec3(floor(p / kBrickSites)), uBrickMin, uBrickMin + uBrickDims - 1);
    // At a brick's (or node's) exit, rounding can put p back in the brick the ray is leaving: step
    // across each face already behind the ray (the same float expressions as clipBox), so that the
    // next brick is marched from t itself and no stretch past its face is skipped.
    vec3 tFar = (vec3(b) * kBrickSites + vec3(greaterThan(d, vec3(0.0))) * kBrickSites - o) * invD;
    b += ivec3(lessThanEqual(tFar, vec3(t))) * ivec3(sign(d));
    if (any(lessThan(b, uBrickMin)) || any(greaterThanEqual(b, uBrickMin + uBrickDims))) break;
    ivec3 rel = b - uBrickMin;
    ivec3 node = rel >> 4;
    if (uSkipEmpty != 0 && nodeEntries[(node.z * uNodeDims.y + node.y) * uNodeDims.x + node.x] == 0u) {
      vec3 nodeLo = vec3(uBrickMin + node * 16) * kBrickSites;
      float tExitNode = clipBox(o, invD, nodeLo, nodeLo + 16.0 * kBrickSites).y;
      t = tExitNode > t ? tExitNode : t + 1e-5 * abs(t) + 1e-6;  // the nudge only guards progress
      prevSign = 0;
#if FCC_MULTI_ISO
      st.side = ivec4(0);
#endif
      continue;
    }
    vec3 brickLo = vec3(b) * kBrickSites;
    float tExitBrick = min(clipBox(o, invD, brickLo, brickLo + kBrickSites).y, tEnd);
    uint index = uint((rel.z * uBrickDims.y + rel.y) * uBrickDims.x + rel.x);
    uint entry = pageEntries[index];
    if (entry == kMissing) {
      request(index, stopped);
      if (!stopped) {
        stopped = true;
        imageStore(uResume, pixel, vec4(t));
      } else if (--lookahead < 0) {
        break;
      }
    } else if (entry == kSkip) {
      prevSign = 0;
#if FCC_MULTI_ISO
      st.side = ivec4(0);
#endif
    } else if (!stopped) {
      slotLastUse[entry] = uPass;
#if FCC_MULTI_ISO
      if (marchBrickSurfaces(b, entry, o, d, invD, t, tExitBrick, st)) {
        found = true;  // opaque enough: nothing behind is composited or requested
        break;
      }
#elif FCC_DVR_FLAT
      walk = dvrBeginBrick(b, entry, o, d, invD, t, tExitBrick);
      inBrick = true;
      rounds = 0;
      continue;
#elif FCC_MODE_DVR
      if (marchBrick(b, entry, o, d, invD, t, tExitBrick, st)) {
        found = true;  // opaque enough: nothing behind is integrated or requested
        break;
      }
#else
      if (marchBrick(b, entry, o, d, invD, t, tExitBrick, prevSign, hit)) {
        found = true;
        break;
      }
#endif
    }
    t = tExitBrick > t ? tExitBrick : t + 1e-5 * abs(t) + 1e-6;
#if FCC_DVR_FLAT && FCC_DVR_BRICKS_FIRST
    }
    if (!inBrick) break;  // past the last brick, or stopped for a missing one
#if FCC_DVR_COUNT == 3
    st.color.r += 1.0;
#endif
    if (dvrRound(walk, o, d, invD, st)) {
      found = true;  // opaque enough: nothing behind is integrated or requested
      break;
    }
    if (walk.done || ++rounds >= kDvrBrickRounds) {
      inBrick = false;
      t = walk.tb > t ? walk.tb : t + 1e-5 * abs(t) + 1e-6;
    }
#endif
  }
#endif
#if FCC_MODE_DVR
  dvrClock(3, st);
  if (stopped && !found) {  // resumes next pass; meanwhile the pixel shows what it has so far
    imageStore(uColor, pixel, vec4(st.color, 1.0 - st.transmittance));
    imageStore(uNormalDepth, pixel, vec4(st.transmittance, 0.0, 0.0, st.depthHalf));
    // What it has so far differs from the background: the viewer's presenter must draw it.
    if (st.transmittance < 1.0) noteSurfacePixel(pixel);
    return;
  }
  imageStore(uResume, pixel, vec4(-1.0));
#if FCC_OCCUPANCY_PAD > 0
  if (gOccupancyPad[gl_LocalInvocationIndex % uint(FCC_OCCUPANCY_PAD)] < -1.0) st.color.r += 1.0;  // never: x >= 0
#endif
#if FCC_WARP_PROBE
  st.color = vec3(float(gl_WarpIDNV), float(gl_SMIDNV), float(gl_WarpsPerSMNV));
  st.transmittance = 0.0;
#endif
  imageStore(uColor, pixel, vec4(st.color, 1.0 - st.transmittance));
  imageStore(uNormalDepth, pixel, vec4(0.0, 0.0, 0.0, st.depthHalf));
  if (st.transmittance < 1.0) noteSurfacePixel(pixel);
  return;
#endif
#if FCC_MULTI_ISO
  // Waiting or not, the pixel shows what the ray has composited (a waiting ray resumes from it).
  if (stopped && !found) imageStore(uTransmittance, pixel, vec4(st.transmittance));
  else imageStore(uResume, pixel, vec4(-1.0));
  imageStore(uColor, pixel, vec4(st.color, 1.0 - st.transmittance));
  imageStore(uNormalDepth, pixel, vec4(st.normal, st.depth));
  if (st.transmittance < 1.0) noteSurfacePixel(pixel);
  return;
#endif
  if (stopped && !found) {  // resumes next pass; meanwhile the pixel shows the background
    imageStore(uColor, pixel, vec4(0.0));
    imageStore(uNormalDepth, pixel, vec4(0.0, 0.0, 0.0, 1.0 / 0.0));
    return;
  }

#if FCC_LOD
  // Provisional: shows what it found and resumes where it first drew a coarser level than wanted.
  bool provisional = tProvisional >= 0.0;
  imageStore(uResume, pixel, vec4(provisional ? tProvisional : -1.0));
  if (provisional) imageStore(uResumeState, pixel, vec4(stateProvisional));
  if (found && !provisional) atomicAdd(levelHits[hitLevel], 1u);
  // (A coarser level's gradient is in its own index space: 2^k times level 0's, the same direction.)
#else
  imageStore(uResume, pixel, vec4(-1.0));
#endif
  if (!found) {
    imageStore(uColor, pixel, vec4(0.0));
    imageStore(uNormalDepth, pixel, vec4(0.0, 0.0, 0.0, 1.0 / 0.0));
    return;
  }
  vec3 n = uNormalFromIndex * hit.gradient;
  float len = length(n);
  n = len > 0.0 ? n / len : -dirWorld;
  // Two-sided Lambert with a little ambient light.
  vec3 nFacing = dot(n, dirWorld) > 0.0 ? -n : n;
  float diffuse = max(dot(nFacing, uLightDir), 0.0);
  vec3 color = uSurfaceColor * (0.15 + 0.85 * diffuse);
#if FCC_WARP_PROBE
  // (uSurfaceColor kept in use: the renderer sets it.)
  color = vec3(float(gl_WarpIDNV) + (color.r < -1.0 ? 1.0 : 0.0), float(gl_SMIDNV), float(gl_WarpsPerSMNV));
#endif
  imageStore(uColor, pixel, vec4(color, 1.0));
  imageStore(uNormalDepth, pixel, vec4(n, hit.t));
  noteSurfacePixel(pixel);
}
