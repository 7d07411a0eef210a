#include "app/worker.h"

#include "engine/maps.h"
#include "engine/step_driver.h"

#include "scene/checkpoint.h"
#include "scene/output.h"
#include "scene/run_outputs.h"
#include "scene/scene_json.h"

#include <algorithm>
#include <iterator>
#include <chrono>
#include <optional>
#include <sstream>

namespace scour {

namespace {

// A command that changes the scene, as the log names it when an invariant breaks after it;
// nullptr for one that does not (play, pause, a step, a file written, a snapshot kept).
const char* editName(const SimCommand& c) {
  static const char* const names[] = {"a parameter",
                                      "a source placed",
                                      "a source edited",
                                      "a source deleted",
                                      "a sink placed",
                                      "a sink resized",
                                      "a sink deleted",
                                      "water painted",
                                      nullptr,  // pause
                                      nullptr,  // play
                                      nullptr,  // a single step
                                      "reset",
                                      "a scene opened",
                                      nullptr,  // steps per frame
                                      "effects",
                                      nullptr,  // a file saved
                                      "a checkpoint resumed",
                                      nullptr,  // a snapshot taken
                                      "a snapshot restored",
                                      nullptr,   // a snapshot deleted
                                      nullptr};  // the map the frames carry
  static_assert(std::size(names) == std::variant_size_v<SimCommand>);
  return names[c.index()];
}

}  // namespace

SimulationWorker::SimulationWorker(SceneSpec spec, bool paused) : spec_(std::move(spec)), paused_(paused) {
  rebuild();
  publish(0);
  thread_ = std::thread([this] { run(); });
}

SimulationWorker::~SimulationWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void SimulationWorker::post(SimCommand c) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back(std::move(c));
  }
  wake_.notify_all();
}

SceneSpec SimulationWorker::spec() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return spec_;
}

void SimulationWorker::rebuild() {
  SceneSpec spec;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    spec = spec_;
  }
  world_ = std::make_unique<World>(buildScene(spec).desc);
  worldEffects_ = spec.effects;
  ++generation_;
  ring_.clear();
  keepRingState();
}

void SimulationWorker::adopt(std::unique_ptr<World> next, const SceneSpec& spec) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    spec_ = spec;
  }
  world_ = std::move(next);
  worldEffects_ = spec.effects;
  ++generation_;
}

void SimulationWorker::restore(int id) {
  auto it =
      std::find_if(kept_.begin(), kept_.end(), [&](const Kept& k) { return k.info.id == id; });
  if (it == kept_.end())
    throw std::invalid_argument("snapshot " + std::to_string(id) + " does not exist");
  SceneSpec spec = it->spec;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    spec.params = spec_.params;  // snapshots are dropped with their scene: Δs is the same
  }
  // Into a fresh World: if the state does not load, the running one is untouched.
  auto next = std::make_unique<World>(buildScene(spec).desc);
  std::istringstream in(it->state);
  next->loadState(in);
  adopt(std::move(next), spec);
  error_.clear();
  notice_ = "restored snapshot " + std::to_string(id) + " (t = " + std::to_string(it->info.time) +
            " s, step " + std::to_string(it->info.step) + ")";
}

void SimulationWorker::run() {
  using Clock = std::chrono::steady_clock;
  for (;;) {
    std::deque<SimCommand> commands;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      if (!stop_ && queue_.empty() && paused_ && stepsToDo_ == 0)
        wake_.wait(lock, [&] { return stop_ || !queue_.empty(); });
      if (stop_) return;
      commands.swap(queue_);
    }
    applyAll(commands);
    if (!paused_ || stepsToDo_ > 0) {
      const auto t0 = Clock::now();
      const RunEnd end = runSteps(*world_, stepsPerFrame_, [&](const StepRecord&) {
        if (world_->steps() > brokeAt_) rollbacksInARow_ = 0;  // got past the step that broke
        if (world_->steps() % kRingEvery == 0) keepRingState();
      });
      const long done = end.steps;
      if (!end.ok() && !(end.status == RunEnd::Status::kInvariantViolated && rollBack(end))) {
        error_ = end.describe() + " (paused; reset to go on)";
        paused_ = true;
      }
      if (stepsToDo_ > 0) --stepsToDo_;
      const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
      publish(seconds > 0 ? done / seconds : 0);
    } else if (!commands.empty()) {
      publish(0);
    }
  }
}

