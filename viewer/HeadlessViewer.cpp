#include "HeadlessViewer.h"

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "GlProgram.h"

namespace fcc::render {

OffscreenTarget::OffscreenTarget(int width, int height) : width_(width), height_(height) {
  glCreateRenderbuffers(1, &color_);
  glNamedRenderbufferStorage(color_, GL_RGBA8, width, height);
  glCreateFramebuffers(1, &framebuffer_);
  glNamedFramebufferRenderbuffer(framebuffer_, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
  if (glCheckNamedFramebufferStatus(framebuffer_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw GlError("the offscreen framebuffer of " + std::to_string(width) + "x" + std::to_string(height) +
                  " is incomplete");
}

OffscreenTarget::~OffscreenTarget() {
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteRenderbuffers(1, &color_);
}

void OffscreenTarget::bind() const { glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_); }

std::vector<unsigned char> OffscreenTarget::readRgba() const {
  std::vector<unsigned char> rgba(std::size_t(width_) * height_ * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadnPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(rgba.size()), rgba.data());
  checkGl("reading the offscreen framebuffer");
  return rgba;
}

HeadlessImGui::HeadlessImGui(int width, int height) {
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.DisplaySize = ImVec2(float(width), float(height));
  if (!ImGui_ImplOpenGL3_Init("#version 450")) {
    ImGui::DestroyContext();
    throw GlError("Dear ImGui's OpenGL 3 backend did not initialise (its loader needs libGL.so.1)");
  }
}

HeadlessImGui::~HeadlessImGui() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui::DestroyContext();
}

void HeadlessImGui::newFrame(float secondsSinceLast) {
  ImGui::GetIO().DeltaTime = secondsSinceLast;
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
}

}  // namespace fcc::render
