#include "app/recorder.h"

#include <chrono>
#include <filesystem>

namespace scour {

namespace fs = std::filesystem;

namespace {

// What the finished video says to the user.
std::string videoMessage(Timelapse& lapse) {
  const std::string problem = lapse.finish();
  const std::string pictures = std::to_string(lapse.pictures()) + " pictures in " + lapse.folder().string();
  if (lapse.videoPath().empty()) return "time-lapse: " + pictures;
  if (!problem.empty()) return "time-lapse: " + pictures + "; no video: " + problem;
  return "time-lapse: " + pictures + ", the video " + lapse.videoPath().string();
}

}  // namespace

TimelapseRecorder::~TimelapseRecorder() {
  if (video_.valid()) video_.wait();
}

std::string TimelapseRecorder::start(const std::string& folder, const TimelapseOptions& o) {
  if (lapse_) return "time-lapse: already recording into " + lapse_->folder().string();
  if (video_.valid()) return "time-lapse: the last one's video is still being made";
  fs::path where = folder;
  for (int n = 2; fs::exists(where / "frame_000000.png") && n < 10000; ++n) where = folder + "_" + std::to_string(n);
  try {
    lapse_.emplace(where, o);
  } catch (const TimelapseError& e) {
    return e.what();
  }
  return "time-lapse: recording into " + where.string();
}

void TimelapseRecorder::frame(const Snapshot& snap, const std::function<void(const std::string&)>& shot) {
  if (!lapse_ || !lapse_->due(snap.frame.step, snap.morphTime)) return;
  shot(lapse_->nextPicture().string());
  lapse_->added(snap.frame.step, snap.frame.time, snap.morphTime, snap.factorNow);
}

std::string TimelapseRecorder::stop() {
  if (!lapse_) return "time-lapse: not recording";
  // The Timelapse moves to the thread that makes the video; it is the thread's alone from here.
  auto lapse = std::make_shared<Timelapse>(std::move(*lapse_));
  lapse_.reset();
  const std::string pictures = std::to_string(lapse->pictures());
  video_ = std::async(std::launch::async, [lapse] { return videoMessage(*lapse); });
  return "time-lapse: stopped after " + pictures + " pictures; making the video";
}

std::optional<std::string> TimelapseRecorder::finished() {
  if (!video_.valid() || video_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return std::nullopt;
  return video_.get();
}

std::string TimelapseRecorder::finishNow() {
  if (lapse_) stop();
  if (!video_.valid()) return "";
  return video_.get();
}

}  // namespace scour
