#include "app/app.h"

// GLEW's header before GLFW's (which would include the system GL header).
// clang-format off
#include "render/gl.h"
#include <GLFW/glfw3.h>
// clang-format on

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <csignal>
#include <fstream>
#include <iostream>
#include <optional>
#include <utility>

#include "app/actions.h"
#include "app/exit_report.h"
#include "app/panels.h"
#include "app/replay_player.h"
#include "app/viewport.h"
#include "app/worker.h"
#include "render/context.h"
#include "render/renderer.h"

namespace scour {

namespace {

// SIGINT or SIGTERM (Ctrl+C in the terminal, a test's kill) close the window as its close button
// does: the exit report is printed and --screenshot written.
volatile std::sig_atomic_t closeRequested = 0;

// The panels' font: DejaVu Sans (Debian's fonts-dejavu-core), for the paper's symbols (Kε, τc,
// Δs) and units (m², kg/m³, ≤) that ImGui's built-in font has no glyphs for.
constexpr ImWchar kFontRanges[] = {
    0x0020, 0x00FF,  // Basic Latin, Latin-1 (², ³, ·, µ, ü)
    0x0370, 0x03FF,  // Greek
    0x2010, 0x205E,  // punctuation (–, …)
    0x2070, 0x209F,  // superscripts and subscripts (ⁿ, ⁻¹)
    0x2190, 0x21FF,  // arrows
    0x2200, 0x22FF,  // mathematical operators (−, ≤, ≥, ≈, √, ∇)
    0,
};

// Dear ImGui over the window, with its GLFW and OpenGL 3 backends, for the window's lifetime.
struct ImGuiSession {
  explicit ImGuiSession(GLFWwindow* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini written next to the user's files
    loadFont();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 450 core");
  }
  ~ImGuiSession() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  ImGuiSession(const ImGuiSession&) = delete;
  ImGuiSession& operator=(const ImGuiSession&) = delete;

  /// Which font the panels use and whether it has the Greek letters (for the log).
  std::string fontNote;

 private:
  void loadFont() {
    ImFontAtlas& atlas = *ImGui::GetIO().Fonts;
    ImFont* font = nullptr;
    if (std::ifstream(SCOUR_UI_FONT).good())  // ImGui asserts on a missing file
      font = atlas.AddFontFromFileTTF(SCOUR_UI_FONT, 15.0f, nullptr, kFontRanges);
    if (!font) {
      atlas.AddFontDefault();
      fontNote = std::string("font: ") + SCOUR_UI_FONT +
                 " not found (install fonts-dejavu-core): Greek letters show as '?'";
      return;
    }
    atlas.Build();
    const bool greek = font->FindGlyphNoFallback(0x03B5) && font->FindGlyphNoFallback(0x03C4) &&
                       font->FindGlyphNoFallback(0x0394);
    fontNote = std::string("font: ") + SCOUR_UI_FONT + (greek ? ", with" : ", without") +
               " the Greek letters (ε τ Δ)";
  }
};

// Key presses in the order GLFW reports them. ImGui 1.86 keeps only whether a key is down at each
// frame, so a tap that goes down and up between two slow frames (one a second on llvmpipe) would
// be lost; a queue loses none. Made before ImGui's backend, which calls this callback after its
// own.
class Keys {
 public:
  struct Press {
    int key, mods;
  };
  explicit Keys(GLFWwindow* window) {
    glfwSetWindowUserPointer(window, this);
    glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int mods) {
      if (action == GLFW_PRESS)
        static_cast<Keys*>(glfwGetWindowUserPointer(w))->presses_.push_back({key, mods});
    });
  }
  /// The presses since the last call.
  std::vector<Press> take() { return std::exchange(presses_, {}); }

 private:
  std::vector<Press> presses_;
};

// Ctrl+Z undoes; Ctrl+Y and Ctrl+Shift+Z redo; Escape cancels a source's drag. Not while a text
// field has the keyboard (it keeps its own Ctrl+Z).
void applyShortcuts(const std::vector<Keys::Press>& presses, Actions& actions) {
  if (ImGui::GetIO().WantCaptureKeyboard) return;
  for (const Keys::Press& p : presses) {
    const bool ctrl = p.mods & GLFW_MOD_CONTROL, shift = p.mods & GLFW_MOD_SHIFT;
    if (ctrl && p.key == GLFW_KEY_Z)
      shift ? actions.redo() : actions.undo();
    else if (ctrl && p.key == GLFW_KEY_Y)
      actions.redo();
    else if (p.key == GLFW_KEY_ESCAPE && actions.drag().index >= 0)
      actions.cancelDrag();
  }
}

