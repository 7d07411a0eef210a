// The window's time-lapse recorder (app/recorder.h): a picture every K steps from the snapshots
// the window draws, again at once after a reset or a restored snapshot, and the pictures' clocks
// in timelapse.csv when it stops.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "app/recorder.h"

using namespace scour;
namespace fs = std::filesystem;

TEST_CASE("the recorder takes a picture every K steps, and at once after the clocks go back", "[app][timelapse]") {
  const fs::path dir = fs::temp_directory_path() / ("scour_recorder_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  TimelapseRecorder rec;
  TimelapseOptions o;
  o.everySteps = 5, o.video = "none";
  // A trailing separator: the folder is the same, the video would go beside it.
  CHECK(rec.start((dir / "lapse").string() + "/", o) == "time-lapse: recording into " + (dir / "lapse").string());
  std::vector<long> shot;
  auto take = [&](const std::string& path) {
    std::ofstream(path) << "picture";
    shot.push_back(long(shot.size()));
  };
  Snapshot s;
  auto at = [&](long step, long generation) {
    s.frame.step = step, s.frame.time = 0.001 * double(step), s.morphTime = s.frame.time, s.generation = generation;
    rec.frame(s, take);
  };
  for (long step : {0, 2, 4, 5, 7, 10}) at(step, 0);  // pictures at 0, 5, 10
  CHECK(rec.pictures() == 3);
  at(1, 1);  // a reset: a new generation, step 1
  at(3, 1);
  at(6, 1);  // 5 steps after the picture at 1
  CHECK(rec.pictures() == 5);
  at(2, 1);  // a snapshot restored: the step went back within the generation
  CHECK(rec.pictures() == 6);
  CHECK(rec.finishNow() == "time-lapse: 6 pictures in " + (dir / "lapse").string());
  std::ifstream csv(dir / "lapse" / "timelapse.csv");
  std::stringstream text;
  text << csv.rdbuf();
  CHECK(text.str() ==
        "frame,step,hydraulic_s,morphological_s,factor\n"
        "0,0,0,0,1\n1,5,0.005,0.005,1\n2,10,0.01,0.01,1\n3,1,0.001,0.001,1\n4,6,0.006,0.006,1\n5,2,0.002,0.002,1\n");
  fs::remove_all(dir);
}
