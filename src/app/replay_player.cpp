#include "app/replay_player.h"

#include <algorithm>

namespace scour {

ReplayPlayer::ReplayPlayer(std::vector<ReplayEvent> events,
                           std::function<void(const std::string&)> screenshot)
    : events_(std::move(events)), screenshot_(std::move(screenshot)) {}

void ReplayPlayer::play(long frame, Actions& actions) {
  for (const ReplayEvent& e : events_)
    if (e.frame == frame) playEvent(e.words, frame, actions);
  if (drag_) moveDrag(frame, actions);
}

// The words were checked when the file was read (replay.cpp): every action has its arguments.
void ReplayPlayer::playEvent(const std::vector<std::string>& w, long frame, Actions& actions) {
  if (w[0] == "click") {
    actions.click(std::stod(w[1]), std::stod(w[2]));
  } else if (w[0] == "drag") {
    actions.release();
    drag_ = ScriptedDrag{frame, std::stod(w[1]), std::stod(w[2]), std::stod(w[3]), std::stod(w[4])};
  } else if (w[0] == "place") {
    actions.toggle(Tool::kSource, w[1] == "on");
  } else if (w[0] == "sink") {
    actions.toggle(Tool::kSink, w[1] == "on");
  } else if (w[0] == "brush") {
    actions.toggle(Tool::kBrush, w[1] == "on");
  } else if (w[0] == "set") {
    actions.setParameter(w[1], w[2]);
  } else if (w[0] == "restore") {
    actions.restoreSnapshot(std::stoi(w[1]));
  } else if (w[0] == "press") {
    press(w[1], actions);
  } else if (w[0] == "screenshot") {
    screenshot_(w[1]);
  }
}

void ReplayPlayer::press(const std::string& button, Actions& actions) {
  if (button == "undo")
    actions.undo();
  else if (button == "redo")
    actions.redo();
  else if (button == "snapshot")
    actions.command(cmd::TakeSnapshot{});
  else if (button == "play")
    actions.command(cmd::Resume{});
  else if (button == "pause")
    actions.command(cmd::Pause{});
  else if (button == "step")
    actions.command(cmd::StepOnce{});
  else if (button == "reset")
    actions.command(cmd::Reset{});
}

void ReplayPlayer::moveDrag(long frame, Actions& actions) {
  const long k = frame - drag_->start;
  if (k == 0 && !actions.press(drag_->x0, drag_->y0)) {
    actions.log().push_back("no source under (" + formatNumber(drag_->x0) + ", " +
                            formatNumber(drag_->y0) + ") to drag");
    drag_.reset();
  } else if (k > 0) {
    const double t = std::min(1.0, double(k) / kDragSteps);
    actions.dragTo(drag_->x0 + t * (drag_->x1 - drag_->x0),
                   drag_->y0 + t * (drag_->y1 - drag_->y0));
    if (k >= kDragSteps) actions.release(), drag_.reset();
  }
}

}  // namespace scour
