#pragma once
// Replay files: scripted input events for the window (docs/app.md), read and checked in full
// before any window opens, so a script never fails half-way through a run. No GL: the fuzzer and
// the tests read them without a display.
#include <cstddef>
#include <string>
#include <vector>

namespace scour {

/// One scripted event: at frame `frame`, an action with its words ("click 320 200").
struct ReplayEvent {
  long frame;
  std::vector<std::string> words;
};

/// Largest replay file read [bytes].
constexpr size_t kMaxReplayBytes = size_t(1) << 20;

/// Reads a replay file; throws std::invalid_argument naming the file, line and problem.
std::vector<ReplayEvent> readReplay(const std::string& path);
/// The same from the file's text; `path` names it in messages.
std::vector<ReplayEvent> parseReplay(const std::string& text, const std::string& path);

}  // namespace scour
