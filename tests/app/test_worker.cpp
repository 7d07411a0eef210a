// The simulation worker: frames arrive through the triple buffer while the engine steps; commands
// posted from this thread take effect between steps (parameters, sources, sinks, pause, single
// step, reset, snapshots); a bad command is reported, not applied. Built twice: in scour_tests, and
// with ThreadSanitizer in scour_tsan_tests, where parameter edits arrive during steps.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "app/worker.h"
#include "engine/maps.h"

using namespace scour;

namespace {

// Polls until `done(snapshot)` holds or 60 s pass; checks every snapshot taken is whole.
template <class F>
bool waitFor(SimulationWorker& w, F&& done) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < end) {
    if (w.poll()) {
      const Snapshot& s = w.latest();
      const Frame& f = s.frame;
      REQUIRE(f.position.size() == f.concentration.size());
      REQUIRE(f.position.size() == f.speed.size());
      REQUIRE(f.height.size() == size_t(f.nx) * size_t(f.nz));
      if (done(s)) return true;
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  return false;
}

// Scale 0.2: coarser than this, the default valley is under-resolved (Δs above its grid cell)
// and a splash can pass 0.5 Δs into the terrain.
SceneSpec small() { return presetSpec("valley", 0.2); }

}  // namespace

TEST_CASE("the worker steps and publishes whole frames", "[app][worker]") {
  SimulationWorker w(small());
  long last = -1;
  int frames = 0;
  CHECK(waitFor(w, [&](const Snapshot& s) {
    CHECK(s.frame.step >= last);  // never an older frame after a newer one
    last = s.frame.step;
    return ++frames >= 20 && s.frame.step >= 20;
  }));
}

TEST_CASE("commands take effect between steps", "[app][worker]") {
  SimulationWorker w(small(), /*paused=*/true);
  REQUIRE(waitFor(w, [](const Snapshot& s) { return s.paused; }));
  const long at = w.latest().frame.step;
  w.post(cmd::StepOnce{});
  REQUIRE(waitFor(w, [&](const Snapshot& s) { return s.frame.step == at + 1; }));
  // A parameter edit reaches the engine and the scene.
  w.post(cmd::SetParam{"erosion.k_eps", "0.25"});
  w.post(cmd::StepOnce{});
  REQUIRE(waitFor(w, [&](const Snapshot& s) { return s.frame.step == at + 2; }));
  CHECK(w.latest().params.k_eps == 0.25);
  CHECK(w.spec().params.k_eps == 0.25);
  // A bad one is refused with the reason, and changes nothing.
  w.post(cmd::SetParam{"erosion.k_eps", "-3"});
  w.post(cmd::SetParam{"fluid.spacing", "0.05"});
  w.post(cmd::StepOnce{});
  REQUIRE(waitFor(w, [&](const Snapshot& s) { return s.frame.step == at + 3; }));
  CHECK_THAT(w.latest().error, Catch::Contains("fluid.spacing"));
  CHECK(w.latest().params.k_eps == 0.25);
  // A source placed at a point emits there.
  Source src;
  src.center = {1.0, 0.5, 0.4};
  src.radius = 0.05;
  src.direction = {0, -1, 0};
  src.rate = 0.002;
  w.post(cmd::AddSource{src});
  w.post(cmd::Resume{});
  REQUIRE(waitFor(w, [&](const Snapshot& s) {
    long near = 0;
    for (const auto& x : s.frame.position) near += (x.cast<double>() - src.center).norm() < 0.15;
    return s.sources.size() == 2 && near >= 10;
  }));
  // Reset: back to the start, with the edits kept.
  w.post(cmd::Pause{});
  w.post(cmd::Reset{});
  REQUIRE(waitFor(w, [&](const Snapshot& s) { return s.generation == 2 && s.frame.step == 0; }));
  CHECK(w.latest().sources.size() == 2);
  CHECK(w.latest().params.k_eps == 0.25);
}

