// The one step driver: it counts and times the steps it runs, says why a run stopped, and a
// run through it is the same run as World::step in a loop.
#include <catch2/catch.hpp>

#include "engine/step_driver.h"
#include "scene/presets.h"

using namespace scour;

TEST_CASE("the step driver runs, times and stops as the caller asks", "[engine][driver]") {
  const Scene s = makePreset("valley", 0.05);
  World driven(s.desc), looped(s.desc);
  double passes = 0, groups = 0;
  long seen = 0;
  const RunEnd end = runSteps(driven, 20, [&](const StepRecord& r) {
    ++seen;
    CHECK(r.stats.step == seen);
    CHECK(r.seconds > 0);
    for (double t : r.passSeconds) passes += t;
    for (double t : r.groupSeconds) groups += t;
  });
  for (int k = 0; k < 20; ++k) looped.step();
  CHECK(end.ok());
  CHECK(std::string(end.statusName()) == "ok");
  CHECK(end.steps == 20);
  CHECK(seen == 20);
  CHECK(driven.stateHash() == looped.stateHash());
  // Every pass falls in one Table 1 group, and the groups add up to the passes.
  CHECK(groups == Approx(passes).epsilon(1e-12));
  double total = 0;
  for (double t : driven.passSeconds()) total += t;
  CHECK(passes <= total);  // the construction's own passes are not a step's
  // runWhile stops when asked.
  const RunEnd half = runWhile(driven, [&] { return driven.time() < 2 * looped.time(); },
                               [](const StepRecord&) {});
  CHECK(half.ok());
  CHECK(driven.time() >= 2 * looped.time());
}

TEST_CASE("the step driver says which way a run stopped", "[engine][driver]") {
  Scene s = makePreset("slope");
  // A fixed step 20× the one the sound speed allows: the run blows up.
  s.desc.params.fixed_dt = 0.01;
  World w(s.desc);
  const RunEnd broken = runSteps(w, 5000);
  CHECK(broken.status == RunEnd::Status::kInvariantViolated);
  CHECK(std::string(broken.statusName()) == "invariant_violated");
  CHECK(broken.steps < 5000);
  CHECK(broken.steps == w.steps() - 1);  // the failed step is not counted
  CHECK_THAT(broken.message, Catch::Contains("step ") && Catch::Contains("particle "));
  CHECK(broken.describe() == "invariant violated at " + broken.message);
  // What the caller does after a step (an output, say) can end the run too.
  World fine(makePreset("valley", 0.05).desc);
  const RunEnd failed = runSteps(fine, 10, [&](const StepRecord& r) {
    if (r.stats.step == 3) throw std::runtime_error("disk full");
  });
  CHECK(failed.status == RunEnd::Status::kFailed);
  CHECK(std::string(failed.statusName()) == "failed");
  CHECK(failed.message == "disk full");
  CHECK(failed.describe() == "the run failed: disk full");
  CHECK(RunEnd{}.describe().empty());
  CHECK(failed.steps == 3);
}

TEST_CASE("a run's progress and ETA come from where it started and its recent rate",
          "[engine][driver]") {
  // A resumed run from step 500 to 1,000: 20 steps/s for the first 10 s (a slow start), then
  // 100 steps/s. The ETA follows the recent rate, not the mean since the start.
  RunProgress p(500, 1000, 5);
  CHECK(p.etaSeconds() < 0);  // no rate yet
  double wall = 0, at = 500;
  for (int k = 0; k < 100; ++k) p.add(wall += 0.1, at += 2);
  CHECK(p.fraction() == Approx(200.0 / 500));
  CHECK(p.etaSeconds() == Approx(300.0 / 20));
  for (int k = 0; k < 100; ++k) p.add(wall += 0.1, at += 10);
  CHECK(p.fraction() == 1.0);
  CHECK(p.etaSeconds() == Approx(0));
  // Six seconds into the fast part of a run to 2,000: the last 5 s were all at 100 steps/s.
  RunProgress r(500, 2000, 5);
  wall = 0, at = 500;
  for (int k = 0; k < 100; ++k) r.add(wall += 0.1, at += 2);
  for (int k = 0; k < 60; ++k) r.add(wall += 0.1, at += 10);
  CHECK(r.fraction() == Approx((1300.0 - 500) / 1500));
  CHECK(r.etaSeconds() == Approx(700.0 / 100).epsilon(0.02));
  // The mean since the start would have said (1,500 − 800) / (800 / 16 s) = 14 s.
}