void SimulationWorker::applyAll(std::deque<SimCommand>& commands) {
  // Parameter edits come in bursts (a slider dragged): a run of them is applied to the engine
  // once, so the constants are rebuilt once per step rather than once per edit.
  std::optional<SimParams> pending;
  std::vector<std::pair<std::string, std::string>> edits;
  auto flush = [&] {
    if (!pending) return;
    try {
      world_->setParams(*pending);
      std::lock_guard<std::mutex> lock(mutex_);
      for (const auto& [k, v] : edits) setParam(spec_.params, k, v);
    } catch (const std::exception& e) {
      error_ = e.what();
    }
    pending.reset();
    edits.clear();
  };
  for (SimCommand& c : commands) {
    if (auto* s = std::get_if<cmd::SetParam>(&c)) {
      SimParams p = pending ? *pending : world_->params();
      const std::string err = setParam(p, s->key, s->value);
      if (!err.empty()) {
        error_ = err;
        continue;
      }
      pending = p;
      edits.emplace_back(s->key, s->value);
      noteEdit(s->key + " = " + s->value);
      continue;
    }
    flush();
    apply(c);
  }
  flush();
}

void SimulationWorker::apply(SimCommand& c) {
  // Edits go to the World and to the spec (so a reset or a saved scene keeps them). A command
  // that fails leaves both as they were and says why in the next snapshot.
  try {
    // (Parameter edits never come here: applyAll batches them.)
    if (const char* what = editName(c)) noteEdit(what);
    if (auto* a = std::get_if<cmd::AddSource>(&c)) {
      world_->addSource(a->source);
      std::lock_guard<std::mutex> lock(mutex_);
      spec_.sources.push_back(a->source);
    } else if (auto* u = std::get_if<cmd::UpdateSource>(&c)) {
      world_->updateSource(u->index, u->source);
      std::lock_guard<std::mutex> lock(mutex_);
      spec_.sources.at(u->index) = u->source;
    } else if (auto* r = std::get_if<cmd::RemoveSource>(&c)) {
      world_->removeSource(r->index);
      std::lock_guard<std::mutex> lock(mutex_);
      spec_.sources.erase(spec_.sources.begin() + long(r->index));
    } else if (auto* k = std::get_if<cmd::AddSink>(&c)) {
      world_->addSink(k->sink);
      std::lock_guard<std::mutex> lock(mutex_);
      spec_.sinks.push_back(k->sink);
    } else if (auto* us = std::get_if<cmd::UpdateSink>(&c)) {
      world_->updateSink(us->index, us->sink);
      std::lock_guard<std::mutex> lock(mutex_);
      spec_.sinks.at(us->index) = us->sink;
    } else if (auto* k2 = std::get_if<cmd::RemoveSink>(&c)) {
      world_->removeSink(k2->index);
      std::lock_guard<std::mutex> lock(mutex_);
      spec_.sinks.erase(spec_.sinks.begin() + long(k2->index));
    } else if (auto* w = std::get_if<cmd::PaintWater>(&c)) {
      world_->addWater(w->centre, w->radius);
    } else if (std::holds_alternative<cmd::Pause>(c)) {
      paused_ = true;
    } else if (std::holds_alternative<cmd::Resume>(c)) {
      paused_ = false;
      error_.clear();
    } else if (std::holds_alternative<cmd::StepOnce>(c)) {
      paused_ = true;
      ++stepsToDo_;
    } else if (std::holds_alternative<cmd::Reset>(c)) {
      rebuild();
      error_.clear();
    } else if (auto* l = std::get_if<cmd::Load>(&c)) {
      load(l->spec);
    } else if (auto* fx = std::get_if<cmd::SetEffects>(&c)) {
      std::lock_guard<std::mutex> lock(mutex_);
      spec_.effects = fx->effects;
    } else if (auto* sv = std::get_if<cmd::Save>(&c)) {
      save(*sv);
    } else if (auto* lc = std::get_if<cmd::LoadCheckpoint>(&c)) {
      resume(lc->path);
    } else if (std::holds_alternative<cmd::TakeSnapshot>(c)) {
      takeSnapshot();
    } else if (auto* rs = std::get_if<cmd::RestoreSnapshot>(&c)) {
      restore(rs->id);
    } else if (auto* ds = std::get_if<cmd::DeleteSnapshot>(&c)) {
      deleteSnapshot(ds->id);
    } else if (auto* sm = std::get_if<cmd::ShowMap>(&c)) {
      if (!sm->name.empty() && !isErosionMap(sm->name))
        throw std::invalid_argument("no erosion map called '" + sm->name + "'");
      frameMap_ = sm->name;
    } else if (auto* f = std::get_if<cmd::SetStepsPerFrame>(&c)) {
      if (f->steps < 1 || f->steps > 1000) throw std::invalid_argument("steps per frame must lie in [1, 1000]");
      stepsPerFrame_ = f->steps;
    }
  } catch (const std::exception& e) {
    error_ = e.what();
  }
}

