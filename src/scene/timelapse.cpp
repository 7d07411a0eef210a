#include "scene/timelapse.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "scene/output.h"

extern char** environ;

namespace scour {

namespace fs = std::filesystem;

namespace {

constexpr const char* kPicturePattern = "frame_%06d.png";

bool executable(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
}

// Runs `args` (args[0] the program) with its output in `log`; the exit status, or -1 when it
// could not be started.
int runProgram(const std::vector<std::string>& args, const fs::path& log) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  const int err = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (err != 0) return -1;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

// ffmpeg reads '%' in an image sequence's name as a pattern: the folder's own are doubled.
std::string escapePercent(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '%' ? std::string("%%") : std::string(1, c);
  return out;
}

}  // namespace

void parseTimelapseSpacing(const std::string& flag, const std::string& text, TimelapseOptions& o) {
  const bool seconds = !text.empty() && text.back() == 's';
  const std::string number = seconds ? text.substr(0, text.size() - 1) : text;
  char* end = nullptr;
  const double v = std::strtod(number.c_str(), &end);
  const bool parsed = !number.empty() && end == number.c_str() + number.size() && std::isfinite(v);
  if (!parsed || v <= 0 || (!seconds && (v != std::floor(v) || v > 1e12)))
    throw TimelapseError(flag + ": expected a step count (250) or seconds of bed time (0.5s), " +
                         "each > 0, found '" + text + "'");
  o.everySteps = seconds ? 0 : long(v);
  o.everyBedSeconds = seconds ? v : 0;
}

void parseTimelapseVideo(const std::string& flag, const std::string& text, TimelapseOptions& o) {
  if (text != "mp4" && text != "gif" && text != "none")
    throw TimelapseError(flag + ": expected mp4, gif or none, found '" + text + "'");
  o.video = text;
}

std::string findFfmpeg() {
  if (const char* own = std::getenv("SCOUR_FFMPEG")) return executable(own) ? own : "";
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  size_t from = 0;
  while (from <= dirs.size()) {
    const size_t to = std::min(dirs.find(':', from), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(from, to - from).empty() ? "." : dirs.substr(from, to - from)) / "ffmpeg";
    if (executable(candidate)) return candidate.string();
    from = to + 1;
  }
  return "";
}

std::string ffmpegMissing() {
  if (!findFfmpeg().empty()) return "";
  const char* own = std::getenv("SCOUR_FFMPEG");
  return std::string("the ffmpeg program, which makes the video, is not ") +
         (own ? "at $SCOUR_FFMPEG ('" + std::string(own) + "')" : "on the PATH") +
         " (scripts/setup.sh installs it); --timelapse-video none keeps the pictures alone";
}

Timelapse::Timelapse(fs::path folder, TimelapseOptions o) : options_(std::move(o)) {
  // Absolute (ffmpeg never reads a path as an option) and without a trailing separator (the
  // video goes beside the folder, not into it as ".mp4").
  std::error_code ec;
  folder_ = fs::absolute(folder, ec).lexically_normal();
  if (ec) folder_ = folder.lexically_normal();
  if (!folder_.has_filename() && folder_.has_parent_path()) folder_ = folder_.parent_path();
  if (options_.everySteps <= 0 && options_.everyBedSeconds <= 0)
    throw TimelapseError("time-lapse: a spacing in steps or in seconds of bed time is needed");
  if (options_.fps < 1 || options_.fps > 240)
    throw TimelapseError("--timelapse-fps: expected 1 to 240 frames per second, found " +
                         std::to_string(options_.fps));
  if (options_.video != "none") {
    ffmpeg_ = findFfmpeg();
    if (ffmpeg_.empty()) throw TimelapseError("time-lapse: " + ffmpegMissing());
  }
  fs::create_directories(folder_, ec);
  if (ec || !fs::is_directory(folder_, ec))
    throw TimelapseError("time-lapse: cannot create the folder '" + folder_.string() + "'" +
                         (ec ? ": " + ec.message() : ""));
  if (fs::exists(folder_ / "frame_000000.png", ec))
    throw TimelapseError("time-lapse: '" + folder_.string() +
                         "' already holds a time-lapse's pictures; choose another output folder");
  csv_ << "frame,step,hydraulic_s,morphological_s,factor\n";
}

bool Timelapse::due(long step, double bedSeconds) const {
  if (count_ == 0 || restarted_) return true;
  if (options_.everySteps > 0) return step - lastStep_ >= options_.everySteps;
  // A bed time that is a whole number of spacings (up to rounding) is due.
  return bedSeconds - lastBed_ >= options_.everyBedSeconds * (1 - 1e-9);
}

fs::path Timelapse::nextPicture() const {
  char name[32];
  std::snprintf(name, sizeof name, kPicturePattern, int(count_));
  return folder_ / name;
}

void Timelapse::added(long step, double waterSeconds, double bedSeconds, double factor) {
  char row[160];
  std::snprintf(row, sizeof row, "%ld,%ld,%.9g,%.9g,%.9g\n", count_, step, waterSeconds, bedSeconds, factor);
  csv_ << row;
  ++count_;
  restarted_ = false;
  lastStep_ = step;
  lastBed_ = bedSeconds;
}

fs::path Timelapse::videoPath() const {
  if (options_.video == "none") return {};
  fs::path p = folder_;
  return p += "." + options_.video;
}

std::string Timelapse::finish() {
  const std::string table = csv_.str();
  writeAtomically(folder_ / "timelapse.csv", [&](std::ostream& out) { out << table; });
  if (options_.video == "none") return "";
  if (count_ < 2) return "one picture makes no video";
  const fs::path video = videoPath();
  fs::path part = video;
  part += ".tmp-" + std::to_string(::getpid());
  const std::string fps = std::to_string(options_.fps);
  std::vector<std::string> args = {ffmpeg_, "-nostdin", "-hide_banner", "-loglevel", "error", "-y",
                                   "-framerate", fps, "-i", escapePercent(folder_.string()) + "/" + kPicturePattern};
  if (options_.video == "mp4") {
    // H.264 in 4:2:0 plays everywhere; it needs even sides.
    for (const char* a : {"-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt", "yuv420p",
                          "-crf", "20", "-movflags", "+faststart", "-f", "mp4"})
      args.emplace_back(a);
  } else {
    // One palette made for these pictures; at most 640 pixels wide, so the file stays small.
    for (const char* a : {"-vf", "scale='min(640,iw)':-2:flags=lanczos,split[a][b];[a]palettegen[p];[b][p]paletteuse",
                          "-loop", "0", "-f", "gif"})
      args.emplace_back(a);
  }
  args.push_back(part.string());
  const fs::path log = folder_ / "ffmpeg.log";
  const int status = runProgram(args, log);
  std::error_code ec;
  if (status != 0) {
    fs::remove(part, ec);
    return status < 0 ? "cannot start " + ffmpeg_
                      : ffmpeg_ + " exited with status " + std::to_string(status) + " (its words: " + log.string() + ")";
  }
  fs::rename(part, video, ec);
  if (ec) {
    fs::remove(part, ec);
    return "cannot write " + video.string();
  }
  fs::remove(log, ec);  // nothing to say
  return "";
}

}  // namespace scour
