// Drawing only what changed (viewer/RedrawTracker.h, viewer/Presenter.h): the rectangles the tracker
// asks for, the presenter drawing exactly those pixels (the first one grown on the GPU to the
// raycaster's surface rectangle), and whole viewer sessions whose back buffers are kept (age 1) or
// swapped between two (age 2) ending every view with the same pixels as one that draws everything.
#include <gtest/gtest.h>

#include <imgui.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <backends/imgui_impl_opengl3.h>

#include "RenderTestSupport.h"
#include "viewer/DatasetSummary.h"
#include "viewer/HeadlessViewer.h"
#include "viewer/ImGuiDrawData.h"
#include "viewer/Presenter.h"
#include "viewer/RedrawTracker.h"
#include "viewer/ViewerSession.h"

namespace fcc {
namespace {

using render::FrameLook;
using render::PixelRect;
using render::RedrawTracker;
using Rects = std::vector<PixelRect>;
using test::GlSuite;
using test::TempDir;

using test::describe;

std::string describe(const std::vector<PixelRect>& rects) {
  std::string out;
  for (const PixelRect& r : rects) out += describe(r) + " ";
  return out;
}

const FrameLook kLook{200, 100, 30, glm::vec3(0.1f, 0.2f, 0.3f)};

TEST(RedrawTracker, UnknownOrDifferentBuffersAreDrawnWhole) {
  RedrawTracker tracker;
  const PixelRect all = kLook.imageArea();
  EXPECT_EQ(describe(tracker.regions(kLook, 1)), describe(Rects{all})) << "nothing drawn yet";
  tracker.drawn(kLook, {40, 10, 80, 50}, {}, 1);
  EXPECT_EQ(describe(tracker.regions(kLook, 0)), describe(Rects{all})) << "age 0: the buffer's contents are unknown";
  EXPECT_EQ(describe(tracker.regions(kLook, 2)), describe(Rects{all})) << "older than any frame drawn";
  EXPECT_EQ(describe(tracker.regions(kLook, 1)), describe(Rects{{40, 10, 80, 50}}));
  FrameLook other = kLook;
  other.background = glm::vec3(1.0f);
  EXPECT_EQ(describe(tracker.regions(other, 1)), describe(Rects{other.imageArea()})) << "another background";
  other = kLook;
  other.firstColumn = 31;
  EXPECT_EQ(describe(tracker.regions(other, 1)), describe(Rects{other.imageArea()})) << "another panel width";
  other = kLook;
  other.height = 101;
  EXPECT_EQ(describe(tracker.regions(other, 1)), describe(Rects{other.imageArea()})) << "another size";
}

// The panel need not be drawn again only where the back buffer shows the same one with nothing
// over the image.
TEST(RedrawTracker, HoldsTheUiOfTheSameLookAndHashWithoutOverlays) {
  RedrawTracker tracker;
  EXPECT_FALSE(tracker.holdsUi(kLook, 1, 7)) << "nothing drawn yet";
  tracker.drawn(kLook, {40, 10, 80, 50}, {}, 7);
  EXPECT_TRUE(tracker.holdsUi(kLook, 1, 7));
  EXPECT_FALSE(tracker.holdsUi(kLook, 1, 8)) << "another user interface";
  EXPECT_FALSE(tracker.holdsUi(kLook, 0, 7)) << "unknown buffer";
  EXPECT_FALSE(tracker.holdsUi(kLook, 2, 7)) << "older than any frame drawn";
  FrameLook other = kLook;
  other.firstColumn = 29;
  EXPECT_FALSE(tracker.holdsUi(other, 1, 7)) << "another look";
  tracker.drawn(kLook, {40, 10, 80, 50}, {{150, 20, 160, 30}}, 7);
  EXPECT_FALSE(tracker.holdsUi(kLook, 1, 7)) << "the image was drawn over: it is drawn again, and so must the UI be";
  EXPECT_TRUE(tracker.holdsUi(kLook, 2, 7));
}

TEST(RedrawTracker, OverlaysAreKeptApartAndClippedToTheImage) {
  RedrawTracker tracker;
  // The panel's antialiased edge, a window inside the surface's rectangle, a line of text.
  tracker.drawn(kLook, {100, 40, 150, 80}, {{0, 0, 32, 100}, {120, 50, 130, 60}, {160, 90, 190, 99}}, 1);
  EXPECT_EQ(describe(tracker.regions(kLook, 1)), describe(Rects{{100, 40, 150, 80}, {30, 0, 32, 100}, {160, 90, 190, 99}}));
}

TEST(RedrawTracker, AgeCountsFramesBack) {
  RedrawTracker tracker;
  for (int i = 0; i < RedrawTracker::kHistory + 2; ++i) {
    tracker.drawn(kLook, {40 + i, 10, 80 + i, 50}, {}, 1);
  }
  const int last = RedrawTracker::kHistory + 1;
  for (int age = 1; age <= RedrawTracker::kHistory; ++age) {
    const PixelRect then{40 + last + 1 - age, 10, 80 + last + 1 - age, 50};
    EXPECT_EQ(describe(tracker.regions(kLook, age)), describe(Rects{then})) << "age " << age;
  }
  EXPECT_EQ(describe(tracker.regions(kLook, RedrawTracker::kHistory + 1)), describe(Rects{kLook.imageArea()}));
}

TEST(RedrawTracker, ManyOverlaysBecomeTheirBoundingBox) {
  RedrawTracker tracker;
  std::vector<PixelRect> many;
  for (int i = 0; i < int(RedrawTracker::kMaxOverlays) + 1; ++i) many.push_back({40 + 10 * i, 5, 45 + 10 * i, 8});
  tracker.drawn(kLook, {}, many, 1);
  EXPECT_EQ(describe(tracker.regions(kLook, 1)), describe(Rects{{}, {40, 5, 45 + 10 * int(RedrawTracker::kMaxOverlays), 8}}));
}

TEST(PixelRect, CoveredAreaCountsOverlapsOnce) {
  EXPECT_EQ(render::coveredArea({}), 0);
  EXPECT_EQ(render::coveredArea({{0, 0, 10, 10}, {5, 5, 15, 15}}), 175);
  EXPECT_EQ(render::coveredArea({{0, 0, 10, 10}, {2, 2, 4, 4}, {20, 0, 21, 3}, {}}), 103);
}

// ImGui frames without a renderer (the font atlas built by hand): a fixed window with a line of text
// and, optionally, a second window over the image.
class ImGuiFrames : public ::testing::Test {
 protected:
  void SetUp() override {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(400.0f, 200.0f);
    unsigned char* pixels = nullptr;
    int width = 0, height = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
    io.Fonts->SetTexID(ImTextureID(intptr_t(1)));
  }
  void TearDown() override { ImGui::DestroyContext(); }
  static const ImDrawData& frame(const char* text, bool windowOverImage = false) {
    ImGui::GetIO().DeltaTime = 1.0f / 60.0f;
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(100.0f, 200.0f));
    ImGui::PushStyleVar(ImGuiStyleVar_WindowBorderSize, 0.0f);
    ImGui::Begin("panel", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoSavedSettings);
    ImGui::PopStyleVar();
    ImGui::TextUnformatted(text);
    ImGui::End();
    if (windowOverImage) {
      ImGui::SetNextWindowPos(ImVec2(150.0f, 50.0f));
      ImGui::SetNextWindowSize(ImVec2(60.0f, 40.0f));
      ImGui::Begin("over the image", nullptr, ImGuiWindowFlags_NoSavedSettings);
      ImGui::End();
    }
    ImGui::Render();
    return *ImGui::GetDrawData();
  }
};

TEST_F(ImGuiFrames, EqualDrawDataHashesEqualAndAnyChangeShows) {
  frame("1.23 ms");  // ImGui settles its windows over the first frames
  frame("1.23 ms");
  const uint64_t a = render::hashOf(frame("1.23 ms"));
  EXPECT_EQ(render::hashOf(frame("1.23 ms")), a);
  EXPECT_NE(render::hashOf(frame("1.25 ms")), a) << "another digit: same vertex count, other texture coordinates";
  EXPECT_NE(render::hashOf(frame("1.23 ms", true)), a) << "another window";
}

TEST_F(ImGuiFrames, OverlaysAreWhatIsDrawnOverTheImage) {
  const PixelRect image{100, 0, 400, 200};
  for (int i = 0; i < 3; ++i) frame("text", true);
  EXPECT_EQ(describe(render::overlaysOf(frame("text"), image)), describe(Rects{}))
      << "a borderless panel of 100 columns stays left of the image";
  const std::vector<PixelRect> over = render::overlaysOf(frame("text", true), image);
  ASSERT_EQ(over.size(), 1u) << describe(over);
  EXPECT_EQ(render::coveredArea({over[0], {150, 50, 210, 90}}), over[0].area())
      << "the window over the image, [150,210)x[50,90), is inside " << describe(over[0]);
  EXPECT_LE(over[0].area(), 64 * 44) << describe(over[0]) << " is more than its border (2 pixels) around the window";
}

class Presenter : public GlSuite {};

// A random premultiplied image: misses (A = 0, no colour) and hits (A = 1).
GlTexture2D randomImage(int width, int height, std::vector<float>& rgba) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  rgba.assign(std::size_t(width) * height * 4, 0.0f);
  for (std::size_t p = 0; p < rgba.size() / 4; ++p)
    if (u(rng) < 0.6f) rgba[4 * p] = u(rng), rgba[4 * p + 1] = u(rng), rgba[4 * p + 2] = u(rng), rgba[4 * p + 3] = 1.0f;
  GlTexture2D image(GL_RGBA32F, width, height);
  glTextureSubImage2D(image.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, rgba.data());
  return image;
}

