#pragma once
// Plays a replay file (replay.h) through the actions, frame by frame, as the mouse and the
// panels would: a scripted drag is a press, eight moves and a release, one a frame.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/actions.h"
#include "app/replay.h"

namespace scour {

class ReplayPlayer {
 public:
  /// `screenshot` writes the window's picture to a path (the renderer's, in the window).
  ReplayPlayer(std::vector<ReplayEvent> events, std::function<void(const std::string&)> screenshot);

  /// Plays the events of frame `frame`, and the next move of a scripted drag.
  void play(long frame, Actions& actions);
  /// A scripted drag holds the (virtual) mouse: the real one is not read meanwhile.
  bool holdsMouse() const { return drag_.has_value(); }

  /// Moves of a scripted drag, a frame each.
  static constexpr int kDragSteps = 8;

 private:
  void playEvent(const std::vector<std::string>& words, long frame, Actions& actions);
  void press(const std::string& button, Actions& actions);
  void moveDrag(long frame, Actions& actions);

  struct ScriptedDrag {
    long start;
    double x0, y0, x1, y1;
  };
  std::vector<ReplayEvent> events_;
  std::function<void(const std::string&)> screenshot_;
  std::optional<ScriptedDrag> drag_;
};

}  // namespace scour