TEST_CASE("sinks placed, resized and removed while paused", "[app][worker]") {
  SceneSpec spec = small();
  spec.sinks.clear();
  spec.sources.clear();  // nothing emitted: every particle gone went through a sink or a wall
  SimulationWorker w(spec, /*paused=*/true);
  REQUIRE(waitFor(w, [](const Snapshot& s) { return s.paused; }));
  const size_t before = w.latest().frame.particles();
  REQUIRE(before > 100);
  long step = w.latest().frame.step;
  auto stepOnce = [&] {
    w.post(cmd::StepOnce{});
    ++step;
    REQUIRE(waitFor(w, [&](const Snapshot& s) { return s.frame.step == step; }));
  };
  // An empty box is refused, and nothing changes.
  w.post(cmd::AddSink{Sink{{0.1, 0.5, 0.1}, {0.0, 0.6, 0.2}}});
  stepOnce();
  CHECK_THAT(w.latest().error, Catch::Contains("sink"));
  CHECK(w.latest().sinks.empty());
  CHECK(w.latest().removedBySinks == 0);
  // A sink over part of the water resting at the upper end takes what lies in it, and says so.
  const Sink part{{0.0, -1.0, 0.0}, {0.15, 3.0, 0.8}};
  w.post(cmd::AddSink{part});
  stepOnce();
  const long first = w.latest().removedBySinks;
  CHECK(w.latest().sinks.size() == 1);
  CHECK(w.spec().sinks.size() == 1);
  CHECK(first > 0);
  CHECK(w.latest().frame.particles() <= before - size_t(first));
  CHECK(w.latest().soil.relativeError() < 1e-6);
  // Widened over the whole block, it takes the rest of it.
  Sink wide = part;
  wide.hi.x() = 0.4;
  w.post(cmd::UpdateSink{0, wide});
  stepOnce();
  CHECK(w.latest().sinks.at(0).hi.x() == 0.4);
  CHECK(w.spec().sinks.at(0).hi.x() == 0.4);
  const long second = w.latest().removedBySinks;
  CHECK(second > first);
  // A sink that does not exist, or a bad box, is refused.
  w.post(cmd::UpdateSink{5, wide});
  stepOnce();
  CHECK_THAT(w.latest().error, Catch::Contains("sink 5 does not exist"));
  w.post(cmd::UpdateSink{0, Sink{wide.hi, wide.lo}});
  stepOnce();
  CHECK_THAT(w.latest().error, Catch::Contains("max must exceed min"));
  CHECK(w.latest().sinks.at(0).hi.x() == 0.4);
  // Removed: what it took stays counted, in the budget too.
  w.post(cmd::RemoveSink{0});
  stepOnce();
  CHECK(w.latest().sinks.empty());
  CHECK(w.spec().sinks.empty());
  CHECK(w.latest().removedBySinks >= second);
  CHECK(w.latest().soil.relativeError() < 1e-6);
  w.post(cmd::RemoveSink{0});
  stepOnce();
  CHECK_THAT(w.latest().error, Catch::Contains("sink 0 does not exist"));
}

TEST_CASE("a snapshot brings the terrain back exactly", "[app][worker]") {
  SimulationWorker w(small());
  // Some steps first, so the state kept is not the scene's start.
  REQUIRE(waitFor(w, [](const Snapshot& s) { return s.frame.step >= 10; }));
  w.post(cmd::Pause{});
  REQUIRE(waitFor(w, [](const Snapshot& s) { return s.paused; }));
  w.post(cmd::TakeSnapshot{});
  REQUIRE(waitFor(w, [](const Snapshot& s) { return s.snapshots.size() == 1; }));
  const Snapshot kept = w.latest();
  const SnapshotInfo info = kept.snapshots[0];
  CHECK(info.step == kept.frame.step);
  CHECK(info.time == kept.frame.time);
  CHECK(info.particles == kept.frame.particles());
  // Erosion and deposition change the terrain; a source added since does not survive a restore.
  Source extra = kept.sources.at(0);
  extra.center.z() += 0.2;
  w.post(cmd::AddSource{extra});
  w.post(cmd::Resume{});
  REQUIRE(waitFor(w, [&](const Snapshot& s) {
    return s.frame.height != kept.frame.height && s.sources.size() == 2;
  }));
  w.post(cmd::Pause{});
  w.post(cmd::RestoreSnapshot{info.id});
  REQUIRE(waitFor(w, [&](const Snapshot& s) { return s.generation == kept.generation + 1; }));
  const Snapshot& back = w.latest();
  INFO(back.error);
  CHECK(back.error.empty());
  CHECK(back.frame.height == kept.frame.height);  // exactly
  CHECK(back.frame.change == kept.frame.change);
  CHECK(back.frame.step == kept.frame.step);
  CHECK(back.frame.time == kept.frame.time);
  CHECK(back.frame.position == kept.frame.position);
  CHECK(back.sources.size() == 1);
  CHECK(w.spec().sources.size() == 1);
  // The soil budget is the one kept, so it still closes.
  CHECK(back.soil.terrain == kept.soil.terrain);
  CHECK(back.soil.suspended == kept.soil.suspended);
  CHECK(back.soil.removed == kept.soil.removed);
  CHECK(back.soil.initial == kept.soil.initial);
  CHECK(back.soil.relativeError() < 1e-6);
  CHECK(back.snapshots.size() == 1);  // still there, to go back to again
  // It steps on from there.
  w.post(cmd::StepOnce{});
  REQUIRE(waitFor(w, [&](const Snapshot& s) { return s.frame.step == kept.frame.step + 1; }));
  CHECK(w.latest().error.empty());
  // Deleted, it is gone; restoring it then is refused and changes nothing.
  w.post(cmd::DeleteSnapshot{info.id});
  w.post(cmd::RestoreSnapshot{info.id});
  w.post(cmd::StepOnce{});
  REQUIRE(waitFor(w, [&](const Snapshot& s) { return s.frame.step == kept.frame.step + 2; }));
  CHECK(w.latest().snapshots.empty());
  CHECK_THAT(w.latest().error, Catch::Contains("does not exist"));
  CHECK(w.latest().generation == kept.generation + 1);
}

