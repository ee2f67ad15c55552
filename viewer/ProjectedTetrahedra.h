// Paper 002's baseline for direct volume rendering of BCC data: projected tetrahedra. The barycentric
// scheme is linear on the BCC Delaunay tetrahedra (sparse/BccBarycentric.h), so along a ray through one
// tetrahedron the field is a line: each tetrahedron is rasterized as its four faces, the fragment of the
// face where the pixel's ray enters integrates the ray's segment through it (shaders/tetra.frag: the
// same transfer table, sub-steps and compositing as the raycaster's DVR, dvr.glsl), and the segments
// are blended back to front in the order of the tetrahedra's power distance from the eye, a visibility
// order of a Delaunay tetrahedralization (H. Edelsbrunner, "An acyclicity theorem for cell complexes
// in d dimensions", 1989), sorted on the host every frame.
//
// In core, as the paper's is: every tetrahedron of the source's bricks with data whose values the
// transfer function does not map to zero is built once (80 + 64 bytes each on the GPU); at most
// `maxTetrahedra` (ValueError beyond, naming the count). For `compare`-sized data, against the
// raycaster's integration of the same field (tests/viewer/test_projected_tetrahedra.cpp).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "BrickSource.h"
#include "Camera.h"
#include "DvrTableGpu.h"
#include "GlProgram.h"
#include "Raycaster.h"

namespace fcc::render {

class ProjectedTetrahedra {
 public:
  struct Options {
    std::shared_ptr<const TransferTable> transfer;  // required
    DvrShading shading;  // dvr.glsl's gradient shading (the tetrahedron's gradient), as RenderOptions'
    glm::vec3 lightInCamera = kDefaultLightInCamera;  // the directional light's (RenderOptions::lightInCamera)
    bool timeGpu = false;                            // FrameStats::gpuSeconds
    std::size_t maxTetrahedra = std::size_t(8) << 20;
    // Faces no ray enters through dropped before rasterization (shaders/tetra.vert; the same image bit
    // for bit); false rasterizes every face, the tests' reference.
    bool cullFaces = true;
  };

  // `source`: a BCC dataset drawn with `barycentric` (ValueError naming what it is otherwise). Decodes
  // every brick with data (through source.decode) and builds the tetrahedra. Needs a current OpenGL 4.5
  // context.
  ProjectedTetrahedra(const BrickSource& source, Options options);
  ~ProjectedTetrahedra();
  ProjectedTetrahedra(const ProjectedTetrahedra&) = delete;
  ProjectedTetrahedra& operator=(const ProjectedTetrahedra&) = delete;

  // One frame: sort, draw, wait. FrameStats::passes is 1; seconds is the frame's wall time, sort included.
  FrameStats render(const Camera& camera, int width, int height);
  // The last frame as the raycaster gives it: premultiplied RGBA, row 0 at the top; normalDepth
  // (0, 0, 0, +inf) (no depth at opacity 0.5 from blended segments).
  FrameImages readImages() const;
  std::size_t tetrahedronCount() const { return centres_.size(); }
  double sortSeconds() const { return sortSeconds_; }  // of the last frame

 private:
  const BrickSource& source_;
  Options options_;
  std::vector<glm::vec4> centres_;  // circumcentre (index space), w = radius^2: the power distance's
  std::vector<uint64_t> keys_;  // render()'s sort: power distance and index
  std::vector<uint32_t> order_;
  std::unique_ptr<GlBuffer> tetrahedra_, orderBuffer_;
  std::unique_ptr<DvrTableGpu> table_;
  GlProgram program_;
  GLuint vertexArray_ = 0, framebuffer_ = 0;
  GlTexture2D color_;
  std::unique_ptr<GpuInterval> timer_;
  double sortSeconds_ = 0.0;
};

}  // namespace fcc::render