// A new scene: a bad one throws before anything changes.
void SimulationWorker::load(const SceneSpec& spec) {
  auto next = std::make_unique<World>(buildScene(spec).desc);  // a bad scene throws here
  adopt(std::move(next), spec);
  error_.clear();
  if (!kept_.empty()) notice_ = "a new scene: its snapshots start afresh";
  kept_.clear();
}

void SimulationWorker::save(const cmd::Save& sv) {
  using K = cmd::Save::Kind;
  switch (sv.kind) {
    case K::kScene: {
      const nlohmann::json j = specToJson(spec());
      writeAtomically(sv.path, [&](std::ostream& o) { o << j.dump(2) << "\n"; });
      break;
    }
    case K::kCheckpoint: writeCheckpoint(sv.path, spec(), *world_); break;
    case K::kHeightPng: writeHeightPng16(sv.path, world_->settledTerrain()); break;
    case K::kHeightRaw: writeHeightRaw(sv.path, world_->settledTerrain()); break;
    case K::kMesh: writeTerrainObj(sv.path, world_->settledTerrain()); break;
    case K::kErosionMap: writeErosionPng(sv.path, world_->settledTerrain(), world_->heightChange()); break;
    case K::kMaps:
    case K::kMapsExr:
      writeErosionMaps(sv.path, erosionMaps(*world_), world_->terrain().nx(), world_->terrain().nz(), erosionMapNames(),
                       sv.kind == K::kMapsExr ? MapFormat::kExr : MapFormat::kPng16);
      break;
  }
  notice_ = "wrote " + sv.path;
}

void SimulationWorker::resume(const std::string& path) {
  Scene scene;
  auto next = std::make_unique<World>(resumeWorld(readCheckpoint(path), scene));
  adopt(std::move(next), scene.spec);
  notice_ = "resumed " + path + " at step " + std::to_string(world_->steps());
  kept_.clear();  // a checkpoint may be of another scene
}

SimulationWorker::Kept SimulationWorker::keep() const {
  Kept k;
  k.spec = spec();
  k.spec.effects = worldEffects_;
  k.spec.sources = world_->sources();
  k.spec.sinks = world_->sinks();
  std::ostringstream out;
  world_->saveState(out);
  k.state = out.str();
  k.info = {0, world_->time(), world_->steps(), world_->fluid().size()};
  return k;
}

void SimulationWorker::keepRingState() {
  if (!ring_.empty() && ring_.back().info.step == world_->steps()) return;
  ring_.push_back(keep());
  while (ring_.size() > kRingSize) ring_.pop_front();
}

