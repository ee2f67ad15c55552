#include "GpuShape.h"

#include <epoxy/gl.h>

#include <cstring>
#include <mutex>

#include "GlProgram.h"

namespace fcc::render {
namespace {

bool contextHasExtension(const char* name) {
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i) {
    const char* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
    if (e && std::strcmp(e, name) == 0) return true;
  }
  return false;
}

GpuShape askTheDriver() {
  if (!contextHasExtension("GL_NV_shader_thread_group")) return {};
  const GlProgram program = GlProgram::compute(R"(#version 450 core
#extension GL_NV_shader_thread_group : require
layout(local_size_x = 1) in;
layout(std430, binding = 0) writeonly buffer Shape { uint shape[2]; };
void main() {
  shape[0] = gl_SMCountNV;
  shape[1] = gl_WarpsPerSMNV;
}
)", "the GPU's shape");
  GlBuffer out(2 * sizeof(GLuint));
  out.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  program.dispatch("the GPU's shape", 1);
  GLuint shape[2] = {0, 0};
  out.read(shape, sizeof shape);
  return GpuShape{int(shape[0]), int(shape[1])};
}

}  // namespace

GpuShape currentGpuShape() {
  static std::once_flag once;
  static GpuShape shape;
  std::call_once(once, [] { shape = askTheDriver(); });
  return shape;
}

}  // namespace fcc::render
