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
#include <sstream>

#include "app/worker.h"
#include "render/context.h"
#include "render/renderer.h"
#include "scene/scene_json.h"

namespace scour {

namespace {

// Orbit camera: yaw and pitch around a target, at a distance.
struct Orbit {
  Eigen::Vector3f target = Eigen::Vector3f::Zero();
  float yaw = -0.6f, pitch = 0.7f, distance = 3.0f;
  Camera camera() const {
    Camera c;
    c.target = target;
    c.eye = target + distance * Eigen::Vector3f(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                                std::cos(pitch) * std::cos(yaw));
    return c;
  }
};

Orbit orbitFor(const Frame& f) {
  const Camera c = overviewCamera(f);
  Orbit o;
  o.target = c.target;
  const Eigen::Vector3f d = c.eye - c.target;
  o.distance = d.norm();
  o.pitch = std::asin(d.y() / o.distance);
  o.yaw = std::atan2(d.x(), d.z());
  return o;
}

// The point of the terrain under the mouse: march along the ray through the pixel.
bool pickTerrain(const Frame& f, const Camera& c, float aspect, double mx, double my, int w, int h,
                 Eigen::Vector3f& hit) {
  const Eigen::Matrix4f inv = (c.projection(aspect, 0.01f, 1000.0f) * c.view()).inverse();
  const float x = float(2 * mx / w - 1), y = float(1 - 2 * my / h);
  Eigen::Vector4f a = inv * Eigen::Vector4f(x, y, -1, 1), b = inv * Eigen::Vector4f(x, y, 1, 1);
  const Eigen::Vector3f p0 = a.head<3>() / a.w(), p1 = b.head<3>() / b.w();
  const Eigen::Vector3f dir = (p1 - p0).normalized();
  auto height = [&](float px, float pz, float& hgt) {
    const double u = (px - f.x0) / f.dx, v = (pz - f.z0) / f.dz;
    if (u < 0 || v < 0 || u > f.nx - 1 || v > f.nz - 1) return false;
    const int i = std::min(int(u), f.nx - 2), k = std::min(int(v), f.nz - 2);
    const float fu = float(u - i), fv = float(v - k);
    auto at = [&](int di, int dk) { return f.height[size_t(k + dk) * size_t(f.nx) + size_t(i + di)]; };
    hgt = (1 - fv) * ((1 - fu) * at(0, 0) + fu * at(1, 0)) + fv * ((1 - fu) * at(0, 1) + fu * at(1, 1));
    return true;
  };
  const float step = float(std::min(f.dx, f.dz)) * 0.5f;
  Eigen::Vector3f p = p0;
  for (int s = 0; s < 200000; ++s, p += step * dir) {
    float hgt = 0;
    if (height(p.x(), p.z(), hgt) && p.y() <= hgt) {
      hit = {p.x(), hgt, p.z()};
      return true;
    }
    if ((p - p0).norm() > 1000) break;
  }
  return false;
}

std::string number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

}  // namespace

std::vector<ReplayEvent> readReplay(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(path + ": cannot open the replay file");
  std::vector<ReplayEvent> events;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    std::istringstream words(line);
    std::string w;
    ReplayEvent e{0, {}};
    if (!(words >> w) || w[0] == '#') continue;
    char* end = nullptr;
    e.frame = std::strtol(w.c_str(), &end, 10);
    const std::string at = path + ":" + std::to_string(n) + ": ";
    if (*end != 0 || e.frame < 0) throw std::invalid_argument(at + "expected a frame number first, found '" + w + "'");
    while (words >> w) e.words.push_back(w);
    if (e.words.empty()) throw std::invalid_argument(at + "an action must follow the frame number");
    const std::string& a = e.words[0];
    const std::map<std::string, size_t> arity = {{"click", 3}, {"place", 2}, {"brush", 2}, {"set", 3},
                                                 {"press", 2}, {"screenshot", 2}};
    auto it = arity.find(a);
    if (it == arity.end())
      throw std::invalid_argument(at + "unknown action '" + a + "' (click, place, brush, set, press, screenshot)");
    if (e.words.size() != it->second)
      throw std::invalid_argument(at + "'" + a + "' takes " + std::to_string(it->second - 1) + " argument(s)");
    events.push_back(e);
  }
  return events;
}

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
  bool haveCamera = false, placing = false, brushing = false;
  float brushRadius = 4 * spec.params.spacing;
  char path[512] = "scour_out";
  Eigen::Vector3d lastSource = Eigen::Vector3d::Constant(NAN);

  long frames = 0;
  long lastGeneration = -1;
  std::deque<float> sph, erosion, boundary, render;
  std::array<double, size_t(Pass::kCount)> lastPass{};
  long lastStep = -1;
  std::vector<std::string> log;
  std::string lastError, lastNotice;
  // Undo/redo of parameter and source edits: each edit keeps the commands that redo and undo it.
  struct Edit {
    std::vector<SimCommand> redo, undo;
    std::string what, key;  // key: a parameter edit that a slider drag may extend
  };
  std::vector<Edit> undoStack, redoStack;
  auto perform = [&](Edit e, bool extend) {
    if (extend && !undoStack.empty() && !e.key.empty() && undoStack.back().key == e.key) {
      undoStack.back().redo = e.redo;  // one drag, one edit: keep the value from before it
    } else {
      undoStack.push_back(e);
    }
    redoStack.clear();
    for (const SimCommand& c : e.redo) worker.post(c);
  };
  // Undo takes the newest edit off the undo stack and posts its undo commands; redo the reverse.
  auto travel = [&](std::vector<Edit>& from, std::vector<Edit>& to, bool back) {
    if (from.empty()) return;
    Edit e = std::move(from.back());
    from.pop_back();
    for (const SimCommand& c : back ? e.undo : e.redo) worker.post(c);
    log.push_back((back ? "undo: " : "redo: ") + e.what);
    to.push_back(std::move(e));
  };
  auto undo = [&] { travel(undoStack, redoStack, true); };
  auto redo = [&] { travel(redoStack, undoStack, false); };
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

    // Mouse: orbit (left drag), pan (right drag), zoom (wheel); a click places a source when
    // the Water panel's "place" mode is on. Only when ImGui does not want the mouse.
    // A click on the terrain places a source or paints water (the real mouse and the replay
    // take this same path).
    auto clickAt = [&](double cx, double cy) {
      Eigen::Vector3f hit;
      int ww = 0, wh = 0;
      glfwGetWindowSize(window, &ww, &wh);
      if (!pickTerrain(frame, orbit.camera(), float(fbw) / float(fbh), cx, cy, ww, wh, hit)) {
        log.push_back("no terrain under the mouse");
        return;
      }
      if (brushing) {
        worker.post(cmd::PaintWater{hit.cast<double>() + Eigen::Vector3d(0, brushRadius, 0), brushRadius});
        log.push_back("painted water at (" + number(hit.x()) + ", " + number(hit.y()) + ", " + number(hit.z()) + ")");
        return;
      }
      Source s;
      s.center = hit.cast<double>() + Eigen::Vector3d(0, 6 * frame.spacing, 0);
      s.radius = 3 * frame.spacing;
      s.direction = {0, -1, 0};
      s.rate = 50 * std::pow(double(frame.spacing), 2);  // about 1 m/s out of the disk
      perform({{cmd::AddSource{s}}, {cmd::RemoveSource{snap.sources.size()}}, "place a source", ""}, false);
      lastSource = s.center;
      log.push_back("source placed at (" + number(s.center.x()) + ", " + number(s.center.y()) + ", " + number(s.center.z()) + ")");
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
      else if (w[0] == "place") placing = w[1] == "on", brushing = brushing && !placing;
      else if (w[0] == "brush") brushing = w[1] == "on", placing = placing && !brushing;
      else if (w[0] == "set") setParameter(w[1], w[2]);
      else if (w[0] == "press") {
        if (w[1] == "undo") undo();
        else if (w[1] == "redo") redo();
        else if (w[1] == "play") worker.post(cmd::Resume{});
        else if (w[1] == "pause") worker.post(cmd::Pause{});
        else if (w[1] == "step") worker.post(cmd::StepOnce{});
        else if (w[1] == "reset") worker.post(cmd::Reset{});
      } else if (w[0] == "screenshot") renderer.writePng(w[1]);
    }

    double mx = 0, my = 0;
    glfwGetCursorPos(window, &mx, &my);
    if (!io.WantCaptureMouse) {
      const float dx = float(mx - lastX), dy = float(my - lastY);
      if ((placing || brushing) && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
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
    if (ImGui::IsItemHovered() && !undoStack.empty()) ImGui::SetTooltip("%s", undoStack.back().what.c_str());
    ImGui::SameLine();
    if (ImGui::Button("Redo")) redo();
    if (ImGui::IsItemHovered() && !redoStack.empty()) ImGui::SetTooltip("%s", redoStack.back().what.c_str());
    if (!io.WantCaptureKeyboard && io.KeyCtrl) {
      if (ImGui::IsKeyPressed(ImGuiKey_Z)) undo();
      if (ImGui::IsKeyPressed(ImGuiKey_Y)) redo();
    }
    if (ImGui::SliderInt("steps per frame", &stepsPerFrame, 1, 50)) worker.post(cmd::SetStepsPerFrame{stepsPerFrame});
    ImGui::Text("t = %.3f s   step %ld   %zu particles", frame.time, frame.step, frame.particles());
    ImGui::Text("%.1f steps/s", snap.stepsPerSecond);
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
    ImGui::TextDisabled("left drag: orbit, right drag: pan, wheel: zoom");
    ImGui::End();

    ImGui::SetNextWindowPos({float(fbw) - 330, 200}, ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize({320, 0}, ImGuiCond_FirstUseEver);
    ImGui::Begin("Water");
    if (ImGui::Checkbox("click the terrain to place a source", &placing) && placing) brushing = false;
    if (ImGui::Checkbox("brush: click to paint water", &brushing) && brushing) placing = false;
    ImGui::SliderFloat("brush radius [m]", &brushRadius, frame.spacing, 30 * frame.spacing, "%.3g");
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
  long near = 0;
  if (lastSource.allFinite())
    for (const auto& x : last.frame.position) near += (x.cast<double>() - lastSource).norm() < 0.25;
  std::cout << "closed after " << frames << " frames; simulated " << last.frame.time << " s, "
            << last.frame.step << " steps; " << last.sources.size() << " sources; erosion.k_eps "
            << last.params.k_eps << "; emitted " << last.emitted << "; painted " << last.painted
            << "; particles within 0.25 m of the last placed source " << near << "; GL errors: " << errors << "\n";
  for (const std::string& line : log) std::cout << "log: " << line << "\n";
  return errors == 0 ? 0 : 1;
}

}  // namespace scour