// Exactly the pixels of the given rectangles are drawn, each as the whole image's draw has it,
// which is the CPU's sRGB encoding of colour over background (within a level of float rounding).
TEST_F(Presenter, DrawsExactlyTheRectanglesAndTheSurfaceRectangle) {
  const int w = 67, h = 45;
  std::vector<float> rgba;
  const GlTexture2D image = randomImage(w, h, rgba);
  const glm::vec3 background(0.2f, 0.05f, 0.6f);
  render::Presenter presenter;
  const render::OffscreenTarget whole(w, h), part(w, h);

  whole.bind();
  presenter.draw(image, background);
  const std::vector<unsigned char> reference = whole.readRgba();
  int worstLevels = 0;
  const auto srgb = [](float v) {
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(std::max(v, 0.0f), 1.0f / 2.4f) - 0.055f;
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const float* p = &rgba[(std::size_t(y) * w + x) * 4];
        const int expected = int(std::lround(255.0f * srgb(p[c] + (1.0f - p[3]) * background[c])));
        const int got = reference[(std::size_t(h - 1 - y) * w + x) * 4 + c];
        worstLevels = std::max(worstLevels, std::abs(got - expected));
      }
  EXPECT_LE(worstLevels, 1) << "the GPU's sRGB encoding strays from the CPU's";

  // Regions (rows from the top), a clip, and the surface rectangle a pass left on the GPU:
  // columns 50..59, rows 30..39 (last ones inclusive, as the raycaster stores them).
  const std::vector<PixelRect> regions{{5, 4, 20, 12}, {40, 2, 44, 44}, {60, 0, 80, 3}};
  const PixelRect clip{3, 1, 64, 44};
  const int32_t results[5] = {0, 50, 30, 59, 39};
  const GlBuffer passResults(sizeof results, results);
  struct Case {
    const char* what;
    const GlBuffer* passResults;
    PixelRect grownFirst;
  };
  std::vector<PixelRect> noFirst = regions;
  noFirst[0] = PixelRect{};
  for (const Case& c : {Case{"with the surface rectangle", &passResults, {5, 4, 60, 40}},
                        Case{"without", nullptr, regions[0]},
                        Case{"with the surface rectangle alone in the first", &passResults, {50, 30, 60, 40}}}) {
    part.bind();
    glClearColor(1.0f, 0.0f, 1.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    const bool alone = c.grownFirst == PixelRect{50, 30, 60, 40};
    presenter.draw(image, background, alone ? noFirst : regions, clip, c.passResults);
    const std::vector<unsigned char> drawn = part.readRgba();
    int drawnPixels = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const PixelRect pixel{x, y, x + 1, y + 1};
        bool inside = false;
        for (const PixelRect& r : {c.grownFirst, regions[1], regions[2]})
          inside = inside || !intersected(intersected(r, clip), pixel).empty();
        const std::size_t i = (std::size_t(h - 1 - y) * w + x) * 4;
        const unsigned char magenta[4] = {255, 0, 255, 255};
        for (int k = 0; k < 4; ++k) {
          const int expected = inside ? reference[i + k] : magenta[k];
          ASSERT_EQ(int(drawn[i + k]), expected) << c.what << ": pixel " << x << "," << y << " channel " << k
                                                 << (inside ? " should be drawn" : " should be left as it was");
        }
        drawnPixels += inside;
      }
    EXPECT_GT(drawnPixels, 0) << c.what;
  }
}

