#pragma once
// The simulation on its own thread. It steps a World (OpenMP inside each step) and after every
// step publishes a Frame with the run's figures through a triple buffer: the renderer draws the
// newest complete one, never waits for a step and never sees a half-written one. Nothing else
// touches the World: the UI posts commands to a queue that the worker drains between steps.
//
// Snapshots to go back to are whole world states (World::saveState) kept by the worker with the
// scene they were taken in: a restore builds a fresh World from that scene and loads the state
// into it, so the terrain, the water, the suspended sediment and what the sinks removed come back
// together and the soil budget stays closed. A restore that fails leaves the running World as it
// was. The UI sees only their list (id, time, step) in each Snapshot.
//
// A sandbox must not lose the user's work: the worker also keeps a ring of automatic states (one
// every kRingEvery steps, the last kRingSize). When a step breaks an invariant, it goes back to
// the newest of them with a smaller time step (λ and λ_f halved, a fixed Δt too), says which
// check broke and which edit came last before it, and runs on. Only after kMaxRollbacks of them
// in a row without getting past the step that broke does it pause.
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "app/triple_buffer.h"
#include "engine/frame.h"
#include "engine/step_driver.h"
#include "engine/world.h"
#include "scene/presets.h"

namespace scour {

namespace cmd {
struct SetParam { std::string key, value; };
struct AddSource { Source source; };
struct UpdateSource { size_t index; Source source; };
struct RemoveSource { size_t index; };
struct AddSink { Sink sink; };
struct UpdateSink { size_t index; Sink sink; };
struct RemoveSink { size_t index; };
struct PaintWater { Eigen::Vector3d centre; double radius; };
struct Pause {};
struct Resume {};
struct StepOnce {};
struct Reset {};                      ///< back to the scene's start (with its current edits)
struct Load { SceneSpec spec; };      ///< a new scene
struct SetStepsPerFrame { int steps; };  ///< steps between published frames
struct SetEffects { Effects effects; };  ///< e.g. rain on/off: takes effect with a reset
/// Files, written or read by the worker (it owns the World): the edited scene as JSON, a
/// checkpoint, the terrain as a 16-bit PNG, raw float, OBJ mesh or erosion map.
struct Save {
  /// kMaps: every erosion map (engine/maps.h) into the folder `path` as 16-bit PNGs with
  /// maps.json; kMapsExr: the same as float32 EXR.
  enum class Kind { kScene, kCheckpoint, kHeightPng, kHeightRaw, kMesh, kErosionMap, kMaps, kMapsExr } kind;
  std::string path;
};
struct LoadCheckpoint { std::string path; };
/// Keeps the world state now (terrain, water, sediment, sources, counters) to go back to.
struct TakeSnapshot {};
/// Back to a kept state, with the parameters as they are now (so the same terrain can be run
/// again with other ones); its sources and sinks come back with it.
struct RestoreSnapshot { int id; };
struct DeleteSnapshot { int id; };
/// The erosion map the published frames carry (Frame::map; "" for none).
struct ShowMap { std::string name; };
}  // namespace cmd

using SimCommand =
    std::variant<cmd::SetParam, cmd::AddSource, cmd::UpdateSource, cmd::RemoveSource, cmd::AddSink,
                 cmd::UpdateSink, cmd::RemoveSink, cmd::PaintWater, cmd::Pause, cmd::Resume,
                 cmd::StepOnce, cmd::Reset, cmd::Load, cmd::SetStepsPerFrame, cmd::SetEffects,
                 cmd::Save, cmd::LoadCheckpoint, cmd::TakeSnapshot, cmd::RestoreSnapshot,
                 cmd::DeleteSnapshot, cmd::ShowMap>;

/// A kept world state as the UI lists it.
struct SnapshotInfo {
  int id = 0;       ///< what RestoreSnapshot and DeleteSnapshot name
  double time = 0;  ///< simulated time when taken [s]
  long step = 0;
  size_t particles = 0;
};

/// What the worker publishes: the frame and the run's figures at that step.
struct Snapshot {
  Frame frame;
  SimParams params;
  std::vector<Source> sources;
  std::vector<Sink> sinks;
  SoilBudget soil;
  std::array<double, size_t(Pass::kCount)> passSeconds{};  ///< cumulative, since the last reset
  double stepsPerSecond = 0;
  bool paused = false;
  long generation = 0;        ///< counts resets and loads
  std::string error;          ///< the last command or step that failed (shown in the log)
  std::string notice;         ///< the last file written or read
  long emitted = 0, painted = 0;  ///< particles made by sources, by the brush
  long removedBySinks = 0;        ///< particles the sinks took out since the start
  std::vector<SnapshotInfo> snapshots;  ///< kept states, oldest first
  long rollbacks = 0;  ///< automatic rollbacks after a broken invariant, since the start
  /// The geologic clock: the bed's time [s], the factor in effect and the one the next step
  /// uses (1 in the spin-up), the bed guard's record and the last step's bed change [Δs].
  double morphTime = 0, factor = 1, factorNow = 1, bedStep = 0;
  Ledger::BedGuard guard;
};

class SimulationWorker {
 public:
  /// Starts the thread on the scene (paused if `paused`).
  explicit SimulationWorker(SceneSpec spec, bool paused = false);
  ~SimulationWorker();  ///< stops and joins
  SimulationWorker(const SimulationWorker&) = delete;
  SimulationWorker& operator=(const SimulationWorker&) = delete;

