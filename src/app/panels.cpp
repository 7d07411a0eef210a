#include "app/panels.h"

#include <imgui.h>
#include <imgui_internal.h>  // a window's content extent (a cut label)

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <initializer_list>
#include <vector>

#include "engine/maps.h"
#include "scene/scene_json.h"

namespace scour {

namespace {

ImVec2 imvec(const Eigen::Vector2f& p) {
  return {p.x(), p.y()};
}

void pushBounded(std::deque<float>& q, float v) {
  q.push_back(v);
  if (q.size() > 200) q.pop_front();
}

// Around a sink's footprint on the terrain, 16 points a side; false if a point is not seen.
bool sinkOutline(const View& view, const Sink& k, std::vector<ImVec2>& outline) {
  const Frame& frame = view.snapshot->frame;
  const double xMax = frame.x0 + (frame.nx - 1) * frame.dx,
               zMax = frame.z0 + (frame.nz - 1) * frame.dz;
  const double x0 = std::max(k.lo.x(), frame.x0), x1 = std::min(k.hi.x(), xMax);
  const double z0 = std::max(k.lo.z(), frame.z0), z1 = std::min(k.hi.z(), zMax);
  if (!(x0 < x1 && z0 < z1)) return false;
  const double corner[5][2] = {{x0, z0}, {x1, z0}, {x1, z1}, {x0, z1}, {x0, z0}};
  for (int side = 0; side < 4; ++side)
    for (int t = 0; t < 16; ++t) {
      const double u = t / 16.0;
      const double x = (1 - u) * corner[side][0] + u * corner[side + 1][0];
      const double z = (1 - u) * corner[side][1] + u * corner[side + 1][1];
      float g = 0;
      Eigen::Vector2f q;
      if (!terrainHeight(frame, x, z, g) ||
          !toWindow(view.camera, view.aspect,
                    Eigen::Vector3f(float(x), g + 0.5f * frame.spacing, float(z)), view.width,
                    view.height, q))
        return false;
      outline.push_back(imvec(q));
    }
  return true;
}

// Stays on the line of the item before if an item `width` wide still fits there.
void sameLineIfFits(float width) {
  const float right = ImGui::GetItemRectMax().x + ImGui::GetStyle().ItemSpacing.x + width;
  if (right <= ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x) ImGui::SameLine();
}

// The width of a checkbox or radio button with this label: its box, a gap, the label.
float toggleWidth(const char* label) {
  return ImGui::GetFrameHeight() + ImGui::GetStyle().ItemInnerSpacing.x +
         ImGui::CalcTextSize(label).x;
}

// One radio button a choice, on one line as far as they fit; returns the index chosen.
int radioRow(int value, std::initializer_list<const char*> labels) {
  int k = 0;
  for (const char* label : labels) {
    if (k > 0) sameLineIfFits(toggleWidth(label));
    ImGui::RadioButton(label, &value, k++);
  }
  return value;
}

// A checkbox on the line of the item before if it fits there, else on the next.
bool flowCheckbox(const char* label, bool* value) {
  sameLineIfFits(toggleWidth(label));
  return ImGui::Checkbox(label, value);
}

void plot(const char* name, const std::deque<float>& q) {
  std::vector<float> v(q.begin(), q.end());
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, "%.2f ms", v.empty() ? 0.0f : v.back());
  ImGui::PlotLines(name, v.data(), int(v.size()), 0, overlay, 0.0f, FLT_MAX, {0, 30});
}

// One panel at its place in the layout, which it may not be moved or resized from; collapsing it
// gives its room to the others. What it asked for (its content's height), where it was drawn and
// whether anything in it was wider than it (a cut label) are kept for the next frame.
class Panel {
 public:
  Panel(PanelState& state, PanelId id) : state_(state), id_(id) {
    const Rect& r = state.layout[id];
    ImGui::SetNextWindowPos({r.x, r.y}, ImGuiCond_Always);
    ImGui::SetNextWindowSize({r.w, r.h}, ImGuiCond_Always);
    open_ = ImGui::Begin(
        panelTitle(id), nullptr,
        ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoSavedSettings);
  }
  ~Panel() {
    PanelWish& wish = state_.wishes[size_t(id_)];
    const ImGuiStyle& style = ImGui::GetStyle();
    wish.collapsed = ImGui::IsWindowCollapsed();
    if (open_) {
      wish.height = ImGui::GetCursorPosY() - style.ItemSpacing.y + style.WindowPadding.y;
      const ImGuiWindow* w = ImGui::GetCurrentWindow();
      state_.cut[size_t(id_)] = w->DC.CursorMaxPos.x > w->WorkRect.Max.x + 0.5f;
    }
    const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    state_.drawn[size_t(id_)] = {pos.x, pos.y, size.x, size.y};
    ImGui::End();
  }
  Panel(const Panel&) = delete;
  Panel& operator=(const Panel&) = delete;
  explicit operator bool() const { return open_; }