// The real mouse: a press on a source's marker drags it (Escape cancels); with a tool on, a
// click places; otherwise a left drag orbits, a right drag pans and the wheel zooms. Only when
// ImGui does not want the mouse, except during a drag, which owns it until the button is up.
class Mouse {
 public:
  /// Reads the mouse for this frame; returns the source under it (-1: none).
  int read(GLFWwindow* window, Actions& actions, Orbit& orbit, bool heldByReplay) {
    double mx = 0, my = 0;
    glfwGetCursorPos(window, &mx, &my);
    const bool left = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    int hovered = -1;
    if (cancelled_ && !left) cancelled_ = false;
    if (dragging_ && actions.drag().index < 0 && left) cancelled_ = true;  // Escape let it go
    dragging_ = false;
    if (heldByReplay || cancelled_) {
      // A scripted drag holds the (virtual) mouse; after a cancelled drag it rests till released.
    } else if (actions.drag().index >= 0) {
      if (!left)
        actions.release();
      else if (mx != lastX_ || my != lastY_)
        actions.dragTo(mx, my);
    } else if (!ImGui::GetIO().WantCaptureMouse) {
      hovered = actions.sourceUnder(mx, my);
      if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) && actions.press(mx, my)) {
        // grabbed a source's marker
      } else if (actions.tool != Tool::kOrbit && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
        actions.click(mx, my);
      } else {
        const bool right = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
        move(orbit, float(mx - lastX_), float(my - lastY_), left, right);
      }
      const float wheel = ImGui::GetIO().MouseWheel;
      if (wheel != 0) orbit.distance *= std::pow(0.9f, wheel);
    }
    lastX_ = mx, lastY_ = my;
    dragging_ = actions.drag().index >= 0 && !heldByReplay;
    return hovered;
  }

 private:
  static void move(Orbit& orbit, float dx, float dy, bool left, bool right) {
    if (left) {
      orbit.yaw -= 0.005f * dx;
      orbit.pitch = std::clamp(orbit.pitch + 0.005f * dy, -1.5f, 1.5f);
    } else if (right) {
      const Camera c = orbit.camera();
      const Eigen::Vector3f forward = (c.target - c.eye).normalized();
      const Eigen::Vector3f rightward = forward.cross(Eigen::Vector3f::UnitY()).normalized();
      const Eigen::Vector3f up = rightward.cross(forward);
      orbit.target += 0.0015f * orbit.distance * (-dx * rightward + dy * up);
    }
  }

  bool cancelled_ = false;  // a drag cancelled with Escape: the mouse rests till released
  bool dragging_ = false;   // the mouse held a source at the end of the last frame
  double lastX_ = 0, lastY_ = 0;
};

// The worker's errors and notices go to the log once each; after an automatic rollback the undo
// history starts afresh.
class WorkerMessages {
 public:
  void read(const Snapshot& snap, Actions& actions) {
    std::vector<std::string>& log = actions.log();
    if (!snap.error.empty() && snap.error != error_) log.push_back(snap.error);
    if (!snap.notice.empty() && snap.notice != notice_) log.push_back(snap.notice);
    error_ = snap.error, notice_ = snap.notice;
    if (snap.rollbacks != rollbacks_)
      actions.forgetHistory("rolled back after a broken invariant: the undo history starts afresh");
    rollbacks_ = snap.rollbacks;
  }

 private:
  std::string error_, notice_;
  long rollbacks_ = 0;
};

// The window's size in the mouse's (and ImGui's) pixels and its framebuffer's, read once a frame.
struct WindowSize {
  int w = 0, h = 0, fbw = 0, fbh = 0;
  explicit WindowSize(GLFWwindow* window) {
    glfwGetWindowSize(window, &w, &h);
    glfwGetFramebufferSize(window, &fbw, &fbh);
    w = std::max(w, 1), h = std::max(h, 1);
    fbw = std::max(fbw, 16), fbh = std::max(fbh, 16);
  }
  float aspect() const { return float(fbw) / float(fbh); }
};

// The view the actions pick through this frame (in window pixels, whatever the 3D view's size).
View viewOf(const WindowSize& size, const Snapshot& snap, const Orbit& orbit) {
  return {&snap, orbit.camera(), size.aspect(), size.w, size.h};
}

