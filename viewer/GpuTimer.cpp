#include "GpuTimer.h"

#include "GlProgram.h"

namespace fcc {

GpuInterval::GpuInterval() {
  glCreateQueries(GL_TIMESTAMP, 2, queries_);
  checkGl("creating GPU timestamp queries");
}

GpuInterval::~GpuInterval() { glDeleteQueries(2, queries_); }

void GpuInterval::begin() { glQueryCounter(queries_[0], GL_TIMESTAMP); }

void GpuInterval::end() { glQueryCounter(queries_[1], GL_TIMESTAMP); }

double GpuInterval::seconds() const {
  GLuint64 t0 = 0, t1 = 0;
  glGetQueryObjectui64v(queries_[0], GL_QUERY_RESULT, &t0);
  glGetQueryObjectui64v(queries_[1], GL_QUERY_RESULT, &t1);
  return t1 > t0 ? double(t1 - t0) * 1e-9 : 0.0;
}

}  // namespace fcc