 private:
  PanelState& state_;
  PanelId id_;
  bool open_ = false;
};

// A greyed hint, wrapped at the panel's width.
void hint(const char* text) {
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  ImGui::TextWrapped("%s", text);
  ImGui::PopStyleColor();
}

// A button on the line of the one before if it fits there, else on the next: rows of buttons
// that wrap with the panel's width instead of being cut.
bool flowButton(const char* label, bool first = false) {
  if (!first) sameLineIfFits(ImGui::CalcTextSize(label).x + 2 * ImGui::GetStyle().FramePadding.x);
  return ImGui::Button(label);
}

// Widgets' width in this panel: what is left of its width after the widest of these labels,
// which then fit beside them.
void labelRoom(std::initializer_list<const char*> labels) {
  float widest = 0;
  for (const char* l : labels) widest = std::max(widest, ImGui::CalcTextSize(l).x);
  ImGui::PushItemWidth(-(widest + ImGui::GetStyle().ItemInnerSpacing.x + 1));
}

void snapshotsSection(const Snapshot& snap, Actions& actions) {
  if (!ImGui::CollapsingHeader("Snapshots", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (ImGui::Button("take snapshot")) actions.command(cmd::TakeSnapshot{});
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("keeps the terrain, the water, its sediment and the sources as they are now");
  for (const SnapshotInfo& k : snap.snapshots) {
    ImGui::PushID(k.id);
    ImGui::TextWrapped("#%d  t = %.3f s, step %ld, %zu particles", k.id, k.time, k.step,
                       k.particles);
    if (ImGui::SmallButton("restore")) actions.restoreSnapshot(k.id);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(
          "back to this terrain, water and sources, with the parameters as they are now");
    ImGui::SameLine();
    if (ImGui::SmallButton("delete")) actions.command(cmd::DeleteSnapshot{k.id});
    ImGui::PopID();
  }
}

void parameterRow(const Snapshot& snap, const ParamInfo& p, Actions& actions) {
  const std::string key = p.key, id = "##" + key;
  // The label on its own line, whole, and the widget the panel's width under it.
  ImGui::TextWrapped("%s %s%s%s%s", p.label, p.symbol, p.unit && *p.unit ? " [" : "",
                     p.unit ? p.unit : "", p.unit && *p.unit ? "]" : "");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s (%s): %s  valid range [%g, %g]", key.c_str(), p.symbol, p.help, p.min,
                      p.max);
  ImGui::SetNextItemWidth(-FLT_MIN);
  const double current = getParam(snap.params, p);
  if (p.choices) {
    int v = int(current);
    int count = 0;
    while (p.choices[count]) ++count;
    if (ImGui::Combo(id.c_str(), &v, p.choices, count)) actions.setParameter(key, p.choices[v]);
    return;
  }
  double v = current;
  const SliderSpan span = sliderSpan(p);
  if (ImGui::SliderScalar(id.c_str(), ImGuiDataType_Double, &v, &span.lo, &span.hi, "%.4g",
                          span.log ? ImGuiSliderFlags_Logarithmic : 0)) {
    // A value typed with Ctrl+click may lie outside the slider's span, not outside the valid range.
    v = std::clamp(v, p.min, p.max);
    if (p.imember) v = std::round(v);
    actions.setParameter(key, formatNumber(v), ImGui::IsItemActive() && !ImGui::IsItemActivated());
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("%s: drag over [%g, %g]%s; Ctrl+click to type any value in [%g, %g]",
                      key.c_str(), span.lo, span.hi, span.log ? " (logarithmic)" : "", p.min,
                      p.max);
}

void sourceRow(const Snapshot& snap, size_t i, Actions& actions) {
  const float spacing = snap.frame.spacing;
  ImGui::PushID(int(i));
  Source s = snap.sources[i];
  bool changed = false;
  ImGui::Text("source %zu at (%.2f, %.2f, %.2f)", i, s.center.x(), s.center.y(), s.center.z());
  float rate = float(s.rate * 1e3), radius = float(s.radius);
  float dir[3] = {float(s.direction.x()), float(s.direction.y()), float(s.direction.z())};
  if (ImGui::SliderFloat3("direction", dir, -1.0f, 1.0f, "%.2f") &&
      Eigen::Vector3f(dir[0], dir[1], dir[2]).norm() > 1e-3f) {
    s.direction = Eigen::Vector3d(dir[0], dir[1], dir[2]);
    changed = true;
  }
  changed |=
      ImGui::SliderFloat("rate [L/s]", &rate, 0.01f, 50.0f, "%.3g", ImGuiSliderFlags_Logarithmic);
  changed |= ImGui::SliderFloat("radius [m]", &radius, spacing, 50 * spacing, "%.3g");
  if (changed) {
    s.rate = rate * 1e-3, s.radius = radius;
    actions.perform({{cmd::UpdateSource{i, s}},
                     {cmd::UpdateSource{i, snap.sources[i]}},
                     "edit source " + std::to_string(i),
                     "source" + std::to_string(i)},
                    ImGui::IsItemActive() && !ImGui::IsItemActivated());
  }
  if (ImGui::Button("delete"))
    actions.perform({{cmd::RemoveSource{i}},
                     {cmd::AddSource{snap.sources[i]}},
                     "delete source " + std::to_string(i),
                     ""},
                    false);
  ImGui::PopID();
}

void sinkRow(const Snapshot& snap, size_t i, Actions& actions) {
  ImGui::PushID("sink");
  ImGui::PushID(int(i));
  const Sink& k = snap.sinks[i];
  const Eigen::Vector3d centre = 0.5 * (k.lo + k.hi), half = 0.5 * (k.hi - k.lo);
  ImGui::Text("sink %zu at (%.2f, %.2f, %.2f)", i, centre.x(), centre.y(), centre.z());
  float h[3] = {float(half.x()), float(half.y()), float(half.z())};
  if (ImGui::DragFloat3("half-size [m]", h, 0.002f, 0.5f * snap.frame.spacing, 10.0f, "%.3g",
                        ImGuiSliderFlags_AlwaysClamp) &&
      std::isfinite(h[0] + h[1] + h[2]) && std::min({h[0], h[1], h[2]}) > 0) {
    Sink resized;
    const Eigen::Vector3d r(h[0], h[1], h[2]);
    resized.lo = centre - r, resized.hi = centre + r;
    actions.perform({{cmd::UpdateSink{i, resized}},
                     {cmd::UpdateSink{i, k}},
                     "resize sink " + std::to_string(i),
                     "sink" + std::to_string(i)},
                    ImGui::IsItemActive() && !ImGui::IsItemActivated());
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("half the box's size along x, y and z, about its centre");
  if (ImGui::Button("delete"))
    actions.perform(
        {{cmd::RemoveSink{i}}, {cmd::AddSink{k}}, "delete sink " + std::to_string(i), ""}, false);
  ImGui::PopID();
  ImGui::PopID();
}

}  // namespace

void TimePlots::addSteps(const Snapshot& snap) {
  const long step = snap.frame.step;
  if (step > 0 && lastStep_ >= 0 && step > lastStep_) {
    double g[3] = {0, 0, 0};
    for (size_t p = 0; p < size_t(Pass::kCount); ++p) {
      const int k = int(table1Group(Pass(p)));
      if (k < 3) g[k] += (snap.passSeconds[p] - lastPass_[p]) / double(step - lastStep_);
    }
    pushBounded(sph, float(g[0] * 1e3));
    pushBounded(erosion, float(g[1] * 1e3));
    pushBounded(boundary, float(g[2] * 1e3));
  }
  lastPass_ = snap.passSeconds;
  lastStep_ = step;
}

void TimePlots::addRender(double seconds) {
  pushBounded(render, float(seconds * 1e3));
}

void drawMarkers(const Actions& actions, int hovered) {
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  const Snapshot& snap = *actions.view().snapshot;
  const SourceDrag& drag = actions.drag();
  for (size_t i = 0; i < snap.sources.size(); ++i) {
    const bool held = drag.index == int(i);
    Eigen::Vector2f foot, top;
    if (!actions.sourceStem(held && drag.moved ? drag.last : snap.sources[i].center, foot, top))
      continue;
    const ImU32 colour =
        held || hovered == int(i) ? IM_COL32(255, 230, 60, 255) : IM_COL32(255, 140, 30, 230);
    draw->AddLine(imvec(foot), imvec(top), colour, 2.0f);
    draw->AddCircle(imvec(foot), 4.0f, colour, 12, 2.0f);
    draw->AddCircleFilled(imvec(top), 6.0f, colour, 12);
    draw->AddText({top.x() + 8, top.y() - 8}, colour, ("source " + std::to_string(i)).c_str());
  }
  for (size_t i = 0; i < snap.sinks.size(); ++i) {
    std::vector<ImVec2> outline;
    if (!sinkOutline(actions.view(), snap.sinks[i], outline)) continue;
    const ImU32 colour = IM_COL32(200, 80, 255, 230);
    draw->AddPolyline(outline.data(), int(outline.size()), colour, ImDrawFlags_Closed, 2.0f);
    draw->AddText(outline[0], colour, ("sink " + std::to_string(i)).c_str());
  }
}

// A picture every K steps or S seconds of bed time into "<File panel's name>_timelapse/", and a
// video of them when stopped (scene/timelapse.h).
void timelapseSection(Actions& actions, PanelState& state) {
  TimelapseRecorder& rec = state.timelapse;
  if (!ImGui::CollapsingHeader("time-lapse", rec.recording() ? ImGuiTreeNodeFlags_DefaultOpen : 0)) return;
  if (!rec.recording()) {
    state.lapseByBed = radioRow(state.lapseByBed, {"every K steps", "every S s of bed time"});
    labelRoom({"spacing"});
    if (state.lapseByBed == 0) {
      ImGui::InputInt("spacing", &state.lapseSteps);
      state.lapseSteps = std::clamp(state.lapseSteps, 1, 1000000);
    } else {
      ImGui::InputFloat("spacing", &state.lapseBedSeconds, 0, 0, "%.3g s");
      state.lapseBedSeconds = std::clamp(state.lapseBedSeconds, 1e-4f, 1e6f);
    }
    ImGui::PopItemWidth();
    ImGui::Text("video:");
    ImGui::SameLine();
    state.lapseVideo = radioRow(state.lapseVideo, {"mp4", "gif", "none"});
    if (flowButton("record", true)) {
      TimelapseOptions o;
      if (state.lapseByBed == 0)
        o.everySteps = state.lapseSteps;
      else
        o.everyBedSeconds = state.lapseBedSeconds;
      o.video = state.lapseVideo == 0 ? "mp4" : state.lapseVideo == 1 ? "gif" : "none";
      actions.log().push_back(rec.start(std::string(state.path) + "_timelapse", o));
    }
    if (rec.makingVideo()) ImGui::TextWrapped("making the last one's video");
  } else {
    ImGui::TextWrapped("recording: %ld pictures in %s", rec.pictures(), rec.folder().c_str());
    if (flowButton("stop recording", true)) actions.log().push_back(rec.stop());
  }
}

void runPanel(const Snapshot& snap, Actions& actions, PanelState& state) {
  Panel panel(state, PanelId::kRun);
  if (!panel) return;
  if (flowButton(snap.paused ? "Play" : "Pause", true))
    actions.command(snap.paused ? SimCommand(cmd::Resume{}) : SimCommand(cmd::Pause{}));
  if (flowButton("Step")) actions.command(cmd::StepOnce{});
  if (flowButton("Reset")) actions.command(cmd::Reset{});
  if (flowButton("Undo")) actions.undo();
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Ctrl+Z: %s", actions.history().nextUndo()
                                        ? actions.history().nextUndo()->what.c_str()
                                        : "nothing to undo");
  if (flowButton("Redo")) actions.redo();
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Ctrl+Y: %s", actions.history().nextRedo()
                                        ? actions.history().nextRedo()->what.c_str()
                                        : "nothing to redo");
  labelRoom({"steps per frame"});
  if (ImGui::SliderInt("steps per frame", &state.stepsPerFrame, 1, 50))
    actions.command(cmd::SetStepsPerFrame{state.stepsPerFrame});
  ImGui::PopItemWidth();
  const Frame& frame = snap.frame;
  ImGui::TextWrapped("t = %.3f s, step %ld, %zu particles, %.1f steps/s", frame.time, frame.step,
                     frame.particles(), snap.stepsPerSecond);
  // The geologic clock (model.md, "two clocks"): the speed-up, both times, the guard.
  if (const ParamInfo* speedUp = findParam("erosion.morphological_factor")) parameterRow(snap, *speedUp, actions);
  ImGui::TextWrapped("water %.3f s, bed %.4g s (N = %.4g%s)", frame.time, snap.morphTime, snap.factorNow,
                     snap.factorNow < snap.factor ? ", in spin-up" : "");
  const double bound = snap.params.max_bed_step;
  if (snap.guard.lowered > 0)
    ImGui::TextWrapped("bed guard: lowered the speed-up %ld time%s, last at t = %.3f s from %.4g to %.4g",
                       snap.guard.lowered, snap.guard.lowered == 1 ? "" : "s", snap.guard.lastAt,
                       snap.guard.lastFrom, snap.factor);
  else
    ImGui::TextWrapped("bed guard: quiet, the bed moved %.2g Δs in the last step (bound %.2g)",
                       snap.bedStep, bound);
  timelapseSection(actions, state);
  snapshotsSection(snap, actions);  // whole world states to go back to (worker.h)
}

void parametersPanel(const Snapshot& snap, Actions& actions, PanelState& state) {
  Panel panel(state, PanelId::kParameters);
  if (!panel) return;
  std::string group;
  bool open = false;
  for (const ParamInfo& p : paramTable()) {
    const std::string key = p.key, g = key.substr(0, key.find('.'));
    if (g != group) {
      group = g;
      open =
          ImGui::CollapsingHeader(g.c_str(), g == "erosion" ? ImGuiTreeNodeFlags_DefaultOpen : 0);
    }
    if (open) parameterRow(snap, p, actions);
  }
}

void displayPanel(PanelState& state) {
  Panel panel(state, PanelId::kDisplay);
  if (!panel) return;
  RenderSettings& settings = state.settings;
  settings.terrain =
      RenderSettings::Terrain(radioRow(int(settings.terrain), {"shaded", "erosion", "sediment", "map"}));
  if (settings.terrain == RenderSettings::Terrain::kMap) {
    // The erosion maps (engine/maps.h): what the run did, and what the water did over it.
    if (ImGui::BeginCombo("erosion map", settings.map.c_str())) {
      for (const std::string& m : erosionMapNames())
        if (ImGui::Selectable(m.c_str(), m == settings.map)) settings.map = m;
      ImGui::EndCombo();
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("dark: none; blue to yellow: to the map's largest value (flow_direction: hue by direction)");
  }
  ImGui::Checkbox("water surface", &settings.water);
  flowCheckbox("spray", &settings.spray);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("water the surface does not cover (a jet in flight, drops) as sprites");
  ImGui::Checkbox("reflections", &settings.reflections);
  flowCheckbox("refraction", &settings.refraction);
  ImGui::Checkbox("caustics", &settings.caustics);
  ImGui::Text("particles:");
  ImGui::SameLine();
  settings.particles =
      RenderSettings::Particles(radioRow(int(settings.particles), {"off", "C", "speed"}));
  // The water's quality: automatic (as the frame budget allows) or pinned to a level.
  std::vector<const char*> names = {"auto"};
  for (const RenderBudget::Level& l : RenderBudget::levels()) names.push_back(l.name);
  int pick = state.budget.choice() + 1;
  labelRoom({"quality"});
  if (ImGui::Combo("quality", &pick, names.data(), int(names.size())))
    state.budget.choose(pick - 1);
  ImGui::PopItemWidth();
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "auto keeps a frame under 40 ms: a coarser surface grid, fewer effects, "
        "last the particles alone");
  hint(state.budget.describe().c_str());
  hint("left drag: orbit, right drag: pan, wheel: zoom");
}

void waterPanel(const Snapshot& snap, const SceneSpec& scene, Actions& actions, PanelState& state) {
  Panel panel(state, PanelId::kWater);
  if (!panel) return;
  const float spacing = snap.frame.spacing;
  for (auto [t, label] : {std::pair{Tool::kSource, "click the terrain: a source"},
                          std::pair{Tool::kSink, "click the terrain: a sink"},
                          std::pair{Tool::kBrush, "click the terrain: paint water"}}) {
    bool on = actions.tool == t;
    if (ImGui::Checkbox(label, &on)) actions.toggle(t, on);
  }
  hint("drag a source's marker to move it");
  labelRoom({"sink size [m]", "direction", "rate [L/s]", "radius [m]", "half-size [m]"});
  ImGui::SliderFloat("brush [m]", &actions.brushRadius, spacing, 30 * spacing, "%.3g");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the water brush's radius");
  ImGui::SliderFloat("sink size [m]", &actions.sinkRadius, 0.5f * spacing, 30 * spacing, "%.3g",
                     ImGuiSliderFlags_AlwaysClamp);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("half the size of a sink placed by a click");
  Effects effects = scene.effects;
  if (!scene.rain.empty() && ImGui::Checkbox("rain (on reset)", &effects.rain)) {
    actions.command(cmd::SetEffects{effects});
    actions.command(cmd::Reset{});
  }
  ImGui::TextWrapped("%ld particles from sources, %ld painted", snap.emitted, snap.painted);
  for (size_t i = 0; i < snap.sources.size(); ++i) sourceRow(snap, i, actions);
  ImGui::Separator();
  ImGui::TextWrapped("%zu sinks; %ld particles removed by them", snap.sinks.size(),
                     snap.removedBySinks);
  for (size_t i = 0; i < snap.sinks.size(); ++i) sinkRow(snap, i, actions);
  ImGui::PopItemWidth();
}

void statsPanel(const Snapshot& snap, const TimePlots& plots, PanelState& state) {
  Panel panel(state, PanelId::kStats);
  if (!panel) return;
  labelRoom({"boundary"});
  plot("SPH", plots.sph);
  plot("erosion", plots.erosion);
  plot("boundary", plots.boundary);
  plot("render", plots.render);
  ImGui::PopItemWidth();
  ImGui::TextWrapped("soil: terrain %.6g, suspended %.3g, removed %.3g m³", snap.soil.terrain,
                     snap.soil.suspended, snap.soil.removed);
  ImGui::TextWrapped("budget error %.2e (relative)", snap.soil.relativeError());
}

void filePanel(Actions& actions, PanelState& state) {
  Panel panel(state, PanelId::kFile);
  if (!panel) return;
  labelRoom({"name"});
  ImGui::InputText("name", state.path, sizeof state.path);
  ImGui::PopItemWidth();
  hint("files: <name>.json, .ckpt, _height.png, .r32, .obj, _erosion.png, _maps/, _maps_exr/, _shot.png");
  const std::string base = state.path;
  using K = cmd::Save::Kind;
  if (flowButton("save scene", true)) actions.command(cmd::Save{K::kScene, base + ".json"});
  if (flowButton("open scene")) {
    try {
      actions.command(cmd::Load{loadSceneFile(base + ".json")});
    } catch (const std::exception& e) {
      actions.log().push_back(e.what());
    }
  }
  if (flowButton("save checkpoint")) actions.command(cmd::Save{K::kCheckpoint, base + ".ckpt"});
  if (flowButton("resume checkpoint")) actions.command(cmd::LoadCheckpoint{base + ".ckpt"});
  if (flowButton("height PNG")) actions.command(cmd::Save{K::kHeightPng, base + "_height.png"});
  if (flowButton("raw float")) actions.command(cmd::Save{K::kHeightRaw, base + ".r32"});
  if (flowButton("mesh OBJ")) actions.command(cmd::Save{K::kMesh, base + ".obj"});
  if (flowButton("erosion map")) actions.command(cmd::Save{K::kErosionMap, base + "_erosion.png"});
  if (flowButton("maps PNG")) actions.command(cmd::Save{K::kMaps, base + "_maps"});
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("every erosion map as a 16-bit PNG, with maps.json, into <name>_maps/");
  if (flowButton("maps EXR")) actions.command(cmd::Save{K::kMapsExr, base + "_maps_exr"});
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("every erosion map as float32 EXR, with maps.json, into <name>_maps_exr/");
  if (flowButton("screenshot")) {
    try {
      state.screenshot(base + "_shot.png");
      actions.log().push_back("wrote " + base + "_shot.png");
    } catch (const std::exception& e) {
      actions.log().push_back(e.what());
    }
  }
}

void logPanel(const std::vector<std::string>& log, PanelState& state) {
  Panel panel(state, PanelId::kLog);
  if (panel) {
    for (const std::string& line : log) ImGui::TextWrapped("%s", line.c_str());
    if (log.size() != state.logLines) ImGui::SetScrollHereY(1.0f);  // the newest in sight
  }
  state.logLines = log.size();
}

}  // namespace scour