  void post(SimCommand c);
  /// The newest snapshot if a new one was published since the last call; then latest() holds it.
  bool poll() { return frames_.take(); }
  const Snapshot& latest() const { return frames_.front(); }
  /// The scene as edited so far (sources, sinks, parameters): what "save scene" writes.
  SceneSpec spec() const;

 private:
  void run();
  void applyAll(std::deque<SimCommand>& commands);
  void apply(SimCommand& c);
  void publish(double stepsPerSecond);
  void rebuild();
  void restore(int id);
  /// Runs `next` from now on, with the scene it was built from (a load, a resume, a restore).
  void adopt(std::unique_ptr<World> next, const SceneSpec& spec);
  void load(const SceneSpec& spec);
  void save(const cmd::Save& save);
  void resume(const std::string& checkpoint);
  void takeSnapshot();
  void deleteSnapshot(int id);
  /// The ring's state now (after a rebuild, and every kRingEvery steps).
  void keepRingState();
  /// After a step broke an invariant: back to the newest ring state with a smaller time step.
  /// False (and nothing changed) if it cannot, or has tried kMaxRollbacks times already.
  bool rollBack(const RunEnd& end);
  /// Remembers the newest edit (the log names it when an invariant breaks).
  void noteEdit(const std::string& what);

  /// A kept world state and the scene it belongs to (the scene's effects are those the World
  /// was built with, its sources and sinks those of the World when taken).
  struct Kept {
    SnapshotInfo info;
    SceneSpec spec;
    std::string state;
  };
  /// The world state now, with the scene it belongs to.
  Kept keep() const;
  /// At most this many are kept (a state is a few MB at the default scales).
  static constexpr size_t kMaxSnapshots = 32;
  static constexpr size_t kRingSize = 4;
  static constexpr long kRingEvery = 500;
  static constexpr int kMaxRollbacks = 6;

  mutable std::mutex mutex_;  // guards queue_, stop_ and spec_
  std::condition_variable wake_;
  std::deque<SimCommand> queue_;
  bool stop_ = false;
  SceneSpec spec_;
  // The worker's own (touched only by its thread).
  std::unique_ptr<World> world_;
  bool paused_ = false;
  int stepsPerFrame_ = 1;
  long stepsToDo_ = 0;
  long generation_ = 0;
  std::string error_, notice_;
  std::string frameMap_;  ///< the erosion map the frames carry (cmd::ShowMap)
  Effects worldEffects_;  ///< what world_ was built with (SetEffects waits for a reset)
  std::vector<Kept> kept_;
  std::deque<Kept> ring_;      ///< automatic states, oldest first
  int rollbacksInARow_ = 0;    ///< since the last step past the one that broke
  long brokeAt_ = -1;          ///< the step that broke last
  long rollbacks_ = 0;
  std::string lastEdit_ = "none";
  int nextSnapshotId_ = 1;
  TripleBuffer<Snapshot> frames_;
  std::thread thread_;
};

}  // namespace scour
