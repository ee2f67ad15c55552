#!/usr/bin/env python3
"""Parts of the DVR program alone, for their register counts (tools/shader-stats/README.md).

  isolated_mains.py DUMPED_RAYCAST_COMP OUTDIR

DUMPED_RAYCAST_COMP: raycast.comp as the renderer compiles it for DVR (FCCVDB_DUMP_SHADERS). Writes
OUTDIR/NAME.comp, the program's text with its main() replaced by one that runs one part on one cell
of each pixel's ray: m1 a gather and the piece's cubic in Taylor form, m3 integrateCell (the chain's
cell), m4 integrateCellPieces (both end pieces gathered), m5 a chord's sub-steps (dvrChord3) alone.
Compile each with make_variants.sh (NAME=). Session 21: m1 55, m3 64, m4 72, m5 37 registers.
"""
import sys
src = open(sys.argv[1]).read()
outdir = sys.argv[2]
head=src[:src.index('void main() {')]
prologue='''void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  vec2 ndc = (vec2(pixel) + 0.5) / vec2(uResolution) * 2.0 - 1.0;
  vec3 dirWorld = normalize(uForward + ndc.x * uRight - ndc.y * uUp);
  vec3 o = (uIndexFromWorld * vec4(uEye, 1.0)).xyz;
  vec3 d = mat3(uIndexFromWorld) * dirWorld;
  ivec3 cell = ivec3(floor(o + 10.0 * d));
  uint slot = pageEntries[pixel.x];
  selectSlot(slot, cell >> 4);
  float t0 = 9.5, t1 = 10.5;
'''
mains={
'm1': '''  FccFrame frame = fcc_locate(o + 10.0 * d);
  FccSamples samples = gatherStencil(frame);
  vec4 g = fcc_piece_taylor(fcc_cubic_t0(samples), frame, o, d, t1);
  imageStore(uColor, pixel, g);
}
''',
'm3': '''  DvrState st;
  st.color = vec3(0.0); st.transmittance = 1.0; st.depthHalf = 1.0/0.0;
  gDvrExitAxis = pixel.y % 3;
  gDvrBrickCellLo = cell & ~15;
  bool stop = integrateCell(cell, o, d, t0, t1, st);
  imageStore(uColor, pixel, vec4(st.color, stop ? 1.0 : st.transmittance));
}
''',
'm4': '''  DvrState st;
  st.color = vec3(0.0); st.transmittance = 1.0; st.depthHalf = 1.0/0.0;
  bool stop = integrateCellPieces(cell, o, d, t0, t1, st);
  imageStore(uColor, pixel, vec4(st.color, stop ? 1.0 : st.transmittance));
}
''',
'm5': '''  DvrState st;
  st.color = vec3(0.0); st.transmittance = 1.0; st.depthHalf = 1.0/0.0;
  vec4 b0 = vec4(o, t0), b1 = vec4(d, t1), b2 = b0 * b1;
  bool stop = dvrChord3(b0, b1, b2, t0, t0 + 0.3, t0 + 0.6, t1, st);
  imageStore(uColor, pixel, vec4(st.color, stop ? 1.0 : st.transmittance));
}
''',
}
for k,v in mains.items():
    open(f'{outdir}/{k}.comp', 'w').write(head+prologue+v)
