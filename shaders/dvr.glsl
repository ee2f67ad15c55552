// Direct volume rendering for raycast.comp (FCC_MODE_DVR): emission-absorption front to back through
// the reconstructed field, with the transfer function sampled as sparse/TransferFunction.h's
// TransferTable (entries (sigma r, sigma g, sigma b, sigma) per world unit, linear between entries).
//
// Along a ray the field is a known polynomial on each piece (a cubic for the box spline and trilinear,
// degree 9 for tricubic), given here in Bernstein form on the piece's segment. Its range lies within
// its Bernstein coefficients, so a segment whose range the table maps to zero extinction is passed
// over exactly, and the others are cut into equal sub-steps, as many as an error estimate on that
// range asks for (dvrSteps; docs/DVR.md, "How many sub-steps"). Each sub-step takes the medium at the
// polynomial's mean over it (a cubic's, exactly; degree 9: at its midpoint) and composites exactly.

layout(std430, binding = 12) readonly buffer TfEntries { vec4 tfEntries[]; };
// tfPrefix[i]: among entries [0, i), those with non-zero extinction (TransferTable::nonZeroPrefix), and
// the sums of their kinks and colour steps in quanta of uTfKinkQuantum and uTfColourQuantum, and in w
// the kinks' sum among [0, i + 1) (viewer/DvrTableGpu.h's prefixes).
layout(std430, binding = 13) readonly buffer TfPrefix { uvec4 tfPrefix[]; };
uniform float uTfKinkQuantum, uTfColourQuantum;
uniform float uTfMin;          // the value of entry 0
uniform float uTfScale;        // entries per unit of value: (size - 1) / (vmax - vmin)
uniform int uTfSize;
// tfLevels[k * uTfSize + i]: the largest and the smallest extinction of entries [i, i + 2^k)
// (viewer/DvrTableGpu.h).
layout(std430, binding = 14) readonly buffer TfLevels { vec2 tfLevels[]; };
uniform float uStopTransmittance;  // 1 - the opacity at which a ray stops

// 1: gradient shading (RenderOptions::dvrShading, `--shading on`): each sub-step's emission times a
// two-sided Lambert term of the reconstruction's analytic gradient at its midpoint, over an ambient
// floor: kDvrAmbient + (1 - kDvrAmbient) |cos| of the angle between the world gradient and the
// direction towards the light, 1 where the gradient is 0 (sparse/ReferenceDvr.h's dvrShadeLit, the
// same formula), plus a white specular term uDvrSpecular |cos|^uDvrSpecularPower of the angle between
// the gradient and Blinn-Phong's half vector (0 where the gradient is 0) emitted in proportion to the
// sub-step's opacity. The light (RenderOptions::dvrShading.light, uDvrLight): a headlight, at the eye, so that
// the direction towards it is the ray's own and the half vector the ray; or the directional light
// uLightDir (RenderOptions::lightInCamera, as the isosurface's); or the light kit (viewer/DvrLight.h:
// four directional lights and the headlight, whose weights add up to 1), each |cos| term its lights'
// weighted sum. Absorption is unchanged, so opacity and depth are those of the unshaded image. 0: the
// unshaded code, unchanged.
#ifndef FCC_DVR_SHADING
#define FCC_DVR_SHADING 0
#endif

// The sub-step rule's two parameters (dvrSteps), measurement knobs (docs/RENDERER.md): the error
// estimate's bound relative to the opacity a segment adds, and the most optical depth one sub-step
// may hold. At most kDvrMaxSteps sub-steps per piece segment (a box spline cell's chord of up to three
// pieces: three times this).
#ifndef FCC_DVR_TOLERANCE
#define FCC_DVR_TOLERANCE 0.01
#endif
#ifndef FCC_DVR_STEP_DEPTH
#define FCC_DVR_STEP_DEPTH 1.0
#endif
const float kDvrTolerance = FCC_DVR_TOLERANCE;
const float kDvrStepDepth = FCC_DVR_STEP_DEPTH;
const int kDvrMaxSteps = 64;
// A box spline cell's chord (dvrChord3): three pieces' worth. A measurement knob (docs/RENDERER.md).
#ifndef FCC_DVR_CHORD_MAX_STEPS
#define FCC_DVR_CHORD_MAX_STEPS (3 * kDvrMaxSteps)
#endif

