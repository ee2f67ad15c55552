#include "GlProgram.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <utility>

namespace fcc {

namespace {

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\0' || s.back() == '\n' || s.back() == ' ' || s.back() == '\r')) s.pop_back();
  return s;
}

std::string shaderLog(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(size_t(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, GLsizei(log.size()), nullptr, log.data());
  return trimmed(log);
}

std::string programLog(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(size_t(std::max(length, 1)), '\0');
  glGetProgramInfoLog(program, GLsizei(log.size()), nullptr, log.data());
  return trimmed(log);
}

}  // namespace

const char* glErrorName(GLenum code) {
  switch (code) {
    case GL_NO_ERROR: return "GL_NO_ERROR";
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST";
    default: return "GL error";
  }
}

void checkGl(std::string_view doing) {
  std::string names;
  for (int i = 0; i < 16; ++i) {  // bounded: a lost context may report errors forever
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR) break;
    if (!names.empty()) names += ", ";
    names += glErrorName(e);
  }
  if (!names.empty()) throw GlError(std::string(doing) + ": " + names);
}

namespace {

// Compiles one stage; throws GlError "compiling <kind> shader '<name>' failed:\n<log>".
GLuint compileStage(GLenum stage, const char* kind, std::string_view source, const std::string& name) {
  if (source.empty()) throw GlError(std::string(kind) + " shader '" + name + "' has no source text");
  const GLuint shader = glCreateShader(stage);
  if (shader == 0) throw GlError("glCreateShader failed for the " + std::string(kind) + " shader '" + name + "'");
  const GLchar* text = source.data();
  const GLint length = GLint(source.size());
  glShaderSource(shader, 1, &text, &length);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = shaderLog(shader);
    glDeleteShader(shader);
    throw GlError("compiling " + std::string(kind) + " shader '" + name + "' failed:\n" + log);
  }
  return shader;
}

// Links the stages into a program (and frees them); throws GlError naming `what`.
GLuint linkStages(const std::vector<GLuint>& shaders, const std::string& what) {
  const GLuint id = glCreateProgram();
  for (GLuint shader : shaders) glAttachShader(id, shader);
  glLinkProgram(id);
  for (GLuint shader : shaders) {
    glDetachShader(id, shader);
    glDeleteShader(shader);
  }
  GLint ok = GL_FALSE;
  glGetProgramiv(id, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = programLog(id);
    glDeleteProgram(id);
    throw GlError("linking " + what + " failed:\n" + log);
  }
  checkGl("building " + what);
  return id;
}

}  // namespace

GlProgram GlProgram::compute(std::string_view source, std::string_view name) {
  // FCCVDB_DUMP_SHADERS=DIR: each compute program's whole source, as compiled, to DIR/N_NAME (for
  // tools/shader-stats, which asks a Vulkan driver what the program compiles to; GL does not say).
  if (const char* dir = std::getenv("FCCVDB_DUMP_SHADERS")) {
    static int dumped = 0;
    std::string base(name);
    for (char& c : base)
      if (c == '/') c = '_';
    std::error_code ignored;  // a folder that cannot be made fails the write below, with its path
    std::filesystem::create_directories(dir, ignored);
    const std::string path = std::string(dir) + "/" + std::to_string(dumped++) + "_" + base;
    std::ofstream out(path);
    out << source;
    if (!out) throw GlError("FCCVDB_DUMP_SHADERS: cannot write " + path);
  }
  GlProgram p;
  p.name_ = std::string(name);
  p.id_ = linkStages({compileStage(GL_COMPUTE_SHADER, "compute", source, p.name_)}, "compute shader '" + p.name_ + "'");
  return p;
}

GlProgram GlProgram::graphics(std::string_view vertexSource, std::string_view fragmentSource, std::string_view name) {
  GlProgram p;
  p.name_ = std::string(name);
  p.id_ = linkStages({compileStage(GL_VERTEX_SHADER, "vertex", vertexSource, p.name_),
                      compileStage(GL_FRAGMENT_SHADER, "fragment", fragmentSource, p.name_)},
                     "program '" + p.name_ + "'");
  return p;
}

GlProgram::GlProgram(GlProgram&& other) noexcept
    : id_(std::exchange(other.id_, 0)), name_(std::move(other.name_)) {}

GlProgram& GlProgram::operator=(GlProgram&& other) noexcept {
  if (this != &other) {
    if (id_) glDeleteProgram(id_);
    id_ = std::exchange(other.id_, 0);
    name_ = std::move(other.name_);
  }
  return *this;
}

