#pragma once
// The window's time-lapse: while recording, a picture of the view every K steps or every S
// seconds of bed time, from the snapshots the window draws; on stopping, the video is made on
// a thread of its own so the window stays live (scene/timelapse.h does the files). No GL, no
// ImGui: the picture is taken by the function it is given.

#include <functional>
#include <future>
#include <optional>
#include <string>

#include "app/worker.h"
#include "scene/timelapse.h"

namespace scour {

class TimelapseRecorder {
 public:
  ~TimelapseRecorder();  ///< waits for a video still being made

  /// Starts recording into `folder`, or the first of `folder`_2, _3, … that holds no time-lapse
  /// yet. Returns what to tell the user: where the pictures go, or why it cannot record.
  std::string start(const std::string& folder, const TimelapseOptions& o);
  /// With a snapshot the window shows: a picture through `shot` when one is due. A reset or a
  /// load (a new generation) does not end the recording; the pictures go on from the new state.
  void frame(const Snapshot& snap, const std::function<void(const std::string&)>& shot);
  /// Stops recording and starts making the video. Returns what to tell the user.
  std::string stop();
  /// Once the video begun by stop() is made: what to tell the user (once); else nothing.
  std::optional<std::string> finished();
  /// Stops if recording and waits for the video; what to tell the user ("" if not recording).
  std::string finishNow();

  bool recording() const { return lapse_.has_value(); }
  bool makingVideo() const { return video_.valid(); }
  long pictures() const { return lapse_ ? lapse_->pictures() : 0; }
  std::string folder() const { return lapse_ ? lapse_->folder().string() : ""; }

 private:
  std::optional<Timelapse> lapse_;
  long generation_ = -1;  ///< the snapshots' generation of the last picture (resets, loads)
  std::future<std::string> video_;
};

}  // namespace scour