// 1: a measurement knob (docs/RENDERER.md): the colour channels count work instead of light, R the
// unit cells a ray visits in resident bricks, G those it integrates, B its sub-steps (the opacity and
// the stopping are as without it). Wrong images: for where a frame's work goes. 2: R the walk's rounds
// that integrate or prepare a cell, G the cells integrated, B the rounds that only gathered a cell's
// entry piece (march_fcc.glsl's chain). 3 (raycast.comp's flat walk): R the walk's rounds (dvrRound,
// those that find nothing too), G its brick steps (resident, skipped or missing bricks and empty
// nodes alike), B the iterations of its outer loop (R + G, unless FCC_DVR_BRICKS_FIRST).
#ifndef FCC_DVR_COUNT
#define FCC_DVR_COUNT 0
#endif

struct DvrState {
  vec3 color;          // premultiplied, accumulated front to back
  float transmittance;
  float depthHalf;     // where the opacity first reached 0.5 (+inf: not yet)
};

// raycast.comp's FCC_DVR_CLOCK (a measurement knob): the SM clock at the last phase boundary, and
// dvrClock(k) adds the cycles since then to phase k (0-2: st.color's R, G, B; 3: st.depthHalf).
#ifndef FCC_DVR_CLOCK
#define FCC_DVR_CLOCK 0
#endif
#if FCC_DVR_CLOCK
uint gDvrClockMark = 0u;
void dvrClock(int k, inout DvrState st) {
  uint now = clock2x32ARB().x;
  float cycles = float(now - gDvrClockMark);  // unsigned: right across the counter's wrap
  gDvrClockMark = now;
  if (k == 0) st.color.r += cycles;
  else if (k == 1) st.color.g += cycles;
  else if (k == 2) st.color.b += cycles;
  else st.depthHalf += cycles;
}
#else
void dvrClock(int k, inout DvrState st) {}
#endif

#if FCC_DVR_SHADING
const float kDvrAmbient = 0.3;
uniform float uDvrSpecular;       // RenderOptions::dvrShading.specular: 0 none, at most 1
uniform float uDvrSpecularPower;  // RenderOptions::dvrShading.specularPower: > 0
// The ray and the unit cell integrateCell is in (dvrBeginCell), for the gradient at a sub-step.
vec3 gDvrO, gDvrD;
ivec3 gDvrCell;
// RenderOptions::dvrShading.light (viewer/DvrLight.h): 0 the light at the eye, 1 uLightDir, 2 the light kit:
// uDvrKitLights (world, unit, towards them) weighted by uDvrKitWeights, and the headlight by
// uDvrKitHeadWeight.
uniform int uDvrLight;
uniform vec3 uDvrKitLights[4];
uniform vec4 uDvrKitWeights;
uniform float uDvrKitHeadWeight;
// For the ray (dvrBeginRay), world space, unit: under the directional light its half vector between
// uLightDir and the direction towards the eye (0 where they are opposite: no highlight); under the
// kit the direction towards the eye itself (the kit's half vectors are taken where they are needed).
vec3 gDvrRayLightWorld = vec3(0.0);
// 2^-k while a pyramid level k is marched (raycast.comp's FCC_LOD path; 1 otherwise): its index space is
// level 0's scaled by 2^-k, so its gradient is 2^k times level 0's while its d is 2^-k times, and
// uNormalFromIndex (level 0's) needs the gradient scaled back.
float gDvrLevelScale = 1.0;
// march_fcc.glsl's or march_cc.glsl's: the reconstruction's index-space gradient at xyz in unit cell
// `cell` (xyz kept inside it, so the stencil stays inside the slot's halo).
vec3 dvrGradient(ivec3 cell, vec3 xyz);