void drawPanels(const Snapshot& snap, const SceneSpec& scene, Actions& actions, int hovered,
                PanelState& state, const TimePlots& plots) {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  drawMarkers(actions, hovered);
  runPanel(snap, actions, state);
  parametersPanel(snap, actions, state);
  filePanel(actions, state);
  displayPanel(state);
  // The frames carry the erosion map the display shows (making one costs a pass over the grid).
  const std::string map = state.settings.terrain == RenderSettings::Terrain::kMap ? state.settings.map : "";
  if (map != state.shownMap) actions.command(cmd::ShowMap{map}), state.shownMap = map;
  waterPanel(snap, scene, actions, state);
  statsPanel(snap, plots, state);
  logPanel(actions.log(), state);
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

// The window as the user sees it, and each panel cut out of it (for docs/app.md).
void writePanelShots(const WindowSize& size, const PanelState& state, const std::string& dir) {
  const int fbw = size.fbw, fbh = size.fbh;
  writeRgbaPng(dir + "/window.png", fbw, fbh, readWindowPixels(0, 0, fbw, fbh, fbh));
  const float sx = float(fbw) / float(size.w), sy = float(fbh) / float(size.h);
  for (size_t i = 0; i < state.drawn.size(); ++i) {
    const Rect& r = state.drawn[i];
    const int x = std::clamp(int(r.x * sx), 0, fbw - 1), y = std::clamp(int(r.y * sy), 0, fbh - 1);
    const int pw = std::clamp(int(r.w * sx), 1, fbw - x),
              ph = std::clamp(int(r.h * sy), 1, fbh - y);
    std::string name = panelTitle(PanelId(i));
    std::transform(name.begin(), name.end(), name.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    writeRgbaPng(dir + "/panel_" + name + ".png", pw, ph, readWindowPixels(x, y, pw, ph, fbh));
  }
}

// The first view: the terrain in the middle the panels leave free.
Orbit fitOrbit(const Frame& frame, const WindowSize& size, const Rect& free) {
  return fitOrbit(frame, orbitFor(frame), size.aspect(), size.w, size.h, free.x, free.y, free.w,
                  free.h);
}

// The panels' places for this frame, in the window's pixels (ImGui's and the mouse's).
void layOutPanels(const WindowSize& size, PanelState& state) {
  LayoutStyle style;
  style.title = std::max(ImGui::GetFrameHeight(), 20.0f);  // (before the first frame: 0 + padding)
  state.layout = layOut(float(size.w), float(size.h), state.wishes, style);
}

}  // namespace

int runApp(const SceneSpec& spec, const AppOptions& o) {
  std::vector<ReplayEvent> events =
      o.replay.empty() ? std::vector<ReplayEvent>{} : readReplay(o.replay);
  auto context =
      createGlContext(GlBackend::kWindow, o.width, o.height, true, "Scour: " + spec.name);
  GLFWwindow* window = context->window();
  glfwSwapInterval(0);
  Keys keys(window);  // before ImGui's backend, which chains to its callback
  std::optional<ImGuiSession> imgui(std::in_place, window);

  SimulationWorker worker(spec, o.paused);
  Renderer renderer(o.width, o.height);
  Actions actions([&](const SimCommand& c) { worker.post(c); }, spec.params.spacing);
  actions.log().push_back(imgui->fontNote);
  PanelState state;
  state.settings.terrain = RenderSettings::Terrain(o.terrain);
  state.budget.choose(o.quality);
  std::optional<Orbit> orbit;
  // A picture at the window's full size, whatever size the level draws the 3D view at.
  state.screenshot = [&](const std::string& path) {
    const WindowSize size(window);
    if (orbit && (renderer.width() != size.fbw || renderer.height() != size.fbh)) {
      renderer.resize(size.fbw, size.fbh);
      renderer.render(worker.latest().frame, orbit->camera(), state.budget.apply(state.settings));
    }
    renderer.writePng(path);
  };
  ReplayPlayer replay(std::move(events), state.screenshot);
  Mouse mouse;
  WorkerMessages messages;
  TimePlots plots;
  SourceWatch watch;
  const double opened = glfwGetTime();
  long frames = 0, firstStep = -1, rebuilds = 0, surfaceFrames = 0, levelChanges = 0;
  int lastLevel = state.budget.level();
  double frameStart = opened;
  std::pair<int, int> lapseSize{0, 0};
  if (o.timelapse.everySteps > 0 || o.timelapse.everyBedSeconds > 0) {
    const std::string note = state.timelapse.start(o.timelapseFolder, o.timelapse);
    actions.log().push_back(note);
    if (!state.timelapse.recording()) throw TimelapseError(note);
  }

  closeRequested = 0;
  auto request = [](int) { closeRequested = 1; };
  std::signal(SIGINT, request);
  std::signal(SIGTERM, request);
  while (!glfwWindowShouldClose(window) && !closeRequested) {
    glfwPollEvents();
    const bool fresh = worker.poll();
    const Snapshot& snap = worker.latest();
    messages.read(snap, actions);
    plots.addSteps(snap);
    const WindowSize size(window);
    layOutPanels(size, state);
    if (!orbit) orbit = fitOrbit(snap.frame, size, state.layout.free);
    actions.setView(viewOf(size, snap, *orbit));
    replay.play(frames, actions);
    applyShortcuts(keys.take(), actions);
    if (fresh) watch.see(snap, actions);
    const int hovered = mouse.read(window, actions, *orbit, replay.holdsMouse());

    const double t0 = glfwGetTime();
    const auto [viewW, viewH] = state.budget.viewSize(size.fbw, size.fbh);
    renderer.resize(viewW, viewH);
    const bool rebuild = state.budget.rebuild(fresh);  // the budget asks for one at first
    rebuilds += rebuild;
    RenderSettings drawn = state.budget.apply(state.settings);
    surfaceFrames += drawn.water;
    levelChanges += state.budget.level() != lastLevel;
    lastLevel = state.budget.level();
    drawn.same_frame = !fresh && frames > 0;
    drawn.keep_surface = !rebuild;
    renderer.render(snap.frame, orbit->camera(), drawn);
    glFinish();
    plots.addRender(glfwGetTime() - t0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, size.fbw, size.fbh);
    renderer.blitTo(size.fbw, size.fbh);
    drawPanels(snap, worker.spec(), actions, hovered, state, plots);
    if (!o.panelShots.empty() && frames + 1 == o.quitAfterFrames)
      writePanelShots(size, state, o.panelShots);
    context->swapBuffers();
    // The budget is for the whole frame the user waits for: the 3D view, the panels, the swap.
    state.budget.measured(glfwGetTime() - t0);
    // The time-lapse's picture, when one is due: at the size the recording started with, after
    // the frame's time is measured (a picture must not lower the water's quality).
    state.timelapse.frame(snap, [&](const std::string& path) {
      if (state.timelapse.pictures() == 0) lapseSize = {size.fbw, size.fbh};
      renderer.resize(lapseSize.first, lapseSize.second);
      renderer.render(snap.frame, orbit->camera(), state.budget.apply(state.settings));
      renderer.writePng(path);
    });
    if (auto done = state.timelapse.finished()) actions.log().push_back(*done);
    if (o.stats) {
      const double now = glfwGetTime();
      o.stats->frameSeconds.push_back(now - frameStart);
      frameStart = now;
    }

    ++frames;
    if (firstStep < 0) firstStep = snap.frame.step;
    if (o.quitAfterFrames > 0 && frames >= o.quitAfterFrames) break;
    if (o.quitAfterSeconds > 0 && glfwGetTime() - opened >= o.quitAfterSeconds) break;
  }
  if (!o.screenshot.empty()) state.screenshot(o.screenshot);
  // A recording still going ends with the window: its video is made before the program ends.
  if (const std::string note = state.timelapse.finishNow(); !note.empty()) actions.log().push_back(note);
  const WindowSize size(window);
  actions.log().push_back(
      checkLayout(state.layout, state.drawn, state.cut, float(size.w), float(size.h)));
  actions.log().push_back("water quality " + state.budget.describe());
  const long errors = context->errors();
  imgui.reset();
  worker.poll();
  const Snapshot& last = worker.latest();
  if (o.stats) {
    o.stats->frames = frames, o.stats->steps = last.frame.step - std::max(firstStep, 0L);
    o.stats->seconds = glfwGetTime() - opened;
    o.stats->quality = state.budget.describe(), o.stats->rebuilds = rebuilds;
    o.stats->surfaceFrames = surfaceFrames, o.stats->levelChanges = levelChanges;
  }
  watch.see(last, actions);
  std::cout << exitReport(last, frames, actions, errors, watch.most());
  return errors == 0 ? 0 : 1;
}

}  // namespace scour
