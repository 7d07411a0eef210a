#pragma once
// The one door through which the mouse, the panels and the replay edit the scene: a click on the
// terrain (a source, a sink or painted water, by the tool), a press, drag and release of a
// source's marker, a parameter set, undo and redo, a snapshot restored. Each edit goes to the
// worker as commands and, when it can be taken back, into the edit history. The actions see the
// scene through a View (the newest snapshot and the camera as drawn); they make no GL or ImGui
// call, so they are tested without a window (tests/app/test_actions.cpp).

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "app/edit_history.h"
#include "app/viewport.h"
#include "app/worker.h"

namespace scour {

/// What a left click on the terrain does (a press on a source's marker always drags it).
enum class Tool { kOrbit, kSource, kSink, kBrush };

/// The scene as the user sees it this frame: what the actions pick through.
struct View {
  const Snapshot* snapshot = nullptr;
  Camera camera;
  float aspect = 1;           ///< of the picture (framebuffer width / height)
  int width = 1, height = 1;  ///< of the window, in the mouse's pixels
};

/// A source being dragged across the terrain: every move is an UpdateSource, and the moves of
/// one drag merge into one undoable edit (like a slider drag). It keeps its height above the
/// terrain, its direction, rate and radius.
struct SourceDrag {
  int index = -1;   ///< -1: none
  Source start;     ///< as it was at the press (what undo brings back)
  double lift = 0;  ///< its height above the terrain [m]
  bool moved = false;
  Eigen::Vector3d last = Eigen::Vector3d::Zero();
};

/// How near a press must be to a source's marker to grab it [window pixels].
constexpr float kMarkerPixels = 10;

/// "%.9g": how the log and the parameter edits write a number.
std::string formatNumber(double v);
/// "(x, y, z)", each as formatNumber writes it.
std::string formatPoint(const Eigen::Vector3d& p);

class Actions {
 public:
  using Post = std::function<void(const SimCommand&)>;
  /// `post` sends a command to the worker; `spacing` is the scene's Δs (the tools' sizes).
  Actions(Post post, double spacing);

  /// The view the next actions pick through (once a frame, before any of them).
  void setView(const View& v) { view_ = v; }
  const View& view() const { return view_; }

  /// A click at window pixel (x, y): places a sink or paints water with those tools, else places
  /// a source (the mouse clicks only with a tool on; a replay's click places a source).
  void click(double x, double y);
  /// A press at (x, y): grabs the nearest source marker within kMarkerPixels; false if none.
  bool press(double x, double y);
  /// The grabbed source follows the terrain under (x, y); off the terrain it waits.
  void dragTo(double x, double y);
  /// Lets the grabbed source go (its moves are one edit).
  void release();
  /// Escape during a drag: the source goes back to where it was, and nothing is left to redo.
  void cancelDrag();

  /// A parameter edit, undoable; `extend` merges it into the previous edit of the same key
  /// (a slider being dragged).
  void setParameter(const std::string& key, const std::string& value, bool extend = false);
  /// Any undoable edit (the panels' source and sink edits).
  void perform(Edit e, bool extend);
  void undo();
  void redo();
  /// Back to a kept state. It brings back its own sources and sinks: edits made before it would
  /// undo onto the wrong ones, so the history starts afresh.
  void restoreSnapshot(int id);
  /// The world went back to another state (an automatic rollback): the edits in the history may
  /// name sources that are not there, so it starts afresh; `why` goes to the log.
  void forgetHistory(const std::string& why) {
    history_.clear();
    log_.push_back(why);
  }
  /// A command that is not an edit (play, pause, step, reset, take a snapshot, save, load).
  void command(const SimCommand& c) { post_(c); }

  /// Turns a tool on, or off (back to orbiting) if it is the one on.
  void toggle(Tool t, bool on) { tool = on ? t : (tool == t ? Tool::kOrbit : tool); }

  /// The window pixels of a source's marker: a stem from the terrain under `centre` up to it.
  bool sourceStem(const Eigen::Vector3d& centre, Eigen::Vector2f& foot, Eigen::Vector2f& top) const;
  /// The source whose marker is nearest (x, y), within kMarkerPixels; -1 if none.
  int sourceUnder(double x, double y) const;

  const SourceDrag& drag() const { return drag_; }
  const EditHistory& history() const { return history_; }
  /// What the actions did and why they did nothing, for the Log panel and the exit report.
  std::vector<std::string>& log() { return log_; }
  const std::vector<std::string>& log() const { return log_; }
  /// The source placed or moved last (its centre is NaN if none) and its radius.
  const Eigen::Vector3d& lastSource() const { return lastSource_; }
  double lastRadius() const { return lastRadius_; }

  Tool tool = Tool::kOrbit;
  float brushRadius, sinkRadius;  ///< [m]

 private:
  void post(const std::vector<SimCommand>& commands);
  void placeSink(const Eigen::Vector3f& hit);
  void placeSource(const Eigen::Vector3f& hit);
  const Snapshot& snapshot() const { return *view_.snapshot; }

  Post post_;
  View view_;
  EditHistory history_;
  SourceDrag drag_;
  std::vector<std::string> log_;
  Eigen::Vector3d lastSource_ = Eigen::Vector3d::Constant(NAN);
  double lastRadius_ = 0;
};

}  // namespace scour