// The shading at ray parameter t: (the emission's factor, the specular light), both from |cos|.
// uNormalFromIndex turns the index-space gradient into the world one, and d (index displacement per
// world unit) gives dot(world gradient, unit world direction).
vec2 dvrShadeAt(float t) {
  vec3 g = dvrGradient(gDvrCell, gDvrO + t * gDvrD);
  vec3 n = uNormalFromIndex * g;  // the world gradient, up to the level's scale
  float lenN = length(n), len = lenN * gDvrLevelScale;
  if (!(len > 0.0)) return vec2(1.0, 0.0);
  // Headlight: both angles the ray's (dot(g, d) is the world gradient along the unit world ray, the
  // same at every level, against len, level 0's length). Directional: n's angles with the light and
  // with the half vector (the level's scale cancels). The kit: both, per light.
  if (uDvrLight == 0) {
    float cHead = min(abs(dot(g, gDvrD)) / len, 1.0);
    return vec2(kDvrAmbient + (1.0 - kDvrAmbient) * cHead, uDvrSpecular > 0.0 ? uDvrSpecular * pow(cHead, uDvrSpecularPower) : 0.0);
  }
  if (uDvrLight == 1) {
    float cLight = min(abs(dot(n, uLightDir)) / lenN, 1.0), cHalf = min(abs(dot(n, gDvrRayLightWorld)) / lenN, 1.0);
    return vec2(kDvrAmbient + (1.0 - kDvrAmbient) * cLight, uDvrSpecular > 0.0 ? uDvrSpecular * pow(cHalf, uDvrSpecularPower) : 0.0);
  }
  // The kit: the headlight's terms and each directional light's, weighted.
  float cHead = min(abs(dot(g, gDvrD)) / len, 1.0);
  float diffuse = uDvrKitHeadWeight * cHead, specular = 0.0;
  if (uDvrSpecular > 0.0) specular = uDvrKitHeadWeight * pow(cHead, uDvrSpecularPower);
  for (int k = 0; k < 4; ++k) {
    diffuse += uDvrKitWeights[k] * min(abs(dot(n, uDvrKitLights[k])) / lenN, 1.0);
    if (uDvrSpecular > 0.0) {
      vec3 sum = uDvrKitLights[k] + gDvrRayLightWorld;
      float lenSum = length(sum);  // 0 where the light is opposite the eye: no highlight
      if (lenSum > 0.0) specular += uDvrKitWeights[k] * pow(min(abs(dot(n, sum)) / (lenN * lenSum), 1.0), uDvrSpecularPower);
    }
  }
  return vec2(kDvrAmbient + (1.0 - kDvrAmbient) * min(diffuse, 1.0), uDvrSpecular * specular);
}
#endif

// Called once a ray, before its cells, with the ray's unit world direction: gDvrRayLightWorld
// (nothing without shading).
void dvrBeginRay(vec3 dirWorld) {
#if FCC_DVR_SHADING
  vec3 sum = uLightDir - dirWorld;
  gDvrRayLightWorld = uDvrLight == 2 ? -dirWorld : (dot(sum, sum) > 0.0 ? normalize(sum) : vec3(0.0));
#endif
}

// What one integrateCell hands the next in the walk of a brick (march_fcc.glsl's chain of pieces; the
// other lattices leave it at kDvrCarryNone): the entry piece of the cell the walk finds next along the
// ray, in Taylor form about that cell's start. kDvrCarryExit: the last cell's exit piece with the jump
// across the face between them, good only for the next cell in the walk (the walk drops it when it
// passes over a cell). kDvrCarryEntry: gathered by a round that did not integrate its cell, which the
// walk keeps for the next round.
const int kDvrCarryNone = 0, kDvrCarryExit = 1, kDvrCarryEntry = 2;
struct DvrCarry {
  vec4 taylor;
  int state;
};
DvrCarry gDvrCarry = DvrCarry(vec4(0.0), kDvrCarryNone);
// Set by raycast.comp's walk before each integrateCell: the axis of the face through which the ray
// leaves the cell (the walk's next step), and the first unit cell of the brick walked.
int gDvrExitAxis = 0;
vec2 gDvrCellBounds = vec2(0.0);  // the cell's slot bounds (for a measurement knob only)
ivec3 gDvrBrickCellLo = ivec3(0);

// Called by integrateCell before its segments: what dvrShadeAt needs (nothing without shading).
void dvrBeginCell(ivec3 cell, vec3 o, vec3 d) {
#if FCC_DVR_SHADING
  gDvrCell = cell;
  gDvrO = o;
  gDvrD = d;
#endif
}

