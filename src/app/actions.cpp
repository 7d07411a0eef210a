#include "app/actions.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <variant>

namespace scour {

std::string formatNumber(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string formatPoint(const Eigen::Vector3d& p) {
  // Appended, not "(" + …: GCC 12 warns falsely (-Wrestrict) on a literal plus a temporary.
  std::string out = "(";
  out += formatNumber(p.x());
  out += ", ";
  out += formatNumber(p.y());
  out += ", ";
  out += formatNumber(p.z());
  out += ")";
  return out;
}

Actions::Actions(Post post, double spacing)
    : brushRadius(float(4 * spacing)), sinkRadius(float(3 * spacing)), post_(std::move(post)) {}

void Actions::post(const std::vector<SimCommand>& commands) {
  for (const SimCommand& c : commands) post_(c);
}

void Actions::click(double x, double y) {
  const Frame& frame = snapshot().frame;
  Eigen::Vector3f hit;
  if (!pickTerrain(frame, view_.camera, view_.aspect, x, y, view_.width, view_.height, hit)) {
    log_.push_back("no terrain under the mouse");
    return;
  }
  if (tool == Tool::kSink) {
    placeSink(hit);
  } else if (tool == Tool::kBrush) {
    post_(cmd::PaintWater{hit.cast<double>() + Eigen::Vector3d(0, brushRadius, 0), brushRadius});
    log_.push_back("painted water at " + formatPoint(hit.cast<double>()));
  } else {
    placeSource(hit);
  }
}

// A box of half-size sinkRadius around the hit: it takes the water (and what it carries) out.
void Actions::placeSink(const Eigen::Vector3f& hit) {
  Sink k;
  k.lo = hit.cast<double>() - Eigen::Vector3d::Constant(sinkRadius);
  k.hi = hit.cast<double>() + Eigen::Vector3d::Constant(sinkRadius);
  perform({{cmd::AddSink{k}}, {cmd::RemoveSink{snapshot().sinks.size()}}, "place a sink", ""},
          false);
  log_.push_back("sink placed at " + formatPoint(hit.cast<double>()) + ", half-size " +
                 formatNumber(sinkRadius) + " m");
}

// Like the scene's own sources (the median rate and radius of those it has now: a click on the
// default scene gave 20 L/s, ten times its 2 L/s), else a disk of 3 Δs pouring 0.3 m/s; 6 Δs over
// the terrain, pouring down.
void Actions::placeSource(const Eigen::Vector3f& hit) {
  const Frame& frame = snapshot().frame;
  const std::vector<Source>& scene = snapshot().sources;
  Source s;
  s.radius = 3 * frame.spacing;
  s.rate = M_PI * s.radius * s.radius * 0.3;
  if (!scene.empty()) {
    auto median = [&](double Source::*field) {
      std::vector<double> v;
      for (const Source& k : scene) v.push_back(k.*field);
      std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
      return v[v.size() / 2];
    };
    s.rate = median(&Source::rate), s.radius = median(&Source::radius);
  }
  s.center = overTerrain(frame, hit.cast<double>(), s.radius, 6 * frame.spacing);
  s.direction = {0, -1, 0};
  perform(
      {{cmd::AddSource{s}}, {cmd::RemoveSource{snapshot().sources.size()}}, "place a source", ""},
      false);
  lastSource_ = s.center, lastRadius_ = s.radius;
  log_.push_back("source placed at " + formatPoint(s.center));
}

bool Actions::press(double x, double y) {
  const int i = sourceUnder(x, y);
  if (i < 0) return false;
  const Frame& frame = snapshot().frame;
  drag_ = SourceDrag{};
  drag_.index = i;
  drag_.start = snapshot().sources[size_t(i)];
  float g = 0;
  const Eigen::Vector3d& c = drag_.start.center;
  drag_.lift = terrainHeight(frame, c.x(), c.z(), g) ? c.y() - g : 6 * frame.spacing;
  return true;
}

void Actions::dragTo(double x, double y) {
  const Frame& frame = snapshot().frame;
  Eigen::Vector3f hit;
  if (drag_.index < 0 ||
      !pickTerrain(frame, view_.camera, view_.aspect, x, y, view_.width, view_.height, hit))
    return;  // off the terrain: it waits
  Source s = drag_.start;
  s.center = overTerrain(frame, hit.cast<double>(), s.radius, drag_.lift);
  if (drag_.moved && (s.center - drag_.last).norm() < 1e-9) return;
  const std::string what = "move source " + std::to_string(drag_.index);
  perform({{cmd::UpdateSource{size_t(drag_.index), s}},
           {cmd::UpdateSource{size_t(drag_.index), drag_.start}},
           what,
           what},
          drag_.moved);
  drag_.moved = true;
  drag_.last = s.center;
}

void Actions::release() {
  if (drag_.index >= 0 && drag_.moved) {
    lastSource_ = drag_.last, lastRadius_ = drag_.start.radius;
    log_.push_back("source " + std::to_string(drag_.index) + " moved to " +
                   formatPoint(drag_.last));
  }
  drag_ = SourceDrag{};
}

void Actions::cancelDrag() {
  if (drag_.moved) {  // a cancelled drag is not there to redo
    if (std::optional<Edit> e = history_.cancel("move source " + std::to_string(drag_.index)))
      post(e->undo), log_.push_back("undo: " + e->what);
  }
  drag_ = SourceDrag{};
}

void Actions::setParameter(const std::string& key, const std::string& value, bool extend) {
  const ParamInfo* info = findParam(key);
  std::string old = value;
  const Edit* last = history_.nextUndo();
  if (extend && last && last->key == key && !last->undo.empty()) {
    // A drag goes on: the value before it is the one its first edit undoes to, not the value
    // the newest snapshot holds (one from the drag's middle).
    old = std::get<cmd::SetParam>(last->undo.front()).value;
  } else if (info) {
    const double current = getParam(snapshot().params, *info);
    old = info->choices ? info->choices[int(current)] : formatNumber(current);
  }
  perform({{cmd::SetParam{key, value}},
           {cmd::SetParam{key, old}},
           key + " = " + value + " (was " + old + ")",
           key},
          extend);
}

void Actions::perform(Edit e, bool extend) {
  post(history_.perform(std::move(e), extend));
}

void Actions::undo() {
  if (std::optional<Edit> e = history_.undo()) post(e->undo), log_.push_back("undo: " + e->what);
}

void Actions::redo() {
  if (std::optional<Edit> e = history_.redo()) post(e->redo), log_.push_back("redo: " + e->what);
}

void Actions::restoreSnapshot(int id) {
  post_(cmd::RestoreSnapshot{id});  // an unknown one: the worker says so
  const auto& kept = snapshot().snapshots;
  if (std::none_of(kept.begin(), kept.end(), [&](const SnapshotInfo& k) { return k.id == id; }))
    return;
  history_.clear();
  log_.push_back("restoring snapshot " + std::to_string(id) + " (undo history cleared)");
}

bool Actions::sourceStem(const Eigen::Vector3d& centre, Eigen::Vector2f& foot,
                         Eigen::Vector2f& top) const {
  float g = 0;
  const Eigen::Vector3f c = centre.cast<float>();
  const Eigen::Vector3f base =
      terrainHeight(snapshot().frame, c.x(), c.z(), g) ? Eigen::Vector3f(c.x(), g, c.z()) : c;
  return toWindow(view_.camera, view_.aspect, c, view_.width, view_.height, top) &&
         toWindow(view_.camera, view_.aspect, base, view_.width, view_.height, foot);
}

int Actions::sourceUnder(double x, double y) const {
  int best = -1;
  float bestDistance = kMarkerPixels;
  const std::vector<Source>& sources = snapshot().sources;
  for (size_t i = 0; i < sources.size(); ++i) {
    Eigen::Vector2f foot, top;
    if (!sourceStem(sources[i].center, foot, top)) continue;
    const float d = segmentDistance(Eigen::Vector2f(float(x), float(y)), foot, top);
    if (d <= bestDistance) best = int(i), bestDistance = d;
  }
  return best;
}

}  // namespace scour
