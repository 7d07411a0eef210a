#pragma once
// The one step driver: steps a World while the caller wants more, times every step and its
// passes, and stops at the first step that throws, saying why. `scour run`, `bench`, `stress`,
// `study` and the window's worker all step through it, so a violated invariant, a limit reached
// or any other failure of a step ends every kind of run the same way.

#include <array>
#include <chrono>
#include <deque>
#include <exception>
#include <string>
#include <utility>

#include "engine/world.h"

namespace scour {

/// How a run of steps ended.
struct RunEnd {
  enum class Status { kOk, kInvariantViolated, kLimitExceeded, kFailed };
  Status status = Status::kOk;
  std::string message;  ///< what the step that failed said ("" when ok)
  long steps = 0;       ///< steps done, the failed one not counted
  bool ok() const { return status == Status::kOk; }
  /// "ok", "invariant_violated", "limit_exceeded" or "failed" (summary.json's `status`).
  const char* statusName() const;
  /// How the messages of run, bench and the window say it: "invariant violated at <message>",
  /// "limit reached at <message>", "the run failed: <message>"; "" when ok.
  std::string describe() const;
};

/// One step as it ran: its figures, its wall time, and the time of each pass and each of the
/// paper's Table 1 groups in it.
struct StepRecord {
  StepStats stats;
  double seconds = 0;
  std::array<double, size_t(Pass::kCount)> passSeconds{};
  std::array<double, 4> groupSeconds{};  ///< by Table1Group
};

/// Steps `world` while `more()` is true, calling `each(record)` after every step. A step that
/// throws ends the run: InvariantViolation, LimitExceeded or any other std::exception, each with
/// its message. An exception `each` throws ends it too (as kFailed: an output that cannot be
/// written, say).
template <class More, class Each>
RunEnd runWhile(World& world, More&& more, Each&& each) {
  RunEnd end;
  try {
    while (more()) {
      StepRecord r;
      const auto before = world.passSeconds();
      const auto t0 = std::chrono::steady_clock::now();
      r.stats = world.step();
      r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      for (size_t p = 0; p < size_t(Pass::kCount); ++p) {
        r.passSeconds[p] = world.passSeconds()[p] - before[p];
        r.groupSeconds[size_t(table1Group(Pass(p)))] += r.passSeconds[p];
      }
      ++end.steps;
      each(r);
    }
  } catch (const InvariantViolation& e) {
    end.status = RunEnd::Status::kInvariantViolated, end.message = e.what();
  } catch (const LimitExceeded& e) {
    end.status = RunEnd::Status::kLimitExceeded, end.message = e.what();
  } catch (const std::exception& e) {
    end.status = RunEnd::Status::kFailed, end.message = e.what();
  }
  return end;
}

/// How far a run is between its start and its end (steps, or simulated seconds) and when it will
/// end, from the progress of the last `window` wall seconds: not the run's mean since it
/// started, which a slow start (the first steps, the first picture, a splash settling) skews for
/// the rest of the run.
class RunProgress {
 public:
  RunProgress(double from, double to, double window = 10) : from_(from), to_(to), window_(window) {}
  /// The progress `at` (steps or seconds) reached `wall` seconds after the run started.
  void add(double wall, double at);
  /// Of the way from start to end, in [0, 1].
  double fraction() const;
  /// Wall seconds left at the recent rate; negative while there is no rate yet.
  double etaSeconds() const;

 private:
  double from_, to_, window_;
  std::deque<std::pair<double, double>> samples_;  // (wall, at), the last window_ seconds
};

/// `steps` steps (or fewer, if one fails).
template <class Each>
RunEnd runSteps(World& world, long steps, Each&& each) {
  long done = 0;
  return runWhile(world, [&] { return done++ < steps; }, std::forward<Each>(each));
}

inline RunEnd runSteps(World& world, long steps) {
  return runSteps(world, steps, [](const StepRecord&) {});
}

}  // namespace scour