// A value's place in the table, in entries. NaN (a damaged file's samples) is entry 0, as on the CPU
// (TransferTable::position). GLSL promises nothing for NaN in clamp, min or max: NVIDIA's clamp gave
// the last entry (RenderDvr.NanSamplesAreTheTablesFirstEntryAsOnTheCpu on the H200, 43.3 dB). Max
// first, then min: both drivers' min and max return the number where one operand is NaN (IEEE 754's
// minNum and maxNum: PTX's min/max.f32, LLVM's minnum/maxnum in llvmpipe), so NaN becomes 0, the max's
// number, at no cost; the NaN test holds it on both (docs/BENCHMARKS.md, session 24: an isnan cost the
// H200 5 % of a DVR frame). Measurement knobs (docs/RENDERER.md): FCC_TF_NAN=1 that isnan and the
// clamp, 0 the clamp alone.
#ifndef FCC_TF_NAN
#define FCC_TF_NAN 2
#endif
float tfPosition(float v) {
  float p = (v - uTfMin) * uTfScale;
#if FCC_TF_NAN == 2
  return min(max(p, 0.0), float(uTfSize - 1));
#elif FCC_TF_NAN
  return isnan(p) ? 0.0 : clamp(p, 0.0, float(uTfSize - 1));
#else
  return clamp(p, 0.0, float(uTfSize - 1));
#endif
}

vec4 tfLookup(float v) {
  float p = tfPosition(v);
  int i = min(int(p), uTfSize - 2);
  return mix(tfEntries[i], tfEntries[i + 1], p - float(i));
}

// The entries [uTfNonZeroFirst, uTfNonZeroEnd) hold every non-zero one; uTfInteriorZeros: a zero entry
// lies among them (viewer/DvrTableGpu.h's nonZeroSpan).
uniform int uTfNonZeroFirst, uTfNonZeroEnd, uTfInteriorZeros;
#ifndef FCC_TF_ZERO_SPAN
#define FCC_TF_ZERO_SPAN 1
#endif

// Whether every lookup in [lo, hi] has zero extinction (TransferTable::zeroOn): the entries first..last
// those lookups read miss the non-zero span, or (only where zeros lie inside it: no memory read
// otherwise, so a cell's skip waits for its bounds alone) the prefix counts say they hold none.
// FCC_TF_ZERO_SPAN=0 (a measurement knob): the prefix counts always. A NaN bound (a damaged file's
// samples, which lookups take as entry 0) stands for the whole table.
bool tfZeroOn(float lo, float hi) {
  bool ordered = lo <= hi;
  int first = ordered ? int(floor(tfPosition(lo))) : 0, last = ordered ? int(ceil(tfPosition(hi))) : uTfSize - 1;
#if FCC_TF_ZERO_SPAN
  if (last < uTfNonZeroFirst || first >= uTfNonZeroEnd) return true;
  if (uTfInteriorZeros == 0) return false;
#endif
  return tfPrefix[last + 1].x == tfPrefix[first].x;
}

// The largest and the smallest extinction of the entries first..last, those a lookup in [lo, hi]
// reads (TransferTable::maxExtinctionOn, minExtinctionOn): two overlapping power-of-two runs of the
// sparse table.
vec2 tfExtinctionOn(int first, int last) {
  int k = findMSB(last - first + 1);
  vec2 a = tfLevels[k * uTfSize + first], b = tfLevels[k * uTfSize + last - (1 << k) + 1];
  return vec2(max(a.x, b.x), min(a.y, b.y));
}

