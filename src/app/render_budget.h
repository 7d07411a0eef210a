#pragma once
// How much of the water the window draws each frame, so that the window stays responsive (the UI
// and the camera at 20 frames per second or more) whatever the scene and the GPU: on llvmpipe the
// full surface of `lake --scale 0.3` takes about a second a frame. The quality goes down a level
// (a coarser surface grid, then fewer effects, last the particles alone) while frames take longer
// than the budget, and back up when a finer level has room; the user may also pin one. The
// surface is rebuilt only when a new frame of the simulation came; in between the picture is
// drawn again from the last one. Pure logic over measured frame times: no GL, no ImGui
// (tests/app/test_render_budget.cpp).

#include <array>
#include <string>

#include "render/renderer.h"

namespace scour {

class RenderBudget {
 public:
  /// A quality level: its name, its surface grid (cell / Δs) and what it draws.
  struct Level {
    const char* key;  ///< on the command line (--quality)
    const char* name;
    double cellOverSpacing;  ///< 0: no surface, the particles alone
    bool caustics, refraction;
  };
  static constexpr int kLevels = 6;
  static const std::array<Level, kLevels>& levels();
  /// The level of a --quality key, -1 for "auto"; throws std::invalid_argument naming the keys.
  static int parse(const std::string& key);

  /// `budget`: the seconds a frame may take to draw.
  explicit RenderBudget(double budget = 0.04) : budget_(budget) {}

  /// The user's choice: -1 automatic, else a level kept whatever the frame times.
  void choose(int level);
  int choice() const { return choice_; }
  /// The level in use.
  int level() const { return level_; }
  /// The settings to draw this frame with: the user's, with the level's grid and effects.
  RenderSettings apply(RenderSettings s) const;
  /// The seconds the last frame took to draw, at the level in use.
  void measured(double seconds);
  /// "auto: grid 1.5 Δs, 38 ms a frame" or "pinned: particles only, 12 ms a frame".
  std::string describe() const;

 private:
  double budget_;
  int choice_ = -1, level_ = 0;
  int framesAtLevel_ = 0;
  std::array<double, kLevels> seen_{};  ///< the last time measured at each level (0: never)
  std::array<double, 3> recent_{};      ///< the last three frames at this level
};

}  // namespace scour
