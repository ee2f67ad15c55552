#include "ProjectedTetrahedra.h"

#include <tbb/parallel_for.h>

#include <boost/sort/sort.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <string>

#include "GpuTimer.h"
#include "embedded_shaders.h"
#include "sparse/Error.h"

namespace fcc::render {
namespace {

// The GL state render() changes, put back as it was (the caller may draw with it next). Not the SSBO
// bindings nor the program: every program of the renderer binds itself and its buffers before it runs
// (and the program current before may be one deleted since, which glUseProgram would refuse).
class SavedGlState {
 public:
  SavedGlState() {
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer_);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFramebuffer_);
    glGetIntegerv(GL_VIEWPORT, viewport_);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertexArray_);
    glGetIntegerv(GL_BLEND_SRC_RGB, &blend_[0]);
    glGetIntegerv(GL_BLEND_DST_RGB, &blend_[1]);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &blend_[2]);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &blend_[3]);
    blendOn_ = glIsEnabled(GL_BLEND);
    depthOn_ = glIsEnabled(GL_DEPTH_TEST);
    cullOn_ = glIsEnabled(GL_CULL_FACE);
  }
  ~SavedGlState() {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, glIsFramebuffer(GLuint(framebuffer_)) ? GLuint(framebuffer_) : 0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, glIsFramebuffer(GLuint(readFramebuffer_)) ? GLuint(readFramebuffer_) : 0);
    glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
    glBindVertexArray(glIsVertexArray(GLuint(vertexArray_)) ? GLuint(vertexArray_) : 0);
    glBlendFuncSeparate(GLenum(blend_[0]), GLenum(blend_[1]), GLenum(blend_[2]), GLenum(blend_[3]));
    (blendOn_ ? glEnable : glDisable)(GL_BLEND);
    (depthOn_ ? glEnable : glDisable)(GL_DEPTH_TEST);
    (cullOn_ ? glEnable : glDisable)(GL_CULL_FACE);
  }
  SavedGlState(const SavedGlState&) = delete;
  SavedGlState& operator=(const SavedGlState&) = delete;

 private:
  GLint framebuffer_ = 0, readFramebuffer_ = 0, viewport_[4] = {}, vertexArray_ = 0, blend_[4] = {};
  GLboolean blendOn_ = GL_FALSE, depthOn_ = GL_FALSE, cullOn_ = GL_FALSE;
};

// As tetra.vert and tetra.frag read it (std430: vec4s only).
struct GpuTetrahedron {
  glm::vec4 vertex[4];
  glm::vec4 plane[4];
  glm::vec4 field;
};
static_assert(sizeof(GpuTetrahedron) == 9 * 16);

// Both cosets' values over a box of coset voxels: the sites of every brick with data, the background
// elsewhere (a brick without data holds it at all its sites).
class BccSites {
 public:
  // In core: at most this many coset voxels in the box of the bricks with data (2 GiB of floats for
  // both cosets), checked before anything is allocated.
  static constexpr std::size_t kMaxVoxels = std::size_t(1) << 28;