// Measurement knobs (FCCVDB_SHADER_DEFINES, docs/RENDERER.md): a fixed sub-step count per segment
// instead of the rule (0: the rule); 1: the rule until session 17 instead (at most 1/16 of optical
// depth and about one table entry of value change a sub-step), for comparison.
#ifndef FCC_DVR_FIXED_STEPS
#define FCC_DVR_FIXED_STEPS 0
#endif
#ifndef FCC_DVR_ENTRY_RULE
#define FCC_DVR_ENTRY_RULE 0
#endif
// 1: a cubic's sub-steps take the medium at their midpoint value and the rule its term for the value
// curving along the segment, as until session 21 (a measurement knob, for comparison; docs/DVR.md,
// "The value a sub-step takes").
#ifndef FCC_DVR_MIDPOINT
#define FCC_DVR_MIDPOINT 0
#endif
// Whether a cubic's sub-step count keeps the rule's curvature term (dvrSteps' `bend`): for midpoint
// values, and with gradient shading, whose headlight term follows the slope along the ray, which
// changes with the same second differences (the shade is taken at each sub-step's midpoint). Also a
// measurement knob: 1 gives an unshaded image the shaded one's sub-steps (test_render_dvr).
#ifndef FCC_DVR_BEND_TERM
#define FCC_DVR_BEND_TERM (FCC_DVR_MIDPOINT != 0 || FCC_DVR_SHADING != 0)
#endif
const bool kDvrBendTerm = bool(FCC_DVR_BEND_TERM);

// Sub-steps for a segment of `len` world units whose values lie in [lo, hi], at most `most`; 0 where
// every entry a lookup there reads has zero extinction (tfZeroOn's question, on the same entries, is a
// largest extinction of 0): one query decides both the skip and the count. `bend`: for sub-steps that
// take the medium at their midpoint value (or are shaded: kDvrBendTerm), the largest second
// difference of the segment's Bernstein coefficients (how far its value curves); else 0.
//
// The rule (docs/DVR.md, "How many sub-steps"): with n equal sub-steps the midpoint rule's error on a
// segment of optical depth at most tau = sigma_max len, whose values span E table entries, is about
//   K E / (8 sigma_max n^2)   (the table's kinks inside [lo, hi], slope changes summing to K per world
//                              unit, each crossed by a sub-step spanning E / n entries),
//   C tau / (12 n^2)          (the colour moving by C while the light is absorbed),
//   C (dsigma / sigma_max) / (12 n^2)   (the colour and the extinction moving together: emission is
//                              their product; dsigma the extinction's range there), and, for midpoint
//                              values only,
//   q (dsigma / sigma_max + C) / (4 n^2)   (the value curving along the segment: a sub-step's midpoint
//                              value is off its mean by up to bend / (4 n^2), q = bend / (hi - lo))
// relative to tau; their sum is held below kDvrTolerance. Where the table is linear over a sub-step's
// values, its mean value gives the optical depth exactly, however the value curves; a medium constant
// along the segment needs one sub-step, and no sub-step holds more than kDvrStepDepth of optical
// depth, where the estimate (second order in the sub-step) stays true.
int dvrSteps(float lo, float hi, float len, int most, float bend) {
  int first = int(floor(tfPosition(lo))), last = int(ceil(tfPosition(hi)));
  vec2 sigma = tfExtinctionOn(first, last);
  if (sigma.x <= 0.0) return 0;
#if FCC_DVR_FIXED_STEPS > 0
  return FCC_DVR_FIXED_STEPS;
#elif FCC_DVR_ENTRY_RULE
  return clamp(int(ceil(max(sigma.x * len * 16.0, (hi - lo) * uTfScale))), 1, most);
#else
  // The kinks crossed: entries strictly inside [lo, hi], i.e. first + 1 .. last - 1, but from entry 0
  // where lo lies below the table and to its last entry where hi lies past it (there the lookup is
  // constant: a kink at the end entry); the colour over the pairs first..last. Two reads: each entry
  // holds its own kink sum and the next's (none inside: a difference <= 0).
  uvec4 atFirst = tfPrefix[first], atLast = tfPrefix[last];
  bool below = (lo - uTfMin) * uTfScale < 0.0, beyond = (hi - uTfMin) * uTfScale > float(uTfSize - 1);
  int kinkSum = int(beyond ? atLast.w : atLast.y) - int(below ? atFirst.y : atFirst.w);
  float kinks = float(max(kinkSum, 0)) * uTfKinkQuantum;
  float colour = float(atLast.z - atFirst.z) * uTfColourQuantum;
  float tau = sigma.x * len, entries = (hi - lo) * uTfScale;
  float q = hi > lo ? bend / (hi - lo) : 0.0, spread = (sigma.x - sigma.y) / sigma.x;
  float n2 = (kinks * entries / (8.0 * sigma.x) + colour * (tau + spread) / 12.0 + 0.25 * q * (spread + colour)) / kDvrTolerance;
  // In float first: a huge (or NaN) count becomes `most`, not an undefined int.
  float n = ceil(max(tau / kDvrStepDepth, sqrt(n2)));
  return n < float(most) ? max(int(n), 1) : most;
#endif
}

