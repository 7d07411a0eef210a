#include "app/recorder.h"

#include <chrono>
#include <filesystem>

namespace scour {

namespace fs = std::filesystem;

namespace {

// What the finished video says to the user.
std::string videoMessage(Timelapse& lapse) {
  std::string problem;
  try {
    problem = lapse.finish();
  } catch (const std::exception& e) {  // timelapse.csv could not be written: say so, keep the window
    problem = e.what();
  }
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
  std::error_code ec;
  for (int n = 2; fs::exists(where / "frame_000000.png", ec) && n < 10000; ++n) where = folder + "_" + std::to_string(n);
  try {
    lapse_.emplace(where, o);
  } catch (const std::exception& e) {
    return e.what();
  }
  generation_ = -1;
  return "time-lapse: recording into " + lapse_->folder().string();
}

void TimelapseRecorder::frame(const Snapshot& snap, const std::function<void(const std::string&)>& shot) {
  if (!lapse_) return;
  if (snap.generation != generation_ && generation_ >= 0) lapse_->restart();
  generation_ = snap.generation;
  // A snapshot restored: the clocks went back within a generation.
  if (lapse_->pictures() > 0 && snap.frame.step < lapse_->lastStep()) lapse_->restart();
  if (!lapse_->due(snap.frame.step, snap.morphTime)) return;
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
