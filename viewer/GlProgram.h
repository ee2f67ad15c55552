// OpenGL compute programs, storage buffers and textures (needs a current 4.5 context, e.g. fcc::EglContext).
//
//   fcc::GlProgram p = fcc::GlProgram::compute(fcc::embedded::shaders("shaders/spline_eval.comp"),
//                                              "shaders/spline_eval.comp");
//   fcc::GlBuffer points(pts);  points.bindBase(GL_SHADER_STORAGE_BUFFER, 0);  ...
//   p.use();  glUniform1ui(p.uniformLocation("uCount"), n);
//   p.dispatch("spline evaluation", n);   // ceil(n / local_size_x) groups, then a barrier
#pragma once

#include <epoxy/gl.h>

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "sparse/Error.h"

namespace fcc {

// An OpenGL failure: a shader that does not compile or link (with its info log), or a GL error code.
struct GlError : Error {
  using Error::Error;
};

// "GL_INVALID_OPERATION" for 0x0502, ...
const char* glErrorName(GLenum code);
// Throws GlError "<doing>: GL_INVALID_VALUE" if glGetError() reports anything (all queued errors are
// drained and named).
void checkGl(std::string_view doing);

// `source` with `defines` ("#define NAME VALUE" lines) inserted after its first line (the #version).
std::string withDefines(std::string_view source, const std::string& defines);

class GlProgram {
 public:
  // Compiles and links one compute shader. `name` labels errors. Throws GlError: "compiling compute
  // shader '<name>' failed:\n<info log>" (or linking).
  static GlProgram compute(std::string_view source, std::string_view name = "compute shader");
  // Compiles and links a vertex and a fragment shader (errors as compute()).
  static GlProgram graphics(std::string_view vertexSource, std::string_view fragmentSource, std::string_view name);

  GlProgram() = default;
  GlProgram(GlProgram&& other) noexcept;
  GlProgram& operator=(GlProgram&& other) noexcept;
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;
  ~GlProgram();

  GLuint id() const { return id_; }
  const std::string& name() const { return name_; }
  void use() const;
  // The location of an active uniform; throws GlError naming it if the program has no such uniform.
  GLint uniformLocation(const char* uniform) const;
  std::array<GLint, 3> localSize() const;  // GL_COMPUTE_WORK_GROUP_SIZE

  // Binds the program, dispatches ceil(count / local_size_x) groups (the shader checks its bound),
  // then issues a barrier so that later buffer reads and shader reads see the writes. Errors name
  // `description`.
  void dispatch(std::string_view description, GLuint count) const;

 private:
  GLuint id_ = 0;
  std::string name_;
};

// An immutable-storage buffer object (glNamedBufferStorage, GL_DYNAMIC_STORAGE_BIT).
class GlBuffer {
 public:
  explicit GlBuffer(std::size_t bytes, const void* data = nullptr);
  template <class T>
  explicit GlBuffer(const std::vector<T>& data) : GlBuffer(data.size() * sizeof(T), data.data()) {}
  GlBuffer(GlBuffer&& other) noexcept;
  GlBuffer& operator=(GlBuffer&& other) noexcept;
  GlBuffer(const GlBuffer&) = delete;
  GlBuffer& operator=(const GlBuffer&) = delete;
  ~GlBuffer();

  GLuint id() const { return id_; }
  std::size_t size() const { return bytes_; }
  void bindBase(GLenum target, GLuint index) const;  // e.g. GL_SHADER_STORAGE_BUFFER, binding = index
  void read(void* out, std::size_t bytes, std::size_t offset = 0) const;
  template <class T>
  void read(std::vector<T>& out) const {
    read(out.data(), out.size() * sizeof(T));
  }
  void write(const void* data, std::size_t bytes, std::size_t offset = 0);
  template <class T>
  void write(const std::vector<T>& data) {
    write(data.data(), data.size() * sizeof(T));
  }
  void clear();  // every byte zero

 private:
  GLuint id_ = 0;
  std::size_t bytes_ = 0;
};

// A small host-visible buffer (persistently mapped) into which results are copied on the GPU and read
// after a fence: the CPU waits only for the commands before the copy, and nothing is copied back
// through the driver (what glGetBufferSubData does).
class GlReadbackBuffer {
 public:
  explicit GlReadbackBuffer(std::size_t bytes);
  GlReadbackBuffer(const GlReadbackBuffer&) = delete;
  GlReadbackBuffer& operator=(const GlReadbackBuffer&) = delete;
  ~GlReadbackBuffer();
  // Reading in two halves, so the CPU can go on while the GPU gets there: copy() queues a copy of
  // `bytes` of `source` from `offset` (after every command so far), wait() waits for it and returns
  // the bytes (valid until the next copy()).
  void copy(const GlBuffer& source, std::size_t bytes, std::size_t offset = 0);
  const void* wait();

 private:
  GLsync fence_ = nullptr;
  GLuint id_ = 0;
  std::size_t bytes_ = 0;
  const void* mapped_ = nullptr;
};

// The mirror of GlReadbackBuffer: a host-visible buffer (persistently mapped, write-only) the CPU
// fills and the GPU copies from, in `segments` equal parts used in turn, so the CPU fills one while
// the GPU may still copy from the others. begin() waits until the next part's previous copies are done
// and returns it; after issuing the copies that read it, end() fences them.
class GlUploadBuffer {
 public:
  GlUploadBuffer(std::size_t segmentBytes, int segments);
  GlUploadBuffer(const GlUploadBuffer&) = delete;
  GlUploadBuffer& operator=(const GlUploadBuffer&) = delete;
  ~GlUploadBuffer();
  GLuint id() const { return id_; }
  std::size_t segmentBytes() const { return segmentBytes_; }
  // The segment to fill: its bytes, and its offset in the buffer (for the copies that read it).
  void* begin(std::size_t& offset);
  void end();

 private:
  GLuint id_ = 0;
  std::size_t segmentBytes_ = 0;
  std::vector<GLsync> fences_;  // one a segment; null when nothing reads it
  std::size_t next_ = 0;
  void* mapped_ = nullptr;
};

// A 2D texture with immutable storage of one level (glTextureStorage2D), e.g. GL_RGBA32F, used as a
// compute shader image.
class GlTexture2D {
 public:
  GlTexture2D() = default;
  GlTexture2D(GLenum internalFormat, int width, int height);
  GlTexture2D(GlTexture2D&& other) noexcept;
  GlTexture2D& operator=(GlTexture2D&& other) noexcept;
  GlTexture2D(const GlTexture2D&) = delete;
  GlTexture2D& operator=(const GlTexture2D&) = delete;
  ~GlTexture2D();

  GLuint id() const { return id_; }
  int width() const { return width_; }
  int height() const { return height_; }
  void bindImage(GLuint unit, GLenum access) const;
  // Fills every texel with `value` (components as the format has them).
  void clear(const float* value);
  // All texels as floats, `components` per texel (GL_RED: 1, GL_RGBA: 4), row 0 first.
  std::vector<float> read(GLenum format, int components) const;

 private:
  GLuint id_ = 0;
  GLenum format_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace fcc
