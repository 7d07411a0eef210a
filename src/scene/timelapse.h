#pragma once
// A time-lapse of a run: a picture every K steps or every S seconds of bed time (the geologic
// clock's, model.md "two clocks"), numbered in order in a folder, a CSV of what each shows, and
// at the end a video made by the `ffmpeg` program. The pictures are the caller's (the run's GL
// renderer, the window's view): this class says when one is due, where it goes, and makes the
// video. Used by `scour run --timelapse` and the window's Run panel (docs/cli.md, docs/app.md).

#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>

namespace scour {

/// A time-lapse that cannot be made as asked (a bad spacing, no ffmpeg, a folder that cannot be
/// made): the message names the setting and the problem.
struct TimelapseError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct TimelapseOptions {
  long everySteps = 0;          ///< > 0: a picture every this many steps
  double everyBedSeconds = 0;   ///< > 0: a picture every this many seconds of bed time
  std::string video = "mp4";    ///< "mp4" (H.264), "gif" or "none" (the pictures alone)
  int fps = 24;                 ///< the video's frames per second
};

/// "250" (steps) or "0.5s" (seconds of bed time) into `o`; TimelapseError naming `flag`.
void parseTimelapseSpacing(const std::string& flag, const std::string& text, TimelapseOptions& o);
/// "mp4", "gif" or "none"; TimelapseError naming `flag`.
void parseTimelapseVideo(const std::string& flag, const std::string& text, TimelapseOptions& o);

/// The ffmpeg program that makes the video: $SCOUR_FFMPEG when set, else `ffmpeg` on the PATH.
/// Empty when there is none.
std::string findFfmpeg();
/// Why no video can be made ("the ffmpeg program, which makes the video, is not …"), or "" when
/// findFfmpeg() finds one.
std::string ffmpegMissing();

class Timelapse {
 public:
  /// Pictures go to `folder` (made; a folder that already holds time-lapse pictures is refused
  /// so two runs never mix), the video beside it as `<folder>.mp4` or `.gif`. Throws
  /// TimelapseError when a video is asked for and there is no ffmpeg, before anything is written.
  Timelapse(std::filesystem::path folder, TimelapseOptions o);

  /// Whether a picture of this state is due: the first call, then every K steps or every S
  /// seconds of bed time since the last picture's.
  bool due(long step, double bedSeconds) const;
  /// The path of the next picture; `added` records it once the caller has written it.
  std::filesystem::path nextPicture() const;
  void added(long step, double waterSeconds, double bedSeconds, double factor);
  /// The clocks went back (a reset, a load, a snapshot restored): the next picture is due at once
  /// and the spacing counts from it.
  void restart() { restarted_ = true; }

  long pictures() const { return count_; }
  /// The step of the last picture (-1 before the first).
  long lastStep() const { return count_ > 0 ? lastStep_ : -1; }
  const std::filesystem::path& folder() const { return folder_; }
  /// The video's path (empty for video "none").
  std::filesystem::path videoPath() const;

  /// Writes timelapse.csv and makes the video from the pictures (two or more; one picture makes
  /// no video). Returns "" when done, else why no video was made (ffmpeg's own words are in
  /// <folder>/ffmpeg.log); the pictures stay either way and no half-written video is left.
  std::string finish();

 private:
  std::filesystem::path folder_;
  TimelapseOptions options_;
  std::string ffmpeg_;
  long count_ = 0, lastStep_ = 0;
  bool restarted_ = false;
  double lastBed_ = 0;
  std::ostringstream csv_;
};

}  // namespace scour
