#pragma once
// The window's ImGui panels, one function each: given the newest snapshot, the state the panels
// keep between frames and the actions, through which every edit of the scene goes. They read
// no worker and draw nothing but ImGui (the picture is the renderer's).

#include <array>
#include <deque>
#include <functional>
#include <string>

#include "app/actions.h"
#include "app/layout.h"
#include "app/recorder.h"
#include "app/render_budget.h"
#include "render/renderer.h"

namespace scour {

/// The last 200 frames' times [ms]: the paper's Table 1 groups per step, and the render.
struct TimePlots {
  std::deque<float> sph, erosion, boundary, render;
  /// Adds the per-step group times of the steps since the last snapshot.
  void addSteps(const Snapshot& snap);
  void addRender(double seconds);

 private:
  std::array<double, size_t(Pass::kCount)> lastPass_{};
  long lastStep_ = -1;
};

/// What the panels keep between frames besides the scene.
struct PanelState {
  RenderSettings settings;
  /// The erosion map last asked of the worker (cmd::ShowMap), "" for none.
  std::string shownMap;
  /// What the picture can afford each frame (the surface's grid, effects); the Display panel
  /// shows its choice and lets the user pin one.
  RenderBudget budget;
  /// Where the panels go this frame (from the window's size and `wishes`), what each asked for
  /// in the last one, where each was drawn and whether something in it was cut.
  Layout layout;
  std::array<PanelWish, size_t(PanelId::kCount)> wishes;
  std::array<Rect, size_t(PanelId::kCount)> drawn;
  std::array<bool, size_t(PanelId::kCount)> cut{};
  size_t logLines = 0;
  int stepsPerFrame = 1;
  char path[512] = "scour_out";  ///< the File panel's base name
  /// Writes the window's picture to a path (the renderer's).
  std::function<void(const std::string&)> screenshot;
  /// The time-lapse (Run panel): its recording, and the spacing and video the panel sets.
  TimelapseRecorder timelapse;
  int lapseByBed = 0;  ///< 0: every lapseSteps steps, 1: every lapseBedSeconds of bed time
  int lapseSteps = 100;
  float lapseBedSeconds = 0.5f;
  int lapseVideo = 0;  ///< mp4, gif, none
};

/// Sources as stems from the terrain to their centre (highlighted when `hovered` or held),
/// sinks as the outline of their box on the terrain; over the picture, under the panels.
void drawMarkers(const Actions& actions, int hovered);

/// Play, pause, step, reset, undo, redo, steps per frame, the geologic clock, the time-lapse,
/// the snapshots.
void runPanel(const Snapshot& snap, Actions& actions, PanelState& state);
/// Every parameter of the table, by group: sliders (logarithmic over a wide range), choices.
void parametersPanel(const Snapshot& snap, Actions& actions, PanelState& state);
/// What is drawn: terrain colours, water surface and its effects, particles.
void displayPanel(PanelState& state);
/// The tools, rain, and every source and sink with its settings.
void waterPanel(const Snapshot& snap, const SceneSpec& scene, Actions& actions, PanelState& state);
/// Time plots and the soil budget.
void statsPanel(const Snapshot& snap, const TimePlots& plots, PanelState& state);
/// Save and open scenes, checkpoints, terrain and pictures.
void filePanel(Actions& actions, PanelState& state);
/// The actions' and the worker's messages.
void logPanel(const std::vector<std::string>& log, PanelState& state);

}  // namespace scour
