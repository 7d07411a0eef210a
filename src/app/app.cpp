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
#include <cmath>
#include <iostream>
#include <optional>

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

// Dear ImGui over the window, with its GLFW and OpenGL 3 backends, for the window's lifetime.
struct ImGuiSession {
  explicit ImGuiSession(GLFWwindow* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini written next to the user's files
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
};

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
    if (heldByReplay || cancelled_) {
      // A scripted drag holds the (virtual) mouse; after a cancelled drag it rests till released.
    } else if (actions.drag().index >= 0) {
      if (ImGui::IsKeyPressed(ImGuiKey_Escape))
        actions.cancelDrag(), cancelled_ = true;
      else if (!left)
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
  double lastX_ = 0, lastY_ = 0;
};

// The worker's errors and notices go to the log once each.
class WorkerMessages {
 public:
  void read(const Snapshot& snap, std::vector<std::string>& log) {
    if (!snap.error.empty() && snap.error != error_) log.push_back(snap.error);
    if (!snap.notice.empty() && snap.notice != notice_) log.push_back(snap.notice);
    error_ = snap.error, notice_ = snap.notice;
  }

 private:
  std::string error_, notice_;
};

// The view the actions pick through this frame; sizes the renderer to the framebuffer.
View viewOf(GLFWwindow* window, const Snapshot& snap, const Orbit& orbit, Renderer& renderer) {
  int fbw = 0, fbh = 0, ww = 0, wh = 0;
  glfwGetFramebufferSize(window, &fbw, &fbh);
  fbw = std::max(fbw, 16), fbh = std::max(fbh, 16);
  renderer.resize(fbw, fbh);
  glfwGetWindowSize(window, &ww, &wh);
  return {&snap, orbit.camera(), float(fbw) / float(fbh), std::max(ww, 1), std::max(wh, 1)};
}

void drawPanels(const Snapshot& snap, const SceneSpec& scene, Actions& actions, int hovered,
                PanelState& state, const TimePlots& plots, const Renderer& renderer) {
  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  const float w = float(renderer.width()), h = float(renderer.height());
  drawMarkers(actions, hovered);
  runPanel(snap, actions, state);
  parametersPanel(snap, actions);
  displayPanel(state, w);
  waterPanel(snap, scene, actions, w);
  statsPanel(snap, plots, w);
  filePanel(actions, state);
  logPanel(actions.log(), h);
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

}  // namespace

int runApp(const SceneSpec& spec, const AppOptions& o) {
  std::vector<ReplayEvent> events =
      o.replay.empty() ? std::vector<ReplayEvent>{} : readReplay(o.replay);
  auto context =
      createGlContext(GlBackend::kWindow, o.width, o.height, true, "Scour: " + spec.name);
  GLFWwindow* window = context->window();
  glfwSwapInterval(0);
  std::optional<ImGuiSession> imgui(std::in_place, window);

  SimulationWorker worker(spec, o.paused);
  Renderer renderer(o.width, o.height);
  Actions actions([&](const SimCommand& c) { worker.post(c); }, spec.params.spacing);
  PanelState state;
  state.settings.terrain = RenderSettings::Terrain(o.terrain);
  state.screenshot = [&](const std::string& path) { renderer.writePng(path); };
  ReplayPlayer replay(std::move(events), state.screenshot);
  Mouse mouse;
  WorkerMessages messages;
  TimePlots plots;
  std::optional<Orbit> orbit;
  const double opened = glfwGetTime();
  long frames = 0, firstStep = -1;

  while (!glfwWindowShouldClose(window)) {
    glfwPollEvents();
    worker.poll();
    const Snapshot& snap = worker.latest();
    if (!orbit) orbit = orbitFor(snap.frame);
    messages.read(snap, actions.log());
    plots.addSteps(snap);
    actions.setView(viewOf(window, snap, *orbit, renderer));
    replay.play(frames, actions);
    const int hovered = mouse.read(window, actions, *orbit, replay.holdsMouse());

    const double t0 = glfwGetTime();
    renderer.render(snap.frame, orbit->camera(), state.settings);
    glFinish();
    plots.addRender(glfwGetTime() - t0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, renderer.width(), renderer.height());
    renderer.blitTo(renderer.width(), renderer.height());
    drawPanels(snap, worker.spec(), actions, hovered, state, plots, renderer);
    context->swapBuffers();

    ++frames;
    if (firstStep < 0) firstStep = snap.frame.step;
    if (o.quitAfterFrames > 0 && frames >= o.quitAfterFrames) break;
    if (o.quitAfterSeconds > 0 && glfwGetTime() - opened >= o.quitAfterSeconds) break;
  }
  if (!o.screenshot.empty()) renderer.writePng(o.screenshot);
  const long errors = context->errors();
  imgui.reset();
  worker.poll();
  const Snapshot& last = worker.latest();
  if (o.stats)
    *o.stats = {frames, last.frame.step - std::max(firstStep, 0L), glfwGetTime() - opened};
  std::cout << exitReport(last, frames, actions, errors);
  return errors == 0 ? 0 : 1;
}

}  // namespace scour