GlProgram::~GlProgram() {
  if (id_) glDeleteProgram(id_);
}

void GlProgram::use() const { glUseProgram(id_); }

GLint GlProgram::uniformLocation(const char* uniform) const {
  const GLint location = glGetUniformLocation(id_, uniform);
  if (location < 0) throw GlError("shader program '" + name_ + "' has no active uniform '" + uniform + "'");
  return location;
}

std::array<GLint, 3> GlProgram::localSize() const {
  std::array<GLint, 3> size{1, 1, 1};
  glGetProgramiv(id_, GL_COMPUTE_WORK_GROUP_SIZE, size.data());
  return size;
}

void GlProgram::dispatch(std::string_view description, GLuint count) const {
  if (count == 0) return;
  const GLuint local = GLuint(std::max(localSize()[0], 1));
  glUseProgram(id_);
  glDispatchCompute((count + local - 1) / local, 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  checkGl(std::string(description) + ": dispatching '" + name_ + "' over " + std::to_string(count) + " items");
}

GlBuffer::GlBuffer(std::size_t bytes, const void* data) : bytes_(bytes) {
  glCreateBuffers(1, &id_);
  // Zero-sized storage is an error; keep one byte so that empty inputs still bind.
  glNamedBufferStorage(id_, GLsizeiptr(bytes == 0 ? 1 : bytes), bytes == 0 ? nullptr : data, GL_DYNAMIC_STORAGE_BIT);
  checkGl("creating a " + std::to_string(bytes) + "-byte buffer");
}

GlBuffer::GlBuffer(GlBuffer&& other) noexcept
    : id_(std::exchange(other.id_, 0)), bytes_(std::exchange(other.bytes_, 0)) {}

GlBuffer& GlBuffer::operator=(GlBuffer&& other) noexcept {
  if (this != &other) {
    if (id_) glDeleteBuffers(1, &id_);
    id_ = std::exchange(other.id_, 0);
    bytes_ = std::exchange(other.bytes_, 0);
  }
  return *this;
}

GlBuffer::~GlBuffer() {
  if (id_) glDeleteBuffers(1, &id_);
}

void GlBuffer::bindBase(GLenum target, GLuint index) const { glBindBufferBase(target, index, id_); }

void GlBuffer::read(void* out, std::size_t bytes, std::size_t offset) const {
  if (bytes == 0) return;
  if (offset + bytes > bytes_)
    throw GlError("reading " + std::to_string(bytes) + " bytes at " + std::to_string(offset) + " of a " +
                  std::to_string(bytes_) + "-byte buffer");
  glGetNamedBufferSubData(id_, GLintptr(offset), GLsizeiptr(bytes), out);
  checkGl("reading a buffer");
}

void GlBuffer::write(const void* data, std::size_t bytes, std::size_t offset) {
  if (bytes == 0) return;
  if (offset + bytes > bytes_)
    throw GlError("writing " + std::to_string(bytes) + " bytes at " + std::to_string(offset) + " of a " +
                  std::to_string(bytes_) + "-byte buffer");
  glNamedBufferSubData(id_, GLintptr(offset), GLsizeiptr(bytes), data);
  checkGl("writing a buffer");
}

void GlBuffer::clear() {
  const GLuint zero = 0;
  glClearNamedBufferData(id_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  checkGl("clearing a buffer");
}

namespace {
// Waits for `fence` however long it takes (the first wait flushes the commands before it), deletes it
// and nulls it; GlError naming `what` if the wait failed.
void waitAndDelete(GLsync& fence, const char* what) {
  GLenum status = glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 1'000'000'000);
  while (status == GL_TIMEOUT_EXPIRED) status = glClientWaitSync(fence, 0, 1'000'000'000);
  glDeleteSync(fence);
  fence = nullptr;
  if (status == GL_WAIT_FAILED) throw GlError(std::string("waiting for ") + what + " failed");
}
}  // namespace

GlReadbackBuffer::GlReadbackBuffer(std::size_t bytes) : bytes_(bytes) {
  constexpr GLbitfield kFlags = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
  glCreateBuffers(1, &id_);
  glNamedBufferStorage(id_, GLsizeiptr(bytes), nullptr, kFlags | GL_CLIENT_STORAGE_BIT);
  mapped_ = glMapNamedBufferRange(id_, 0, GLsizeiptr(bytes), kFlags);
  checkGl("creating a " + std::to_string(bytes) + "-byte read-back buffer");
  if (!mapped_) throw GlError("mapping a " + std::to_string(bytes) + "-byte read-back buffer failed");
}

GlReadbackBuffer::~GlReadbackBuffer() {
  if (fence_) glDeleteSync(fence_);
  if (id_) {
    glUnmapNamedBuffer(id_);
    glDeleteBuffers(1, &id_);
  }
}

void GlReadbackBuffer::copy(const GlBuffer& source, std::size_t bytes, std::size_t offset) {
  if (bytes > bytes_ || offset + bytes > source.size())
    throw GlError("reading back " + std::to_string(bytes) + " bytes at " + std::to_string(offset) + " of a " +
                  std::to_string(source.size()) + "-byte buffer into " + std::to_string(bytes_));
  if (fence_) glDeleteSync(fence_);
  glCopyNamedBufferSubData(source.id(), id_, GLintptr(offset), 0, GLsizeiptr(bytes));
  fence_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  glFlush();  // submitted now: the GPU gets on with it while the CPU does other work
}

const void* GlReadbackBuffer::wait() {
  if (!fence_) throw GlError("waiting for a read-back that was never started");
  waitAndDelete(fence_, "a read-back");
  checkGl("reading back a buffer");
  return mapped_;
}

std::string withDefines(std::string_view source, const std::string& defines) {
  std::string s(source);
  const auto eol = s.find('\n');
  s.insert(eol == std::string::npos ? s.size() : eol + 1, defines);
  return s;
}

GlUploadBuffer::GlUploadBuffer(std::size_t segmentBytes, int segments)
    // Segments start at multiples of 256 bytes: any GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT allows that.
    : segmentBytes_((segmentBytes + 255) / 256 * 256), fences_(std::size_t(std::max(segments, 1)), nullptr) {
  const std::size_t bytes = segmentBytes_ * fences_.size();
  constexpr GLbitfield kFlags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
  glCreateBuffers(1, &id_);
  glNamedBufferStorage(id_, GLsizeiptr(bytes), nullptr, kFlags);
  mapped_ = glMapNamedBufferRange(id_, 0, GLsizeiptr(bytes), kFlags);
  checkGl("creating a " + std::to_string(bytes) + "-byte upload buffer");
  if (!mapped_) throw GlError("mapping a " + std::to_string(bytes) + "-byte upload buffer failed");
}

GlUploadBuffer::~GlUploadBuffer() {
  for (GLsync fence : fences_)
    if (fence) glDeleteSync(fence);
  if (id_) {
    glUnmapNamedBuffer(id_);
    glDeleteBuffers(1, &id_);
  }
}

void* GlUploadBuffer::begin(std::size_t& offset) {
  if (fences_[next_]) waitAndDelete(fences_[next_], "an upload buffer");
  offset = next_ * segmentBytes_;
  return static_cast<char*>(mapped_) + offset;
}

void GlUploadBuffer::end() {
  fences_[next_] = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  next_ = (next_ + 1) % fences_.size();
}

GlTexture2D::GlTexture2D(GLenum internalFormat, int width, int height)
    : format_(internalFormat), width_(width), height_(height) {
  glCreateTextures(GL_TEXTURE_2D, 1, &id_);
  glTextureStorage2D(id_, 1, internalFormat, width, height);
  checkGl("creating a " + std::to_string(width) + "x" + std::to_string(height) + " texture");
}

GlTexture2D::GlTexture2D(GlTexture2D&& other) noexcept
    : id_(std::exchange(other.id_, 0)), format_(other.format_), width_(other.width_), height_(other.height_) {}

GlTexture2D& GlTexture2D::operator=(GlTexture2D&& other) noexcept {
  if (this != &other) {
    if (id_) glDeleteTextures(1, &id_);
    id_ = std::exchange(other.id_, 0);
    format_ = other.format_;
    width_ = other.width_;
    height_ = other.height_;
  }
  return *this;
}

GlTexture2D::~GlTexture2D() {
  if (id_) glDeleteTextures(1, &id_);
}

void GlTexture2D::bindImage(GLuint unit, GLenum access) const {
  glBindImageTexture(unit, id_, 0, GL_FALSE, 0, access, format_);
}

void GlTexture2D::clear(const float* value) {
  const GLenum format = format_ == GL_R32F ? GL_RED : GL_RGBA;
  glClearTexImage(id_, 0, format, GL_FLOAT, value);
  checkGl("clearing a texture");
}

std::vector<float> GlTexture2D::read(GLenum format, int components) const {
  std::vector<float> out(std::size_t(width_) * height_ * components);
  glGetTextureImage(id_, 0, format, GL_FLOAT, GLsizei(out.size() * sizeof(float)), out.data());
  checkGl("reading a texture");
  return out;
}

}  // namespace fcc