  explicit BccSites(const BrickSource& source) : background_(source.background()) {
    glm::ivec3 lo, hi;
    source.brickBox(lo, hi);
    if (glm::any(glm::lessThan(hi, lo))) return;
    const glm::dvec3 extent = 8.0 * glm::dvec3(hi - lo + 1) + 2.0 * kBccSlotLo;
    if (extent.x * extent.y * extent.z > double(kMaxVoxels))
      throw ValueError(source.path() + ": its bricks with data span " + std::to_string(int64_t(extent.x)) + " x " +
                       std::to_string(int64_t(extent.y)) + " x " + std::to_string(int64_t(extent.z)) +
                       " coset voxels; projected tetrahedra hold at most " + std::to_string(kMaxVoxels) + " in core");
    min_ = 8 * lo - kBccSlotLo;
    dims_ = glm::ivec3(extent);
    const std::size_t count = std::size_t(dims_.x) * dims_.y * dims_.z;
    for (auto& coset : values_) coset.assign(count, background_);
    std::vector<glm::ivec3> bricks;
    source.forEachVaryingBrick([&](const glm::ivec3& b, float, float) { bricks.push_back(b); });
    tbb::parallel_for(std::size_t(0), bricks.size(), std::size_t(16), [&](std::size_t first) {
      std::vector<LoadedBrick> chunk;
      for (std::size_t i = first; i < std::min(first + 16, bricks.size()); ++i) chunk.push_back(LoadedBrick{bricks[i], {}});
      source.decode(chunk);
      constexpr int kDim = kBccSlotDim;
      for (const LoadedBrick& b : chunk)
        for (int c = 0; c < 2; ++c)
          for (int z = 0; z < 8; ++z)
            for (int y = 0; y < 8; ++y)
              for (int x = 0; x < 8; ++x) {
                const glm::ivec3 m = 8 * b.brick + glm::ivec3(x, y, z);
                values_[c][index(m)] = b.halo[std::size_t(c) * kDim * kDim * kDim +
                                              (std::size_t(z + kBccSlotLo) * kDim + y + kBccSlotLo) * kDim + x + kBccSlotLo];
              }
    });
  }
  // The value at BCC site x (all coordinates even or all odd).
  float at(const glm::ivec3& x) const {
    const glm::ivec3 m = x >> 1;  // floor(x / 2): coset voxel of either coset
    const glm::ivec3 l = m - min_;
    if (glm::any(glm::lessThan(l, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(l, dims_))) return background_;
    return values_[x.x & 1][index(m)];
  }
  const glm::ivec3& min() const { return min_; }
  const glm::ivec3& dims() const { return dims_; }

 private:
  std::size_t index(const glm::ivec3& m) const {
    const glm::ivec3 l = m - min_;
    return (std::size_t(l.z) * dims_.y + l.y) * dims_.x + l.x;
  }
  float background_;
  glm::ivec3 min_{0}, dims_{0};
  std::vector<float> values_[2];
};

// Tetrahedron (a, b, c, d) with its values: planes, linear field and circumsphere.
void makeTetrahedron(const glm::ivec3 (&v)[4], const float (&f)[4], GpuTetrahedron& gpu, glm::vec4& sphere) {
  glm::dvec3 p[4];
  for (int i = 0; i < 4; ++i) {
    p[i] = glm::dvec3(v[i]);
    gpu.vertex[i] = glm::vec4(glm::vec3(p[i]), f[i]);
  }
  for (int i = 0; i < 4; ++i) {
    const glm::dvec3& a = p[(i + 1) % 4];
    const glm::dvec3& b = p[(i + 2) % 4];
    const glm::dvec3& c = p[(i + 3) % 4];
    glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
    if (glm::dot(n, p[i] - a) > 0.0) n = -n;  // outward: away from the opposite vertex
    gpu.plane[i] = glm::vec4(glm::vec3(n), float(glm::dot(n, a)));
  }
  // Rows: edges from vertex 0; the gradient solves edges * g = value differences.
  const glm::dmat3 edgesT(p[1] - p[0], p[2] - p[0], p[3] - p[0]);  // columns: the edges
  const glm::dmat3 edges = glm::transpose(edgesT);
  const glm::dvec3 g = glm::inverse(edges) * glm::dvec3(f[1] - f[0], f[2] - f[0], f[3] - f[0]);
  gpu.field = glm::vec4(glm::vec3(g), float(double(f[0]) - glm::dot(g, p[0])));
  // Circumcentre: 2 (p_i - p_0) . c = |p_i|^2 - |p_0|^2.
  const glm::dvec3 rhs(glm::dot(p[1], p[1]) - glm::dot(p[0], p[0]), glm::dot(p[2], p[2]) - glm::dot(p[0], p[0]),
                       glm::dot(p[3], p[3]) - glm::dot(p[0], p[0]));
  const glm::dvec3 centre = glm::inverse(2.0 * edges) * rhs;
  sphere = glm::vec4(glm::vec3(centre), float(glm::dot(centre - p[0], centre - p[0])));
}

// A finite float's bits as an unsigned key that sorts the floats largest first.
uint32_t largestFirstKey(float value) {
  uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  const uint32_t smallestFirst = (bits & 0x80000000u) ? ~bits : (bits | 0x80000000u);
  return ~smallestFirst;
}

}  // namespace

