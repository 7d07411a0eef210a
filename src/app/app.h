#pragma once
// The interactive sandbox: a window that shows the newest frame of the simulation worker, with
// Dear ImGui panels to run it, edit every parameter, place sources and choose what is drawn.
#include <string>
#include <vector>

#include "app/replay.h"
#include "scene/presets.h"
#include "scene/timelapse.h"

namespace scour {

struct AppOptions {
  int width = 1280, height = 720;
  long quitAfterFrames = 0;  ///< > 0: close after this many frames (tests)
  std::string screenshot;    ///< write the last frame's picture here on exit
  bool paused = false;
  int terrain = 1;           ///< the terrain colours at the start: 0 shaded, 1 erosion, 2 sediment
  std::string replay;        ///< a file of scripted input events (see docs/app.md)
  /// With quitAfterFrames: the last frame as seen, panels included, as DIR/window.png, and each
  /// panel as DIR/panel_<title>.png
  std::string panelShots;
  int quality = -1;  ///< the water's quality level (RenderBudget), -1 automatic
  double quitAfterSeconds = 0;  ///< > 0: close after this long (bench --with-window)
  struct Stats {
    long frames = 0, steps = 0;  ///< drawn; simulated while the window was open
    double seconds = 0;
    std::string quality;  ///< the water's quality at the end (RenderBudget::describe)
    long rebuilds = 0;    ///< frames that rebuilt the water surface
    long surfaceFrames = 0;  ///< frames drawn with the water surface (kept or rebuilt)
    long levelChanges = 0;   ///< times the quality level changed
    std::vector<double> frameSeconds;  ///< each frame, from the start of one to the next
  };
  Stats* stats = nullptr;    ///< filled on closing when set
  /// A spacing set: record a time-lapse from the start into timelapseFolder (the Run panel's).
  TimelapseOptions timelapse{0, 0, "mp4", 24};
  std::string timelapseFolder = "scour_out_timelapse";
};


/// Opens the window on the scene and runs until it is closed. Throws GlError if no window can
/// be made.
int runApp(const SceneSpec& spec, const AppOptions& o);

}  // namespace scour
