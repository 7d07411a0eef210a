#include "app/replay.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>

#include "scene/input_file.h"
#include "scene/scene_json.h"

namespace scour {

std::vector<ReplayEvent> readReplay(const std::string& path) {
  try {
    return parseReplay(readInputFile(path, "replay file", kMaxReplayBytes), path);
  } catch (const InputFileError& e) {
    throw std::invalid_argument(e.what());
  }
}

std::vector<ReplayEvent> parseReplay(const std::string& text, const std::string& path) {
  std::istringstream in(text);
  std::vector<ReplayEvent> events;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    line = line.substr(0, line.find('#'));  // `#` starts a comment, also after an event
    std::istringstream words(line);
    std::string w;
    ReplayEvent e{0, {}};
    if (!(words >> w)) continue;
    char* end = nullptr;
    e.frame = std::strtol(w.c_str(), &end, 10);
    const std::string at = path + ":" + std::to_string(n) + ": ";
    if (*end != 0 || e.frame < 0) throw std::invalid_argument(at + "expected a frame number first, found '" + excerpt(w) + "'");
    while (words >> w) e.words.push_back(w);
    if (e.words.empty()) throw std::invalid_argument(at + "an action must follow the frame number");
    const std::string& a = e.words[0];
    const std::map<std::string, size_t> arity = {{"click", 3}, {"drag", 5},    {"place", 2},
                                                 {"sink", 2},  {"brush", 2},   {"set", 3},
                                                 {"press", 2}, {"restore", 2}, {"screenshot", 2}};
    auto it = arity.find(a);
    if (it == arity.end())
      throw std::invalid_argument(
          at + "unknown action '" + excerpt(a) +
          "' (click, drag, place, sink, brush, set, press, restore, screenshot)");
    if (e.words.size() != it->second)
      throw std::invalid_argument(at + "'" + a + "' takes " + std::to_string(it->second - 1) + " argument(s)");
    // The arguments are checked here, so a script never fails half-way through a run.
    auto isNumber = [](const std::string& s) {
      char* stop = nullptr;
      const double v = std::strtod(s.c_str(), &stop);
      return !s.empty() && *stop == 0 && std::isfinite(v);
    };
    if (a == "click" || a == "drag")
      for (size_t k = 1; k < e.words.size(); ++k)
        if (!isNumber(e.words[k]))
          throw std::invalid_argument(at + "'" + a + "' takes window pixels, found '" +
                                      excerpt(e.words[k]) + "'");
    if ((a == "place" || a == "sink" || a == "brush") && e.words[1] != "on" && e.words[1] != "off")
      throw std::invalid_argument(at + "'" + a + "' takes on or off, found '" + excerpt(e.words[1]) + "'");
    static const char* const kButtons[] = {"play", "pause", "step",    "reset",
                                           "undo", "redo",  "snapshot"};
    if (a == "press" &&
        std::find(std::begin(kButtons), std::end(kButtons), e.words[1]) == std::end(kButtons))
      throw std::invalid_argument(
          at + "'press' takes play, pause, step, reset, undo, redo or snapshot, found '" +
          excerpt(e.words[1]) + "'");
    if (a == "restore" &&
        (e.words[1].find_first_not_of("0123456789") != std::string::npos || e.words[1].size() > 9))
      throw std::invalid_argument(at + "'restore' takes a snapshot number, found '" + excerpt(e.words[1]) +
                                  "'");
    events.push_back(e);
  }
  return events;
}

}  // namespace scour
