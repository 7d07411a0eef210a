#include "app/app.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include "render/gl.h"  // before GLFW
#include <GLFW/glfw3.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <deque>
#include <iostream>
#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "app/edit_history.h"
#include "app/viewport.h"
#include "app/worker.h"
#include "render/context.h"
#include "render/renderer.h"
#include "scene/scene_json.h"

namespace scour {

namespace {

// toWindow in ImGui's pixel type, for drawing.
bool toWindow(const Camera& c, float aspect, const Eigen::Vector3f& p, int w, int h, ImVec2& out) {
  Eigen::Vector2f q;
  if (!toWindow(c, aspect, p, w, h, q)) return false;
  out = {q.x(), q.y()};
  return true;
}

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

}  // namespace

int runApp(const SceneSpec& spec, const AppOptions& o) {
  const std::vector<ReplayEvent> replay = o.replay.empty() ? std::vector<ReplayEvent>{} : readReplay(o.replay);
  auto context = createGlContext(GlBackend::kWindow, o.width, o.height, true, "Scour: " + spec.name);
  GLFWwindow* window = context->window();
  glfwSwapInterval(0);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini written next to the user's files
  ImGui_ImplGlfw_InitForOpenGL(window, true);
  ImGui_ImplOpenGL3_Init("#version 450 core");

  SimulationWorker worker(spec, o.paused);
  const double opened = glfwGetTime();
  long firstStep = -1;
  Renderer renderer(o.width, o.height);
  RenderSettings settings;
  settings.terrain = RenderSettings::Terrain(o.terrain);
  Orbit orbit;
  bool haveCamera = false;
  // What a left click on the terrain does (a press on a source's marker always drags it).
  enum class Tool { kOrbit, kSource, kSink, kBrush } tool = Tool::kOrbit;
  auto toggle = [&](Tool t, bool on) { tool = on ? t : (tool == t ? Tool::kOrbit : tool); };
  float brushRadius = 4 * spec.params.spacing;
  float sinkRadius = 3 * spec.params.spacing;
  char path[512] = "scour_out";
  Eigen::Vector3d lastSource = Eigen::Vector3d::Constant(NAN);  // placed or moved (the exit line)
  double lastRadius = 0;

  long frames = 0;
  long lastGeneration = -1;
  std::deque<float> sph, erosion, boundary, render;
  std::array<double, size_t(Pass::kCount)> lastPass{};
  long lastStep = -1;
  std::vector<std::string> log;
  std::string lastError, lastNotice;
  // Undo/redo of parameter and source edits (edit_history.h).
  EditHistory history;
  auto post = [&](const std::vector<SimCommand>& commands) {
    for (const SimCommand& c : commands) worker.post(c);
  };
  auto perform = [&](Edit e, bool extend) { post(history.perform(std::move(e), extend)); };
  auto undo = [&] {
    if (std::optional<Edit> e = history.undo()) post(e->undo), log.push_back("undo: " + e->what);
  };
  auto redo = [&] {
    if (std::optional<Edit> e = history.redo()) post(e->redo), log.push_back("redo: " + e->what);
  };
  // A restored snapshot brings back its own sources and sinks: edits made before it would undo
  // onto the wrong ones, so the history starts afresh.
  auto restoreSnapshot = [&](int id) {
    worker.post(cmd::RestoreSnapshot{id});  // an unknown one: the worker says so
    const auto& kept = worker.latest().snapshots;
    if (std::none_of(kept.begin(), kept.end(), [&](const SnapshotInfo& k) { return k.id == id; }))
      return;
    history.clear();
    log.push_back("restoring snapshot " + std::to_string(id) + " (undo history cleared)");
  };
  // A source being dragged across the terrain: every move is an UpdateSource, and the moves of
  // one drag merge into one undoable edit (like a slider drag). It keeps its height above the
  // terrain, its direction, rate and radius.
  struct SourceDrag {
    int index = -1;   ///< -1: none
    Source start;     ///< as it was at the press (what undo brings back)
    double lift = 0;  ///< its height above the terrain [m]
    bool moved = false;
    Eigen::Vector3d last = Eigen::Vector3d::Zero();
  } drag;
  // A scripted drag (replay `drag x0 y0 x1 y1`): press, kDragSteps moves, release, a frame each.
  struct ScriptedDrag {
    long start;
    double x0, y0, x1, y1;
  };
  std::optional<ScriptedDrag> scripted;
  constexpr int kDragSteps = 8;
  constexpr float kMarkerPixels = 10;  // how near a press must be to a marker to grab it
  bool cancelled = false;  // a drag cancelled with Escape: the mouse rests till released
  double lastX = 0, lastY = 0;
  int stepsPerFrame = 1;

  while (!glfwWindowShouldClose(window)) {
    glfwPollEvents();
    worker.poll();
    const Snapshot& snap = worker.latest();
    const Frame& frame = snap.frame;
    if (!haveCamera || snap.generation != lastGeneration) {
      if (!haveCamera) orbit = orbitFor(frame);
      haveCamera = true;
      lastGeneration = snap.generation;
    }
    if (!snap.error.empty() && snap.error != lastError) log.push_back(snap.error);
    lastError = snap.error;
    if (!snap.notice.empty() && snap.notice != lastNotice) log.push_back(snap.notice);
    lastNotice = snap.notice;
    // Per-step pass times, grouped like the paper's Table 1.
    if (frame.step != lastStep && frame.step > 0 && lastStep >= 0 && frame.step > lastStep) {
      double g[3] = {0, 0, 0};
      for (size_t p = 0; p < size_t(Pass::kCount); ++p) {
        const int k = int(table1Group(Pass(p)));
        if (k < 3) g[k] += (snap.passSeconds[p] - lastPass[p]) / double(frame.step - lastStep);
      }
      for (auto [q, v] : {std::pair{&sph, g[0]}, std::pair{&erosion, g[1]}, std::pair{&boundary, g[2]}}) {
        q->push_back(float(v * 1e3));
        if (q->size() > 200) q->pop_front();
      }
    }
    lastPass = snap.passSeconds;
    lastStep = frame.step;

    int fbw = 0, fbh = 0;
    glfwGetFramebufferSize(window, &fbw, &fbh);
    fbw = std::max(fbw, 16), fbh = std::max(fbh, 16);
    renderer.resize(fbw, fbh);
    int ww = 0, wh = 0;
    glfwGetWindowSize(window, &ww, &wh);
    ww = std::max(ww, 1), wh = std::max(wh, 1);
    const float aspect = float(fbw) / float(fbh);

    // Markers: a source is drawn as a stem from the terrain under it up to its centre; a press
    // within kMarkerPixels of the stem grabs it (the nearest one).
    auto sourceStem = [&](const Eigen::Vector3d& centre, ImVec2& foot, ImVec2& top) {
      float g = 0;
      const Eigen::Vector3f c = centre.cast<float>();
      const Eigen::Vector3f base =
          terrainHeight(frame, c.x(), c.z(), g) ? Eigen::Vector3f(c.x(), g, c.z()) : c;
      return toWindow(orbit.camera(), aspect, c, ww, wh, top) &&
             toWindow(orbit.camera(), aspect, base, ww, wh, foot);
    };
    auto sourceUnder = [&](double mx, double my) {
      int best = -1;
      float bestDistance = kMarkerPixels;
      for (size_t i = 0; i < snap.sources.size(); ++i) {
        ImVec2 foot, top;
        if (!sourceStem(snap.sources[i].center, foot, top)) continue;
        const float d = segmentDistance(Eigen::Vector2f(float(mx), float(my)), {foot.x, foot.y},
                                        {top.x, top.y});
        if (d <= bestDistance) best = int(i), bestDistance = d;
      }
      return best;
    };

    // Mouse: orbit (left drag), pan (right drag), zoom (wheel); a click places a source when
    // the Water panel's "place" mode is on. Only when ImGui does not want the mouse.
    // A click on the terrain places a source or paints water (the real mouse and the replay
    // take this same path).
    auto clickAt = [&](double cx, double cy) {
      Eigen::Vector3f hit;
      if (!pickTerrain(frame, orbit.camera(), aspect, cx, cy, ww, wh, hit)) {
        log.push_back("no terrain under the mouse");
        return;
      }
      if (tool == Tool::kSink) {
        // A box of half-size r around the hit: it takes the water (and what it carries) out.
        Sink k;
        k.lo = hit.cast<double>() - Eigen::Vector3d::Constant(sinkRadius);
        k.hi = hit.cast<double>() + Eigen::Vector3d::Constant(sinkRadius);
        perform({{cmd::AddSink{k}}, {cmd::RemoveSink{snap.sinks.size()}}, "place a sink", ""},
                false);
        log.push_back("sink placed at (" + number(hit.x()) + ", " + number(hit.y()) + ", " +
                      number(hit.z()) + "), half-size " + number(sinkRadius) + " m");
        return;
      }
      if (tool == Tool::kBrush) {
        worker.post(cmd::PaintWater{hit.cast<double>() + Eigen::Vector3d(0, brushRadius, 0), brushRadius});
        log.push_back("painted water at (" + number(hit.x()) + ", " + number(hit.y()) + ", " + number(hit.z()) + ")");
        return;
      }
      Source s;
      s.radius = 3 * frame.spacing;
      s.center = overTerrain(frame, hit.cast<double>(), s.radius, 6 * frame.spacing);
      s.direction = {0, -1, 0};
      s.rate = 50 * std::pow(double(frame.spacing), 2);  // about 1 m/s out of the disk
      perform({{cmd::AddSource{s}}, {cmd::RemoveSource{snap.sources.size()}}, "place a source", ""}, false);
      lastSource = s.center, lastRadius = s.radius;
      log.push_back("source placed at (" + number(s.center.x()) + ", " + number(s.center.y()) + ", " + number(s.center.z()) + ")");
    };
    // Dragging a source: the real mouse and the replay take these same three steps.
    auto pressAt = [&](double cx, double cy) {
      const int i = sourceUnder(cx, cy);
      if (i < 0) return false;
      drag = SourceDrag{};
      drag.index = i;
      drag.start = snap.sources[size_t(i)];
      float g = 0;
      const Eigen::Vector3d& c = drag.start.center;
      drag.lift = terrainHeight(frame, c.x(), c.z(), g) ? c.y() - g : 6 * frame.spacing;
      return true;
    };
    auto dragTo = [&](double cx, double cy) {
      Eigen::Vector3f hit;
      if (drag.index < 0 || !pickTerrain(frame, orbit.camera(), aspect, cx, cy, ww, wh, hit))
        return;  // off the terrain: it waits
      Source s = drag.start;
      s.center = overTerrain(frame, hit.cast<double>(), s.radius, drag.lift);
      if (drag.moved && (s.center - drag.last).norm() < 1e-9) return;
      const std::string what = "move source " + std::to_string(drag.index);
      perform({{cmd::UpdateSource{size_t(drag.index), s}},
               {cmd::UpdateSource{size_t(drag.index), drag.start}},
               what,
               what},
              drag.moved);
      drag.moved = true;
      drag.last = s.center;
    };
    auto release = [&] {
      if (drag.index >= 0 && drag.moved) {
        lastSource = drag.last, lastRadius = drag.start.radius;
        log.push_back("source " + std::to_string(drag.index) + " moved to (" +
                      number(drag.last.x()) + ", " + number(drag.last.y()) + ", " +
                      number(drag.last.z()) + ")");
      }
      drag = SourceDrag{};
    };
    // A parameter edit, undoable; `extend` merges it into the previous edit of the same key
    // (a slider being dragged).
    auto setParameter = [&](const std::string& key, const std::string& value, bool extend = false) {
      const ParamInfo* info = findParam(key);
      std::string old = value;
      if (info) old = info->choices ? info->choices[int(getParam(snap.params, *info))] : number(getParam(snap.params, *info));
      perform({{cmd::SetParam{key, value}}, {cmd::SetParam{key, old}}, key + " = " + value, key}, extend);
    };
    // Scripted events of this frame.
    for (const ReplayEvent& e : replay) {
      if (e.frame != frames) continue;
      const auto& w = e.words;
      if (w[0] == "click") clickAt(std::stod(w[1]), std::stod(w[2]));
      else if (w[0] == "drag") {
        release();
        scripted = ScriptedDrag{frames, std::stod(w[1]), std::stod(w[2]), std::stod(w[3]),
                                std::stod(w[4])};
      } else if (w[0] == "place")
        toggle(Tool::kSource, w[1] == "on");
      else if (w[0] == "sink")
        toggle(Tool::kSink, w[1] == "on");
      else if (w[0] == "brush")
        toggle(Tool::kBrush, w[1] == "on");
      else if (w[0] == "set") setParameter(w[1], w[2]);
      else if (w[0] == "restore")
        restoreSnapshot(std::stoi(w[1]));
      else if (w[0] == "press") {
        if (w[1] == "undo") undo();
        else if (w[1] == "snapshot")
          worker.post(cmd::TakeSnapshot{});
        else if (w[1] == "redo") redo();
        else if (w[1] == "play") worker.post(cmd::Resume{});
        else if (w[1] == "pause") worker.post(cmd::Pause{});
        else if (w[1] == "step") worker.post(cmd::StepOnce{});
        else if (w[1] == "reset") worker.post(cmd::Reset{});
      } else if (w[0] == "screenshot") renderer.writePng(w[1]);
    }
    if (scripted) {
      const long k = frames - scripted->start;
      if (k == 0 && !pressAt(scripted->x0, scripted->y0)) {
        log.push_back("no source under (" + number(scripted->x0) + ", " + number(scripted->y0) +
                      ") to drag");
        scripted.reset();
      } else if (k > 0) {
        const double t = std::min(1.0, double(k) / kDragSteps);
        dragTo(scripted->x0 + t * (scripted->x1 - scripted->x0),
               scripted->y0 + t * (scripted->y1 - scripted->y0));
        if (k >= kDragSteps) release(), scripted.reset();
      }
    }

    double mx = 0, my = 0;
    glfwGetCursorPos(window, &mx, &my);
    int hovered = -1;
    if (cancelled && glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) != GLFW_PRESS)
      cancelled = false;
    if (scripted || cancelled) {
      // A scripted drag holds the (virtual) mouse; after a cancelled drag it rests till released.
    } else if (drag.index >= 0) {
      // A drag owns the mouse until the button is up, over a panel or not; Escape cancels it.
      if (ImGui::IsKeyPressed(ImGuiKey_Escape)) {
        if (drag.moved) {  // a cancelled drag is not there to redo
          if (std::optional<Edit> e = history.cancel("move source " + std::to_string(drag.index)))
            post(e->undo), log.push_back("undo: " + e->what);
        }
        drag = SourceDrag{};
        cancelled = true;
      } else if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) {
        if (mx != lastX || my != lastY) dragTo(mx, my);
      } else {
        release();
      }
    } else if (!io.WantCaptureMouse) {
      const float dx = float(mx - lastX), dy = float(my - lastY);
      hovered = sourceUnder(mx, my);
      if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) && pressAt(mx, my)) {
        // grabbed a source's marker
      } else if (tool != Tool::kOrbit && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
        clickAt(mx, my);
      } else if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) {
        orbit.yaw -= 0.005f * dx;
        orbit.pitch = std::clamp(orbit.pitch + 0.005f * dy, -1.5f, 1.5f);
      } else if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS) {
        const Camera c = orbit.camera();
        const Eigen::Vector3f fwd = (c.target - c.eye).normalized();
        const Eigen::Vector3f right = fwd.cross(Eigen::Vector3f::UnitY()).normalized();
        const Eigen::Vector3f up = right.cross(fwd);
        orbit.target += 0.0015f * orbit.distance * (-dx * right + dy * up);
      }
      if (io.MouseWheel != 0) orbit.distance *= std::pow(0.9f, io.MouseWheel);
    }
    lastX = mx, lastY = my;

    const double t0 = glfwGetTime();
    renderer.render(frame, orbit.camera(), settings);
    glFinish();
    render.push_back(float((glfwGetTime() - t0) * 1e3));
    if (render.size() > 200) render.pop_front();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fbw, fbh);
    renderer.blitTo(fbw, fbh);

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();

    // Markers over the picture, under the panels. Sources: a stem from the terrain to the centre
    // (highlighted when the mouse is on it or it is being dragged). Sinks: the outline of their
    // box on the terrain.
    {
      ImDrawList* draw = ImGui::GetBackgroundDrawList();
      for (size_t i = 0; i < snap.sources.size(); ++i) {
        const bool held = drag.index == int(i);
        ImVec2 foot, top;
        if (!sourceStem(held && drag.moved ? drag.last : snap.sources[i].center, foot, top))
          continue;
        const ImU32 colour =
            held || hovered == int(i) ? IM_COL32(255, 230, 60, 255) : IM_COL32(255, 140, 30, 230);
        draw->AddLine(foot, top, colour, 2.0f);
        draw->AddCircle(foot, 4.0f, colour, 12, 2.0f);
        draw->AddCircleFilled(top, 6.0f, colour, 12);
        draw->AddText({top.x + 8, top.y - 8}, colour, ("source " + std::to_string(i)).c_str());
      }
      const double xMax = frame.x0 + (frame.nx - 1) * frame.dx,
                   zMax = frame.z0 + (frame.nz - 1) * frame.dz;
      for (size_t i = 0; i < snap.sinks.size(); ++i) {
        const Sink& k = snap.sinks[i];
        const double x0 = std::max(k.lo.x(), frame.x0), x1 = std::min(k.hi.x(), xMax);
        const double z0 = std::max(k.lo.z(), frame.z0), z1 = std::min(k.hi.z(), zMax);
        if (!(x0 < x1 && z0 < z1)) continue;
        // Around the footprint, on the terrain, 16 points a side.
        std::vector<ImVec2> outline;
        const double corner[5][2] = {{x0, z0}, {x1, z0}, {x1, z1}, {x0, z1}, {x0, z0}};
        bool seen = true;
        for (int side = 0; side < 4 && seen; ++side)
          for (int t = 0; t < 16 && seen; ++t) {
            const double u = t / 16.0;
            const double x = (1 - u) * corner[side][0] + u * corner[side + 1][0];
            const double z = (1 - u) * corner[side][1] + u * corner[side + 1][1];
            float g = 0;
            ImVec2 q;
            seen =
                terrainHeight(frame, x, z, g) &&
                toWindow(orbit.camera(), aspect,
                         Eigen::Vector3f(float(x), g + 0.5f * frame.spacing, float(z)), ww, wh, q);
            outline.push_back(q);
          }
        if (!seen) continue;
        const ImU32 colour = IM_COL32(200, 80, 255, 230);
        draw->AddPolyline(outline.data(), int(outline.size()), colour, ImDrawFlags_Closed, 2.0f);
        draw->AddText(outline[0], colour, ("sink " + std::to_string(i)).c_str());
      }
    }

    ImGui::SetNextWindowPos({10, 10}, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize({340, 0}, ImGuiCond_FirstUseEver);
    ImGui::Begin("Run");
    if (ImGui::Button(snap.paused ? "Play" : "Pause")) worker.post(snap.paused ? SimCommand(cmd::Resume{}) : SimCommand(cmd::Pause{}));
    ImGui::SameLine();
    if (ImGui::Button("Step")) worker.post(cmd::StepOnce{});
    ImGui::SameLine();
    if (ImGui::Button("Reset")) worker.post(cmd::Reset{});
    ImGui::SameLine();
    if (ImGui::Button("Undo")) undo();
    if (ImGui::IsItemHovered() && history.nextUndo())
      ImGui::SetTooltip("%s", history.nextUndo()->what.c_str());
    ImGui::SameLine();
    if (ImGui::Button("Redo")) redo();
    if (ImGui::IsItemHovered() && history.nextRedo())
      ImGui::SetTooltip("%s", history.nextRedo()->what.c_str());
    if (!io.WantCaptureKeyboard && io.KeyCtrl) {
      if (ImGui::IsKeyPressed(ImGuiKey_Z)) undo();
      if (ImGui::IsKeyPressed(ImGuiKey_Y)) redo();
    }
    if (ImGui::SliderInt("steps per frame", &stepsPerFrame, 1, 50)) worker.post(cmd::SetStepsPerFrame{stepsPerFrame});
    ImGui::Text("t = %.3f s   step %ld   %zu particles", frame.time, frame.step, frame.particles());
    ImGui::Text("%.1f steps/s", snap.stepsPerSecond);
    // Whole world states to go back to (the worker keeps them; see worker.h).
    if (ImGui::CollapsingHeader("Snapshots", ImGuiTreeNodeFlags_DefaultOpen)) {
      if (ImGui::Button("take snapshot")) worker.post(cmd::TakeSnapshot{});
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "keeps the terrain, the water, its sediment and the sources as they are now");
      for (const SnapshotInfo& k : snap.snapshots) {
        ImGui::PushID(k.id);
        ImGui::Text("#%d  t = %.3f s  step %ld  %zu particles", k.id, k.time, k.step, k.particles);
        ImGui::SameLine();
        if (ImGui::SmallButton("restore")) restoreSnapshot(k.id);
        if (ImGui::IsItemHovered())
          ImGui::SetTooltip(
              "back to this terrain, water and sources, with the parameters as they are now");
        ImGui::SameLine();
        if (ImGui::SmallButton("delete")) worker.post(cmd::DeleteSnapshot{k.id});
        ImGui::PopID();
      }
    }
    ImGui::End();

    ImGui::SetNextWindowPos({10, 140}, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize({340, 420}, ImGuiCond_FirstUseEver);
    ImGui::Begin("Parameters");
    std::string group;
    bool open = false;
    for (const ParamInfo& p : paramTable()) {
      const std::string key = p.key, g = key.substr(0, key.find('.'));
      if (g != group) {
        group = g;
        open = ImGui::CollapsingHeader(g.c_str(), g == "erosion" ? ImGuiTreeNodeFlags_DefaultOpen : 0);
      }
      if (!open) continue;
      const std::string label = std::string(p.label) + " " + p.symbol + (p.unit && *p.unit ? std::string(" [") + p.unit + "]" : "");
      const double current = getParam(snap.params, p);
      if (p.choices) {
        int v = int(current);
        int count = 0;
        while (p.choices[count]) ++count;
        if (ImGui::Combo(label.c_str(), &v, p.choices, count)) setParameter(key, p.choices[v]);
      } else {
        double v = current;
        const bool logScale = p.min > 0 && p.max / p.min > 100;
        if (ImGui::SliderScalar(label.c_str(), ImGuiDataType_Double, &v, &p.min, &p.max, "%.4g",
                                logScale ? ImGuiSliderFlags_Logarithmic : 0))
          setParameter(key, number(v), ImGui::IsItemActive() && !ImGui::IsItemActivated());
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s (%s): %s  range [%g, %g]", key.c_str(), p.symbol, p.help, p.min, p.max);
    }
    ImGui::End();

    ImGui::SetNextWindowPos({float(fbw) - 330, 10}, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize({320, 0}, ImGuiCond_FirstUseEver);
    ImGui::Begin("Display");
    int mode = int(settings.terrain);
    ImGui::RadioButton("shaded", &mode, 0);
    ImGui::SameLine();
    ImGui::RadioButton("erosion", &mode, 1);
    ImGui::SameLine();
    ImGui::RadioButton("sediment", &mode, 2);
    settings.terrain = RenderSettings::Terrain(mode);
    ImGui::Checkbox("water surface", &settings.water);
    ImGui::Checkbox("reflections", &settings.reflections);
    ImGui::SameLine();
    ImGui::Checkbox("refraction", &settings.refraction);
    ImGui::SameLine();
    ImGui::Checkbox("caustics", &settings.caustics);
    int particles = int(settings.particles);
    ImGui::Text("particles:");
    ImGui::SameLine();
    ImGui::RadioButton("off", &particles, 0);
    ImGui::SameLine();
    ImGui::RadioButton("C", &particles, 1);
    ImGui::SameLine();
    ImGui::RadioButton("speed", &particles, 2);
    settings.particles = RenderSettings::Particles(particles);
    ImGui::TextDisabled(
        "left drag: orbit, right drag: pan, wheel: zoom;\ndrag a source's marker to move it");
    ImGui::End();

    ImGui::SetNextWindowPos({float(fbw) - 330, 200}, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize({320, 0}, ImGuiCond_FirstUseEver);
    ImGui::Begin("Water");
    for (auto [t, label] : {std::pair{Tool::kSource, "click the terrain to place a source"},
                            std::pair{Tool::kSink, "click the terrain to place a sink"},
                            std::pair{Tool::kBrush, "brush: click to paint water"}}) {
      bool on = tool == t;
      if (ImGui::Checkbox(label, &on)) toggle(t, on);
    }
    ImGui::TextDisabled("drag a source's marker to move it (one undo step)");
    ImGui::SliderFloat("brush radius [m]", &brushRadius, frame.spacing, 30 * frame.spacing, "%.3g");
    ImGui::SliderFloat("new sink half-size [m]", &sinkRadius, 0.5f * frame.spacing,
                       30 * frame.spacing, "%.3g", ImGuiSliderFlags_AlwaysClamp);
    {
      SceneSpec edited = worker.spec();
      bool rain = edited.effects.rain;
      if (!edited.rain.empty() && ImGui::Checkbox("rain (on reset)", &rain)) {
        edited.effects.rain = rain;
        worker.post(cmd::SetEffects{edited.effects});
        worker.post(cmd::Reset{});
      }
    }
    ImGui::Text("%ld particles from sources, %ld painted", snap.emitted, snap.painted);
    for (size_t i = 0; i < snap.sources.size(); ++i) {
      ImGui::PushID(int(i));
      Source s = snap.sources[i];
      bool changed = false;
      ImGui::Text("source %zu at (%.2f, %.2f, %.2f)", i, s.center.x(), s.center.y(), s.center.z());
      float rate = float(s.rate * 1e3), radius = float(s.radius);
      float dir[3] = {float(s.direction.x()), float(s.direction.y()), float(s.direction.z())};
      if (ImGui::SliderFloat3("direction", dir, -1.0f, 1.0f, "%.2f") && Eigen::Vector3f(dir[0], dir[1], dir[2]).norm() > 1e-3f) {
        s.direction = Eigen::Vector3d(dir[0], dir[1], dir[2]);
        changed = true;
      }
      changed |= ImGui::SliderFloat("rate [L/s]", &rate, 0.01f, 50.0f, "%.3g", ImGuiSliderFlags_Logarithmic);
      changed |= ImGui::SliderFloat("radius [m]", &radius, frame.spacing, 50 * frame.spacing, "%.3g");
      if (changed) {
        s.rate = rate * 1e-3, s.radius = radius;
        perform({{cmd::UpdateSource{i, s}}, {cmd::UpdateSource{i, snap.sources[i]}}, "edit source " + std::to_string(i),
                 "source" + std::to_string(i)},
                ImGui::IsItemActive() && !ImGui::IsItemActivated());
      }
      if (ImGui::Button("delete"))
        perform({{cmd::RemoveSource{i}}, {cmd::AddSource{snap.sources[i]}}, "delete source " + std::to_string(i), ""}, false);
      ImGui::PopID();
    }
    ImGui::Separator();
    ImGui::Text("%zu sinks; %ld particles removed by them", snap.sinks.size(), snap.removedBySinks);
    for (size_t i = 0; i < snap.sinks.size(); ++i) {
      ImGui::PushID("sink");
      ImGui::PushID(int(i));
      const Sink& k = snap.sinks[i];
      const Eigen::Vector3d centre = 0.5 * (k.lo + k.hi), half = 0.5 * (k.hi - k.lo);
      ImGui::Text("sink %zu at (%.2f, %.2f, %.2f)", i, centre.x(), centre.y(), centre.z());
      float h[3] = {float(half.x()), float(half.y()), float(half.z())};
      if (ImGui::DragFloat3("half-size [m]", h, 0.002f, 0.5f * frame.spacing, 10.0f, "%.3g",
                            ImGuiSliderFlags_AlwaysClamp) &&
          std::isfinite(h[0] + h[1] + h[2]) && std::min({h[0], h[1], h[2]}) > 0) {
        Sink resized;
        const Eigen::Vector3d r(h[0], h[1], h[2]);
        resized.lo = centre - r, resized.hi = centre + r;
        perform({{cmd::UpdateSink{i, resized}},
                 {cmd::UpdateSink{i, k}},
                 "resize sink " + std::to_string(i),
                 "sink" + std::to_string(i)},
                ImGui::IsItemActive() && !ImGui::IsItemActivated());
      }
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("half the box's size along x, y and z, about its centre");
      if (ImGui::Button("delete"))
        perform({{cmd::RemoveSink{i}}, {cmd::AddSink{k}}, "delete sink " + std::to_string(i), ""},
                false);
      ImGui::PopID();
      ImGui::PopID();
    }
    ImGui::End();

    ImGui::SetNextWindowPos({float(fbw) - 330, 380}, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize({320, 0}, ImGuiCond_FirstUseEver);
    ImGui::Begin("Stats");
    auto plot = [](const char* name, const std::deque<float>& q) {
      std::vector<float> v(q.begin(), q.end());
      char overlay[64];
      std::snprintf(overlay, sizeof overlay, "%.2f ms", v.empty() ? 0.0f : v.back());
      ImGui::PlotLines(name, v.data(), int(v.size()), 0, overlay, 0.0f, FLT_MAX, {0, 40});
    };
    plot("SPH", sph);
    plot("erosion", erosion);
    plot("boundary", boundary);
    plot("render", render);
    ImGui::Text("soil: terrain %.6g  suspended %.3g  removed %.3g m3", snap.soil.terrain, snap.soil.suspended, snap.soil.removed);
    ImGui::Text("budget error %.2e (relative)", snap.soil.relativeError());
    ImGui::End();

    ImGui::SetNextWindowPos({360, 10}, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize({360, 0}, ImGuiCond_FirstUseEver);
    ImGui::Begin("File");
    ImGui::InputText("name", path, sizeof path);
    ImGui::TextDisabled("files are <name>.json, .ckpt, _height.png, .r32, .obj, _erosion.png, _shot.png");
    const std::string base = path;
    using K = cmd::Save::Kind;
    if (ImGui::Button("save scene")) worker.post(cmd::Save{K::kScene, base + ".json"});
    ImGui::SameLine();
    if (ImGui::Button("save checkpoint")) worker.post(cmd::Save{K::kCheckpoint, base + ".ckpt"});
    ImGui::SameLine();
    if (ImGui::Button("resume checkpoint")) worker.post(cmd::LoadCheckpoint{base + ".ckpt"});
    if (ImGui::Button("open scene")) {
      try {
        worker.post(cmd::Load{loadSceneFile(base + ".json")});
      } catch (const std::exception& e) {
        log.push_back(e.what());
      }
    }
    if (ImGui::Button("height PNG")) worker.post(cmd::Save{K::kHeightPng, base + "_height.png"});
    ImGui::SameLine();
    if (ImGui::Button("raw float")) worker.post(cmd::Save{K::kHeightRaw, base + ".r32"});
    ImGui::SameLine();
    if (ImGui::Button("mesh OBJ")) worker.post(cmd::Save{K::kMesh, base + ".obj"});
    ImGui::SameLine();
    if (ImGui::Button("erosion map")) worker.post(cmd::Save{K::kErosionMap, base + "_erosion.png"});
    if (ImGui::Button("screenshot")) {
      try {
        renderer.writePng(base + "_shot.png");
        log.push_back("wrote " + base + "_shot.png");
      } catch (const std::exception& e) {
        log.push_back(e.what());
      }
    }
    ImGui::End();

    ImGui::SetNextWindowPos({10, float(fbh) - 130}, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize({600, 120}, ImGuiCond_FirstUseEver);
    ImGui::Begin("Log");
    for (const std::string& line : log) ImGui::TextWrapped("%s", line.c_str());
    ImGui::End();

    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    context->swapBuffers();
    ++frames;
    if (firstStep < 0) firstStep = frame.step;
    if (o.quitAfterFrames > 0 && frames >= o.quitAfterFrames) break;
    if (o.quitAfterSeconds > 0 && glfwGetTime() - opened >= o.quitAfterSeconds) break;
  }
  if (!o.screenshot.empty()) renderer.writePng(o.screenshot);
  const long errors = context->errors();
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  worker.poll();
  const Snapshot& last = worker.latest();
  if (o.stats) *o.stats = {frames, last.frame.step - std::max(firstStep, 0L), glfwGetTime() - opened};
  // Near it, and close around its disk (there only what it emits, not water flowing past below).
  long near = 0, atDisk = 0;
  if (lastSource.allFinite())
    for (const auto& x : last.frame.position) {
      const double d = (x.cast<double>() - lastSource).norm();
      near += d < 0.25;
      atDisk += d < lastRadius + last.frame.spacing;
    }
  std::ostringstream where;
  for (const Source& s : last.sources)
    where << (where.tellp() > 0 ? " " : "") << "(" << number(s.center.x()) << ", "
          << number(s.center.y()) << ", " << number(s.center.z()) << ")";
  std::cout << "closed after " << frames << " frames; simulated " << last.frame.time << " s, "
            << last.frame.step << " steps; " << last.sources.size() << " sources at ["
            << where.str() << "]; " << last.sinks.size() << " sinks, removed "
            << last.removedBySinks << "; " << last.snapshots.size() << " snapshots; erosion.k_eps "
            << last.params.k_eps << "; emitted " << last.emitted << "; painted " << last.painted
            << "; particles within 0.25 m of the last placed or moved source " << near
            << ", around its disk " << atDisk << "; GL errors: " << errors << "\n";
  for (const std::string& line : log) std::cout << "log: " << line << "\n";
  return errors == 0 ? 0 : 1;
}

}  // namespace scour