bool SimulationWorker::rollBack(const RunEnd& end) {
  const long broke = world_->steps() + 1;  // the step that threw was not counted
  if (ring_.empty() || rollbacksInARow_ >= kMaxRollbacks) return false;
  // A second break before getting past the first: the newest state may already hold the trouble
  // (a particle on its way through), so go one further back each time, as far as the ring goes.
  const size_t back = std::min(size_t(rollbacksInARow_), ring_.size() - 1);
  const Kept& k = ring_[ring_.size() - 1 - back];
  SimParams p = world_->params();
  p.cfl = std::max(0.5 * p.cfl, 0.01);
  p.force_cfl = std::max(0.5 * p.force_cfl, 0.01);
  if (p.fixed_dt > 0) p.fixed_dt *= 0.5;
  SceneSpec spec = k.spec;
  spec.params = p;
  try {
    auto next = std::make_unique<World>(buildScene(spec).desc);
    std::istringstream in(k.state);
    next->loadState(in);
    adopt(std::move(next), spec);
  } catch (const std::exception&) {
    return false;  // the running World is as it was: pause
  }
  // The newer ring states are of the timeline just left.
  while (ring_.size() > 1 && ring_.back().info.step > k.info.step) ring_.pop_back();
  ++rollbacksInARow_, ++rollbacks_;
  brokeAt_ = std::max(brokeAt_, broke);
  std::ostringstream msg;
  msg << end.describe() << "; the edit before it: " << lastEdit_ << ". Rolled back to step "
      << k.info.step << " (t = " << k.info.time << " s) with a smaller time step (time.cfl "
      << p.cfl << ", time.force_cfl " << p.force_cfl;
  if (p.fixed_dt > 0) msg << ", time.fixed_dt " << p.fixed_dt;
  msg << "); running on";
  error_ = msg.str();
  return true;
}

void SimulationWorker::noteEdit(const std::string& what) {
  lastEdit_ = what + " at step " + std::to_string(world_->steps());
}

void SimulationWorker::takeSnapshot() {
  if (kept_.size() >= kMaxSnapshots)
    throw std::invalid_argument("at most " + std::to_string(kMaxSnapshots) +
                                " snapshots: delete one first");
  Kept k = keep();
  k.info.id = nextSnapshotId_++;
  notice_ = "took snapshot " + std::to_string(k.info.id) +
            " at t = " + std::to_string(k.info.time) + " s";
  kept_.push_back(std::move(k));
}

void SimulationWorker::deleteSnapshot(int id) {
  auto it = std::find_if(kept_.begin(), kept_.end(),
                         [&](const Kept& k) { return k.info.id == id; });
  if (it == kept_.end())
    throw std::invalid_argument("snapshot " + std::to_string(id) + " does not exist");
  kept_.erase(it);
  notice_ = "deleted snapshot " + std::to_string(id);
}

void SimulationWorker::publish(double stepsPerSecond) {
  Snapshot& s = frames_.back();
  s.frame = makeFrame(*world_, frameMap_);
  s.params = world_->params();
  s.sources = world_->sources();
  s.sinks = world_->sinks();
  s.soil = world_->soilBudget();
  s.passSeconds = world_->passSeconds();
  s.stepsPerSecond = stepsPerSecond;
  s.paused = paused_;
  s.generation = generation_;
  s.error = error_;
  s.notice = notice_;
  s.emitted = world_->emitted();
  s.painted = world_->painted();
  s.removedBySinks = world_->removedBySinks();
  s.rollbacks = rollbacks_;
  s.morphTime = world_->morphologicalTime();
  s.factor = world_->morphologicalFactor();
  s.factorNow = world_->factorNow();
  s.bedStep = world_->lastBedStep();
  s.guard = world_->bedGuard();
  s.snapshots.clear();
  for (const Kept& k : kept_) s.snapshots.push_back(k.info);
  frames_.publish();
}

}  // namespace scour