// The largest second difference of Bernstein coefficients b (dvrSteps' `bend`).
float dvrBend(vec4 b) { return max(abs(b.x - 2.0 * b.y + b.z), abs(b.y - 2.0 * b.z + b.w)); }

// 1 - exp(-x) for x >= 0 without float's cancellation at small x (GLSL has no expm1): below 1/64 its
// series to x^3 (relative error at most x^3 / 24 < 1.6e-7); above, the difference (relative rounding
// at most about 2^-24 / x < 3.8e-6). Many thin sub-steps would otherwise each lose up to 2^-24 of
// opacity.
float dvrOpacity(float x) { return x < 0.015625 ? x * (1.0 - x * (0.5 - x * (1.0 / 6.0))) : 1.0 - exp(-x); }

// One sub-step [ta, ta + h] at value v: composited exactly for the medium held constant.
void dvrComposite(float v, float ta, float h, inout DvrState st) {
  vec4 e = tfLookup(v);
#if FCC_DVR_COUNT == 1
  st.color.b += 1.0;
#endif
  if (e.a <= 0.0) return;  // zero extinction emits nothing either (premultiplied entries)
  float a = dvrOpacity(e.a * h);
#if FCC_DVR_COUNT || FCC_DVR_CLOCK
#elif FCC_DVR_SHADING
  vec2 shade = dvrShadeAt(ta + 0.5 * h);
  st.color += st.transmittance * (e.rgb / e.a) * a * shade.x;
  st.color += st.transmittance * a * shade.y;  // white light: 0 without the specular term
#else
  st.color += st.transmittance * (e.rgb / e.a) * a;
#endif
  float before = st.transmittance;
  st.transmittance -= st.transmittance * a;  // not T (1 - a): 1 - a would round a thin sub-step's a
#if !FCC_DVR_CLOCK
  if (isinf(st.depthHalf) && st.transmittance <= 0.5) st.depthHalf = ta + log(2.0 * before) / e.a;
#endif
}

// The segment [s0, s1] of the ray where the field is the cubic with Bernstein coefficients bz. Returns
// true once the ray is opaque enough to stop.
bool dvrSegment3(vec4 bz, float s0, float s1, inout DvrState st) {
  float lo = min(min(bz.x, bz.y), min(bz.z, bz.w)), hi = max(max(bz.x, bz.y), max(bz.z, bz.w));
  int n = dvrSteps(lo, hi, s1 - s0, kDvrMaxSteps, kDvrBendTerm ? dvrBend(bz) : 0.0);
  if (n == 0) return false;
  float h = (s1 - s0) / float(n), w = 1.0 / float(n);
  for (int i = 0; i < n; ++i) {
    float um = (float(i) + 0.5) / float(n);
    dvrComposite(FCC_DVR_MIDPOINT != 0 ? fcc_bernstein3(bz, um) : fcc_bernstein3_mean(bz, um, w), s0 + float(i) * h, h, st);
    if (st.transmittance <= uStopTransmittance) return true;
  }
  return false;
}

// Where tm lies in [a, b] as a parameter in [0, 1]; 0 for an empty span (a chord an ulp long can put a
// sub-step's midpoint on its end: no 0 / 0).
float dvrSpanParameter(float tm, float a, float b) { return b > a ? clamp((tm - a) / (b - a), 0.0, 1.0) : 0.0; }

