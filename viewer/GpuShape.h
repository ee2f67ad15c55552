// How many SMs the GPU has and how many warps an SM can hold, where the driver tells a shader
// (GL_NV_shader_thread_group: NVIDIA): the raycaster's persistent work groups (RenderOptions::
// persistentGroups, shaders/raycast.comp's FCC_PERSISTENT_GROUPS) are as many as fill every warp slot.
#pragma once

namespace fcc::render {

struct GpuShape {
  int sms = 0;           // 0: not told (no GL_NV_shader_thread_group)
  int warpsPerSm = 0;    // the most warps an SM holds
};

// Asked of the current context once per process (a compute shader writes gl_SMCountNV and
// gl_WarpsPerSMNV) and kept. Needs a current OpenGL 4.5 context.
GpuShape currentGpuShape();

}  // namespace fcc::render