TEST_CASE("a broken invariant rolls back to a recent state with a smaller step and runs on",
          "[app][worker][rollback]") {
  SimulationWorker w(small(), /*paused=*/true);
  REQUIRE(waitFor(w, [](const Snapshot& s) { return s.paused; }));
  // Four times the stable step: the water blows up within a few dozen steps.
  w.post(cmd::SetParam{"time.fixed_dt", "0.004"});
  w.post(cmd::Resume{});
  REQUIRE(waitFor(w, [](const Snapshot& s) { return s.rollbacks >= 1; }));
  const std::string said = w.latest().error;
  INFO(said);
  CHECK(said.rfind("invariant violated at step ", 0) == 0);
  CHECK(said.find("; the edit before it: time.fixed_dt = 0.004 at step 0. Rolled back to step 0 "
                  "(t = 0 s) with a smaller time step (time.cfl 0.2, time.force_cfl 0.125, "
                  "time.fixed_dt 0.002); running on") != std::string::npos);
  // It goes on by itself, never paused, at the halved step, and keeps every invariant.
  REQUIRE(waitFor(w, [](const Snapshot& s) { return s.frame.step >= 300; }));
  const Snapshot& s = w.latest();
  CHECK_FALSE(s.paused);
  CHECK(s.params.fixed_dt == 0.002);
  CHECK(s.rollbacks == 1);
  CHECK(s.soil.relativeError() < 1e-6);
}

TEST_CASE("parameter edits arriving during steps are safe", "[app][worker][tsan]") {
  SimulationWorker w(small());
  // This thread edits while the worker steps and reads every frame it gets.
  // At least 3 s and 4 frames (the machine may be busy), at most 60 s.
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::steady_clock::now() - start; };
  int k = 0;
  long frames = 0;
  while ((elapsed() < std::chrono::seconds(3) || frames < 4) && elapsed() < std::chrono::seconds(60)) {
    w.post(cmd::SetParam{"erosion.k_eps", std::to_string(0.05 + 0.01 * (k % 10))});
    w.post(cmd::SetParam{"erosion.tau_c", std::to_string(1.0 + (k % 7))});
    if (k % 50 == 0) w.post(cmd::PaintWater{{0.6, 0.6, 0.4}, 0.05});
    ++k;
    if (w.poll()) {
      const Frame& f = w.latest().frame;
      REQUIRE(f.position.size() == f.concentration.size());
      ++frames;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  CHECK(frames > 3);
  INFO(w.latest().error);
  CHECK(w.latest().error.empty());
}

TEST_CASE("the frames carry the erosion map the display asks for; the File panel writes them all", "[app][worker]") {
  SimulationWorker w(small(), /*paused=*/true);
  REQUIRE(waitFor(w, [](const Snapshot& s) { return s.paused; }));
  CHECK(w.latest().frame.map.empty());
  w.post(cmd::ShowMap{"flow_direction"});
  w.post(cmd::StepOnce{});
  REQUIRE(waitFor(w, [](const Snapshot& s) { return s.frame.mapName == "flow_direction"; }));
  const Frame& f = w.latest().frame;
  CHECK(f.map.size() == f.height.size());
  CHECK(f.map2.size() == f.height.size());
  w.post(cmd::ShowMap{"nonsense"});
  w.post(cmd::StepOnce{});
  REQUIRE(waitFor(w, [](const Snapshot& s) { return !s.error.empty(); }));
  CHECK(w.latest().error == "no erosion map called 'nonsense'");
  w.post(cmd::ShowMap{""});
  w.post(cmd::StepOnce{});
  REQUIRE(waitFor(w, [](const Snapshot& s) { return s.frame.mapName.empty() && s.frame.map.empty(); }));
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("scour_worker_maps_" + std::to_string(::getpid()));
  w.post(cmd::Save{cmd::Save::Kind::kMaps, dir.string()});
  REQUIRE(waitFor(w, [&](const Snapshot& s) { return s.notice == "wrote " + dir.string(); }));
  for (const std::string& m : erosionMapNames()) CHECK(std::filesystem::exists(dir / (m + ".png")));
  CHECK(std::filesystem::exists(dir / "maps.json"));
  std::filesystem::remove_all(dir);
}