class ViewerRedraw : public GlSuite {};

// Three sessions on one dataset go through the same views: one draws the whole image every frame
// (buffer age 0), one draws into a target it keeps (age 1), one alternates two targets (age 2). Once
// a view has settled, the image beside the panel is the same in all three: nothing is left behind
// of the surface in an earlier view, of the help window, or of the streaming line. (The panels
// differ: they show each session's own frame times.)
TEST_F(ViewerRedraw, KeptBackBuffersEndEachViewLikeWholeRedraws) {
  TempDir dir;
  const std::string blobs = test::writeSmallBlobs(dir);
  const io::BrickStore store(blobs);
  const int w = 400, h = 240;
  const render::HeadlessImGui imgui(w, h);
  ImGui::GetIO().FontGlobalScale = 0.5f;  // a narrower panel: more image, fewer rays on llvmpipe
  render::RenderOptions options;
  options.iso = 0.3f;
  options.gpuCacheBytes = test::kSmallPoolBytes;  // several passes a view
  const render::Camera start = test::smallBlobsCamera();

  struct Viewer {
    int bufferAge;
    std::unique_ptr<render::ViewerSession> session;
    std::vector<std::unique_ptr<render::OffscreenTarget>> targets;  // used in turn
    int frames = 0;
    const render::OffscreenTarget& last() const { return *targets[std::size_t(frames - 1) % targets.size()]; }
  };
  std::vector<Viewer> viewers;
  for (int age : {0, 1, 2}) {
    Viewer v{age, std::make_unique<render::ViewerSession>(store, options, start, render::summarizeDataset(store)), {}};
    for (int i = 0; i < std::max(age, 1); ++i) v.targets.push_back(std::make_unique<render::OffscreenTarget>(w, h));
    viewers.push_back(std::move(v));
  }
  double partialFraction = 1.0;
  int uiKept = 0;  // frames of the sessions with kept buffers that left the panel as it was
  const render::OffscreenTarget scratch(w, h);
  const int panelColumns = int(std::floor(render::ViewerSession::kPanelWidth * 0.5f));
  // Where a frame left the panel as the buffer had it, the panel is what drawing this frame's
  // ImGui draw lists gives (the panel is opaque: over anything).
  const auto expectPanelAsDrawn = [&](const render::OffscreenTarget& target, int view) {
    const std::vector<unsigned char> kept = target.readRgba();
    scratch.bind();
    glClearColor(0.0f, 1.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    const std::vector<unsigned char> drawn = scratch.readRgba();
    int differing = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < panelColumns; ++x)
        for (int c = 0; c < 4; ++c) differing += kept[(std::size_t(y) * w + x) * 4 + c] != drawn[(std::size_t(y) * w + x) * 4 + c];
    EXPECT_EQ(differing, 0) << "view " << view << ": the panel left in the buffer is not this frame's";
  };
  int currentView = 0;
  const auto frame = [&](Viewer& v) {
    render::HeadlessImGui::newFrame();
    v.targets[std::size_t(v.frames) % v.targets.size()]->bind();
    // The first frame into each target finds it undefined.
    v.session->frame(w, h, h, v.frames < int(v.targets.size()) ? 0 : v.bufferAge);
    ++v.frames;
    if (v.bufferAge > 0) {
      partialFraction = std::min(partialFraction, v.session->stats().imageDrawn);
      if (!v.session->stats().uiDrawn) {
        ++uiKept;
        expectPanelAsDrawn(v.last(), currentView);
      }
    } else {
      EXPECT_TRUE(v.session->stats().uiDrawn) << "a buffer of unknown age needs the panel drawn";
    }
  };

  for (int view = 0; view < 6; ++view) {
    currentView = view;
    render::Camera camera = start;
    const double angle = 0.15 * view;  // radians about the vertical through the look-at point
    // Views 2-4 from afar: the surface's rectangle shrinks, so what the near views showed, the help
    // window (view 3) and the streaming line reach past it and must be drawn over again.
    const glm::dvec3 offset = (view >= 2 && view <= 4 ? 3.0 : 1.0) * (start.eye - start.lookat);
    camera.eye = start.lookat + glm::dvec3(std::cos(angle) * offset.x - std::sin(angle) * offset.y,
                                           std::sin(angle) * offset.x + std::cos(angle) * offset.y, offset.z);
    for (Viewer& v : viewers) {
      v.session->setCamera(camera);
      v.session->settings().showHelp = view == 3;
      if (view == 5) v.session->settings().background = glm::vec3(0.3f, 0.1f, 0.1f);
      int n = 0;
      do frame(v);  // settled() tells of the last frame: the new view needs one first
      while (!v.session->settled() && ++n < 2000);
      ASSERT_TRUE(v.session->settled()) << "view " << view << " did not settle";
      frame(v);  // the streaming line of the last frame is gone (it tells the previous frame's figures)
      frame(v);
      ASSERT_TRUE(v.session->settled()) << "view " << view;
    }
    const std::vector<unsigned char> expected = viewers[0].last().readRgba();
    for (std::size_t k = 1; k < viewers.size(); ++k) {
      const std::vector<unsigned char> got = viewers[k].last().readRgba();
      int differing = 0, firstX = -1, firstY = -1;
      for (int y = 0; y < h; ++y)
        for (int x = panelColumns; x < w; ++x)
          for (int c = 0; c < 4; ++c) {
            const std::size_t i = (std::size_t(y) * w + x) * 4 + c;
            if (got[i] != expected[i]) {
              if (differing++ == 0) firstX = x, firstY = h - 1 - y;
            }
          }
      EXPECT_EQ(differing, 0) << "view " << view << ", buffer age " << viewers[k].bufferAge << ": " << differing
                              << " channels differ from drawing everything, first at pixel " << firstX << ","
                              << firstY << " (row from the top)";
    }
  }
  EXPECT_LT(partialFraction, 0.9) << "the kept buffers never drew less than the whole image: nothing was tested";
  EXPECT_GT(uiKept, 0) << "the kept buffers always drew the panel again: its skipping was not tested";
  std::printf("least image drawn by a frame into a kept buffer: %.1f%%; frames leaving the panel as it was: %d\n",
              100.0 * partialFraction, uiKept);
}

}  // namespace
}  // namespace fcc
