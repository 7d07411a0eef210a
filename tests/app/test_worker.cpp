// The simulation worker: frames arrive through the triple buffer while the engine steps; commands
// posted from this thread take effect between steps (parameters, sources, pause, single step,
// reset); a bad command is reported, not applied. Built twice: in scour_tests, and with
// ThreadSanitizer in scour_tsan_tests, where parameter edits arrive during steps.
#include <catch2/catch.hpp>

#include <chrono>
#include <thread>

#include "app/worker.h"

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
SceneSpec small() { return presetSpec("default", 0.2); }

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