// Three consecutive cubic segments [t0, ta], [ta, tb], [tb, t1] (Bernstein coefficients b0, b1, b2;
// empty ones allowed) as one for the sub-step rule: their union's hull and the whole length
// (march_fcc.glsl: a unit cell's chord of the box spline). A sub-step's value is the mean of the
// piecewise cubic over it, from its primitive at the sub-step's ends, whatever pieces it spans.
bool dvrChord3(vec4 b0, vec4 b1, vec4 b2, float t0, float ta, float tb, float t1, inout DvrState st) {
  vec4 lo4 = min(min(b0, b1), b2), hi4 = max(max(b0, b1), b2);
  int n = dvrSteps(min(min(lo4.x, lo4.y), min(lo4.z, lo4.w)), max(max(hi4.x, hi4.y), max(hi4.z, hi4.w)), t1 - t0,
                   FCC_DVR_CHORD_MAX_STEPS, kDvrBendTerm ? max(max(dvrBend(b0), dvrBend(b1)), dvrBend(b2)) : 0.0);
  if (n == 0 || !(t1 > t0)) return false;
  float h = (t1 - t0) / float(n);
#if FCC_DVR_MIDPOINT
  for (int i = 0; i < n; ++i) {
    float ts = t0 + float(i) * h, tm = ts + 0.5 * h;
    float v = tm < ta ? fcc_bernstein3(b0, dvrSpanParameter(tm, t0, ta))
                      : (tm < tb ? fcc_bernstein3(b1, dvrSpanParameter(tm, ta, tb)) : fcc_bernstein3(b2, dvrSpanParameter(tm, tb, t1)));
    dvrComposite(v, ts, h, st);
    if (st.transmittance <= uStopTransmittance) return true;
  }
#else
  // The primitive V(t) of (value - vRef) from t0, per piece in power form (vRef, the entry value, keeps
  // V's differences free of a large offset); vA = V(ta), vB = V(tb).
  float vRef = b0.x;
  vec4 p0 = fcc_bernstein3_primitive(b0 - vRef), p1 = fcc_bernstein3_primitive(b1 - vRef),
       p2 = fcc_bernstein3_primitive(b2 - vRef);
  float vA = (ta - t0) * fcc_primitive3_at(p0, 1.0), vB = vA + (tb - ta) * fcc_primitive3_at(p1, 1.0);
  float ts = t0, vBefore = 0.0;  // the sub-step's start and V there
  for (int i = 0; i < n; ++i) {
    float te = i + 1 < n ? t0 + float(i + 1) * h : t1;
    bool first = te < ta, second = te < tb;
    vec4 p = first ? p0 : (second ? p1 : p2);
    float sa = first ? t0 : (second ? ta : tb), sb = first ? ta : (second ? tb : t1), base = first ? 0.0 : (second ? vA : vB);
    float vAfter = base + (sb - sa) * fcc_primitive3_at(p, dvrSpanParameter(te, sa, sb));
    // (A sub-step shorter than float can tell, te = ts: the entry value, not 0 / 0.)
    dvrComposite(vRef + (te > ts ? (vAfter - vBefore) / (te - ts) : 0.0), ts, h, st);
    ts = te;
    vBefore = vAfter;
    if (st.transmittance <= uStopTransmittance) return true;
  }
#endif
  return false;
}

// The same for a polynomial of degree 9 (tricubic).
bool dvrSegment9(FccBernstein9 p, float s0, float s1, inout DvrState st) {
  float lo = p.b[0], hi = p.b[0], bend = 0.0;
  for (int i = 1; i <= p.n; ++i) {
    lo = min(lo, p.b[i]);
    hi = max(hi, p.b[i]);
    if (i >= 2) bend = max(bend, abs(p.b[i] - 2.0 * p.b[i - 1] + p.b[i - 2]));
  }
  // A degree-p polynomial's second derivative is p (p - 1) times its Bernstein second differences', a
  // cubic's 6: scaled to the cubic's measure.
  bend *= float(p.n * (p.n - 1)) / 6.0;
  int n = dvrSteps(lo, hi, s1 - s0, kDvrMaxSteps, bend);
  if (n == 0) return false;
  float h = (s1 - s0) / float(n);
  for (int i = 0; i < n; ++i) {
    dvrComposite(fcc_bernstein9_at(p, (float(i) + 0.5) / float(n)), s0 + float(i) * h, h, st);
    if (st.transmittance <= uStopTransmittance) return true;
  }
  return false;
}
