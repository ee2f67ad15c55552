// Keeping the GPU busy before a measurement: a GPU that has idled runs its first work at lower clocks
// (the H200's first streaming frames were 2-3x slower on a machine's first run, docs/BENCHMARKS.md),
// so a benchmark that measures frames, not clock ramps, warms the GPU first. The work is arithmetic in
// a compute shader: no data is read and no cache the measurement depends on (brick pool, host cache,
// file pages) is touched. Needs a current OpenGL 4.5 context.
#pragma once

namespace fcc::render {

// Dispatches arithmetic and waits for it until `seconds` of wall time have passed (at least one
// dispatch when seconds > 0; none otherwise). Returns the dispatches made.
int warmUpGpu(double seconds);

}  // namespace fcc::render