ProjectedTetrahedra::ProjectedTetrahedra(const BrickSource& source, Options options)
    : source_(source), options_(std::move(options)) {
  if (source.slotBlock() != SlotBlock::BccPacked || source.reconstruction().name != "barycentric")
    throw ValueError("projected tetrahedra draw a BCC dataset with the barycentric reconstruction (linear on its tetrahedra); " +
                     source.path() + " is drawn with " + std::string(source.reconstruction().name));
  if (!options_.transfer) throw ValueError("projected tetrahedra need a transfer function");
  const TransferTable& table = *options_.transfer;
  const BccSites sites(source);
  // The cube of every primary site 2m in the box, and one layer below it (its faces' tetrahedra reach
  // into the box); each cube owns the tetrahedra of its three upper faces: a face's four edges, each
  // with the centres of the two cubes on either side (12 a cube).
  const glm::ivec3 cubeMin = sites.min() - 1, cubeDims = sites.dims();
  std::vector<GpuTetrahedron> tetrahedra;
  std::mutex merge;
  tbb::parallel_for(0, cubeDims.z, [&](int z) {
    std::vector<GpuTetrahedron> local;
    std::vector<glm::vec4> spheres;
    for (int y = 0; y < cubeDims.y; ++y)
      for (int x = 0; x < cubeDims.x; ++x) {
        const glm::ivec3 m = cubeMin + glm::ivec3(x, y, z);
        const glm::ivec3 c1 = 2 * m + 1;
        for (int k = 0; k < 3; ++k) {
          const int a = (k + 1) % 3, b = (k + 2) % 3;
          glm::ivec3 ek(0), ea(0), eb(0);
          ek[k] = 2;
          ea[a] = 2;
          eb[b] = 2;
          const glm::ivec3 c2 = c1 + ek;
          const glm::ivec3 corner[4] = {2 * m + ek, 2 * m + ek + ea, 2 * m + ek + ea + eb, 2 * m + ek + eb};
          for (int e = 0; e < 4; ++e) {
            const glm::ivec3 v[4] = {corner[e], corner[(e + 1) % 4], c1, c2};
            const float f[4] = {sites.at(v[0]), sites.at(v[1]), sites.at(v[2]), sites.at(v[3])};
            const float lo = std::min({f[0], f[1], f[2], f[3]}), hi = std::max({f[0], f[1], f[2], f[3]});
            if (table.zeroOn(lo, hi)) continue;
            GpuTetrahedron t;
            glm::vec4 sphere;
            makeTetrahedron(v, f, t, sphere);
            local.push_back(t);
            spheres.push_back(sphere);
          }
        }
      }
    const std::lock_guard<std::mutex> lock(merge);
    tetrahedra.insert(tetrahedra.end(), local.begin(), local.end());
    centres_.insert(centres_.end(), spheres.begin(), spheres.end());
  });
  // One draw of 12 vertices a tetrahedron: its vertex count must be a GLsizei.
  const std::size_t most = std::min(options_.maxTetrahedra, std::size_t(std::numeric_limits<GLsizei>::max() / 12));
  if (tetrahedra.size() > most)
    throw ValueError(source.path() + ": " + std::to_string(tetrahedra.size()) + " tetrahedra with data; projected tetrahedra draw at most " +
                     std::to_string(most) + " (in core)");
  order_.resize(tetrahedra.size());
  tetrahedra_ = std::make_unique<GlBuffer>(std::max<std::size_t>(1, tetrahedra.size()) * sizeof(GpuTetrahedron),
                                           tetrahedra.empty() ? nullptr : tetrahedra.data());
  orderBuffer_ = std::make_unique<GlBuffer>(std::max<std::size_t>(1, order_.size()) * sizeof(uint32_t));
  table_ = std::make_unique<DvrTableGpu>(table);
  const DvrShading& shading = options_.shading;
  checkDvrShading(shading);
  program_ = GlProgram::graphics(
      embedded::shaders("shaders/tetra.vert"),
      withDefines(embedded::shaders("shaders/tetra.frag"), shading.on ? "#define FCC_DVR_SHADING 1\n" : ""),
      "projected tetrahedra");
  table_->setUniforms(program_, -1.0f);  // no early stop inside a segment: segments composite afterwards
  glProgramUniform1f(program_.id(), glGetUniformLocation(program_.id(), "uDvrSpecular"), shading.specular);  // shaded only
  glProgramUniform1f(program_.id(), glGetUniformLocation(program_.id(), "uDvrSpecularPower"), shading.specularPower);
  setDvrLightUniforms(program_.id(), shading.light);
  if (options_.timeGpu) timer_ = std::make_unique<GpuInterval>();  // before the objects the destructor frees
  glCreateVertexArrays(1, &vertexArray_);
  glCreateFramebuffers(1, &framebuffer_);
}

ProjectedTetrahedra::~ProjectedTetrahedra() {
  if (framebuffer_) glDeleteFramebuffers(1, &framebuffer_);
  if (vertexArray_) glDeleteVertexArrays(1, &vertexArray_);
}

