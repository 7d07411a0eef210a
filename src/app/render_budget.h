#pragma once
// How much of the water the window draws each frame, and how often it rebuilds the water
// surface, so that the window stays responsive (the UI and the camera at 20 frames per second or
// more) whatever the scene and the GPU: on llvmpipe the full surface of `lake --scale 0.3` took
// about a second a frame. A frame costs its drawing, and, when it rebuilds the surface of a new
// simulation frame, the rebuild. The rebuild comes only every few frames when the budget needs
// it (in between the last surface is drawn from the new camera, and the new frame's particles
// that left it show as spray); the quality goes down a level (a coarser surface grid, then fewer
// effects, last the particles alone) while the frames miss the budget or a rebuild would stall the
// picture for longer than a hitch, and back up when a finer level has room; the user may also pin
// a level. Pure logic over measured frame times: no GL, no ImGui (tests/app/test_render_budget.cpp).

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
    double resolution;  ///< the 3D view's pixels per window pixel, along each side
  };
  static constexpr int kLevels = 7;
  static const std::array<Level, kLevels>& levels();
  /// The level of a --quality key, -1 for "auto"; throws std::invalid_argument naming the keys.
  static int parse(const std::string& key);

  /// `budget`: the seconds a frame may take on average; `hitch`: the longest one frame (one that
  /// rebuilds the surface) may take.
  explicit RenderBudget(double budget = 0.04, double hitch = 0.1) : budget_(budget), hitch_(hitch) {}

  /// The user's choice: -1 automatic, else a level kept whatever the frame times.
  void choose(int level);
  int choice() const { return choice_; }
  /// The level in use.
  int level() const { return level_; }
  /// The settings to draw this frame with: the user's, with the level's grid and effects.
  RenderSettings apply(RenderSettings s) const;
  /// The 3D view's size for a window framebuffer of `w` × `h` (drawn smaller at the last levels,
  /// then stretched over the window).
  std::pair<int, int> viewSize(int w, int h) const;
  /// Whether the frame about to be drawn rebuilds the surface. `newFrame`: the simulation gave a
  /// new frame since the last call. A frame the surface is not rebuilt for is still drawn
  /// (RenderSettings::keep_surface); the rebuild waits for at most every() − 1 frames.
  bool rebuild(bool newFrame);
  /// The seconds the frame took to draw, at the level in use, with or without the rebuild that
  /// rebuild() asked for.
  void measured(double seconds);
  /// Frames from one rebuild of the surface to the next at this level: 1 when a rebuild fits in
  /// every frame, at most kMaxEvery.
  int every() const;
  static constexpr int kMaxEvery = 8;
  /// "auto: grid 1.5 Δs, 38 ms a frame" or, when the surface waits, "auto: grid 1.5 Δs, surface
  /// every 3rd frame (rebuild 90 ms, draw 20 ms), 37 ms a frame".
  std::string describe() const;

 private:
  /// The median of the last three frames of a kind at this level (fewer: their mean); 0 if none.
  struct Recent {
    std::array<double, 3> t{};
    int n = 0;
    void add(double s) { t[size_t(n++ % 3)] = s; }
    double value() const;
  };
  void moveTo(int level);
  /// The mean frame time when the rebuild (`b`) comes every `k` frames and the others draw (`d`).
  static double mean(double b, double d, int k) { return (b + (k - 1) * d) / k; }
  static int everyFor(double b, double d, double budget);
  /// A frame's mean cost at `level` as last seen there, its rebuilds every every() frames; 0: never seen.
  double frameMean(int level) const;

  double budget_, hitch_;
  int choice_ = -1, level_ = 0;
  int framesAtLevel_ = 0, sinceRebuild_ = kMaxEvery;
  bool stale_ = true, rebuilding_ = false;
  Recent build_, draw_, all_;  ///< frames with and without a rebuild, and all, at this level
  /// As last measured at each level (0: never): rebuild frames, draw-only frames; at this level,
  /// what build_ and draw_ hold.
  std::array<double, kLevels> seenBuild_{}, seenDraw_{};
  /// Frames at the level below before a level last seen near its limits is tried again: doubled
  /// each time the level fails soon after it was tried (the first wait is kRetryMin).
  static constexpr int kRetryMin = 60, kRetryMax = 480;
  std::array<int, kLevels> retry_ = [] {
    std::array<int, kLevels> r{};
    r.fill(kRetryMin / 2);
    return r;
  }();
};

}  // namespace scour