FrameStats ProjectedTetrahedra::render(const Camera& camera, int width, int height) {
  if (width <= 0 || height <= 0)
    throw ValueError("image size " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
  const auto start = std::chrono::steady_clock::now();
  const CameraFrame frame = cameraFrame(camera, double(width) / double(height));
  const glm::dmat4 worldFromIndex = source_.worldFromIndex();
  const glm::dmat4 indexFromWorld = glm::inverse(worldFromIndex);
  // Back to front: the largest power distance |c - eye|^2 - r^2 first, in index space (an affine map
  // keeps the order along every ray, so a visibility order there is one in world space).
  const glm::vec3 eye(indexFromWorld * glm::dvec4(frame.eye, 1.0));
  // Sorted as 64-bit keys, the power's float bits ordered largest first above the tetrahedron's index:
  // one contiguous sort without a comparator reading another array, ties in index order (tetrahedra of
  // equal power distance do not overlap on the screen). Boost's block_indirect_sort, a parallel sort
  // of its own threads, faster than tbb::parallel_sort on such keys (`render --timings`' sort, which
  // includes making the keys, for 3.3 M on dev-2core: 0.11 s against 0.16; docs/BENCHMARKS.md, session 30).
  keys_.resize(centres_.size());
  tbb::parallel_for(std::size_t(0), centres_.size(), [&](std::size_t i) {
    const glm::vec3 r = glm::vec3(centres_[i]) - eye;
    keys_[i] = (uint64_t(largestFirstKey(glm::dot(r, r) - centres_[i].w)) << 32) | uint64_t(i);
  });
  boost::sort::block_indirect_sort(keys_.begin(), keys_.end());
  tbb::parallel_for(std::size_t(0), keys_.size(), [&](std::size_t i) { order_[i] = uint32_t(keys_[i]); });
  sortSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!order_.empty()) orderBuffer_->write(order_);

  if (color_.width() != width || color_.height() != height) {
    color_ = GlTexture2D(GL_RGBA32F, width, height);
    glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, color_.id(), 0);
    if (glCheckNamedFramebufferStatus(framebuffer_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw GlError("projected tetrahedra: the RGBA32F framebuffer is not complete");
  }
  const GLuint p = program_.id();
  const glm::mat4 worldFromIndexF(worldFromIndex), indexFromWorldF(indexFromWorld);
  const glm::mat3 normalFromIndex = glm::transpose(glm::mat3(indexFromWorldF));
  const glm::vec3 eyeWorld(frame.eye), forward(frame.forward), right(frame.right), up(frame.up);
  glProgramUniformMatrix4fv(p, glGetUniformLocation(p, "uWorldFromIndex"), 1, GL_FALSE, &worldFromIndexF[0][0]);
  glProgramUniformMatrix4fv(p, glGetUniformLocation(p, "uIndexFromWorld"), 1, GL_FALSE, &indexFromWorldF[0][0]);
  glProgramUniform1i(p, glGetUniformLocation(p, "uCullFaces"), options_.cullFaces ? 1 : 0);
  glProgramUniform3fv(p, glGetUniformLocation(p, "uEyeIndex"), 1, &eye.x);
  glProgramUniformMatrix3fv(p, glGetUniformLocation(p, "uNormalFromIndex"), 1, GL_FALSE, &normalFromIndex[0][0]);
  glProgramUniform3fv(p, glGetUniformLocation(p, "uEye"), 1, &eyeWorld.x);
  glProgramUniform3fv(p, glGetUniformLocation(p, "uForward"), 1, &forward.x);
  glProgramUniform3fv(p, glGetUniformLocation(p, "uRight"), 1, &right.x);
  glProgramUniform3fv(p, glGetUniformLocation(p, "uUp"), 1, &up.x);
  glProgramUniform2i(p, glGetUniformLocation(p, "uResolution"), width, height);
  const glm::vec3 lightDir = lightTowardsWorld(frame, options_.lightInCamera);
  glProgramUniform3fv(p, glGetUniformLocation(p, "uLightDir"), 1, &lightDir.x);  // shaded only
  if (options_.shading.on && options_.shading.light == DvrLight::Kit) setDvrLightFrameUniforms(p, frame);  // as the raycaster's

  if (timer_) timer_->begin();
  {
    const SavedGlState saved;
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glViewport(0, 0, width, height);
    const float clear[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearBufferfv(GL_COLOR, 0, clear);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // "over", premultiplied, back to front
    tetrahedra_->bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    orderBuffer_->bindBase(GL_SHADER_STORAGE_BUFFER, 1);
    table_->bind();
    program_.use();
    glBindVertexArray(vertexArray_);
    if (!order_.empty()) glDrawArrays(GL_TRIANGLES, 0, GLsizei(12 * order_.size()));  // 12 a tetrahedron: tetra.vert
  }  // the caller's state back
  if (timer_) timer_->end();
  glFinish();
  checkGl("drawing " + std::to_string(order_.size()) + " projected tetrahedra");
  FrameStats stats;
  stats.passes = 1;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (timer_) stats.gpuSeconds = timer_->seconds();
  return stats;
}

FrameImages ProjectedTetrahedra::readImages() const {
  FrameImages out;
  out.width = color_.width();
  out.height = color_.height();
  out.rgba = color_.read(GL_RGBA, 4);
  out.normalDepth.assign(out.rgba.size(), 0.0f);
  for (std::size_t i = 3; i < out.normalDepth.size(); i += 4) out.normalDepth[i] = std::numeric_limits<float>::infinity();
  return out;
}

}  // namespace fcc::render
