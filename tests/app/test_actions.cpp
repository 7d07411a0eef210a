// The one door for the window's edits, without a window: a click places a source over the
// terrain, a press on its marker grabs it, a drag is one undoable edit, Escape takes it back for
// good, a parameter edit undoes to the value before it, and a replay plays through the same door.
#include <catch2/catch.hpp>

#include "app/actions.h"
#include "app/exit_report.h"
#include "app/replay_player.h"

using namespace scour;

namespace {

// A flat 1 m × 1 m terrain at y = 0.2, 11 × 11 vertices, Δs = 2 cm.
Snapshot flatSnapshot() {
  Snapshot s;
  Frame& f = s.frame;
  f.nx = f.nz = 11;
  f.dx = f.dz = 0.1;
  f.spacing = 0.02f;
  f.height.assign(121, 0.2f);
  return s;
}

struct Posted {
  std::vector<SimCommand> commands;
  Actions::Post post() {
    return [this](const SimCommand& c) { commands.push_back(c); };
  }
  template <class T>
  const T& last() const {
    REQUIRE(!commands.empty());
    REQUIRE(std::holds_alternative<T>(commands.back()));
    return std::get<T>(commands.back());
  }
};

View viewOf(const Snapshot& s) {
  return {&s, orbitFor(s.frame).camera(), 800.0f / 600.0f, 800, 600};
}

}  // namespace

TEST_CASE("a click with the source tool places a source over the terrain, undone by removing it",
          "[app][actions]") {
  Snapshot snap = flatSnapshot();
  Posted posted;
  Actions actions(posted.post(), snap.frame.spacing);
  actions.setView(viewOf(snap));
  actions.toggle(Tool::kSink, true);
  actions.toggle(Tool::kSink, false);  // back to orbiting: a click places a source
  CHECK(actions.tool == Tool::kOrbit);
  actions.click(400, 300);
  const Source s = posted.last<cmd::AddSource>().source;
  // A scene without sources: a disk of 3 Δs pouring at 0.3 m/s.
  CHECK(s.radius == Approx(3 * 0.02));
  CHECK(s.rate == Approx(M_PI * 0.06 * 0.06 * 0.3));
  CHECK(s.center.y() == Approx(0.2 + 6 * 0.02));  // 6 Δs over the terrain
  CHECK(s.direction == Eigen::Vector3d(0, -1, 0));
  CHECK(actions.lastSource() == s.center);
  CHECK(actions.log().back().rfind("source placed at (", 0) == 0);
  actions.undo();
  CHECK(posted.last<cmd::RemoveSource>().index == 0);
  actions.redo();
  CHECK(posted.last<cmd::AddSource>().source.center == s.center);
  // The sky misses the terrain: nothing placed, and the log says why.
  const size_t before = posted.commands.size();
  actions.click(400, 0);
  CHECK(posted.commands.size() == before);
  CHECK(actions.log().back() == "no terrain under the mouse");
}

TEST_CASE("a click-placed source is like the scene's own: their median rate and radius",
          "[app][actions]") {
  Snapshot snap = flatSnapshot();
  for (double rate : {0.002, 0.001, 0.004}) {
    Source k;
    k.center = {0.5, 0.6, 0.5}, k.radius = rate * 25, k.rate = rate, k.direction = {0, -1, 0};
    snap.sources.push_back(k);
  }
  Posted posted;
  Actions actions(posted.post(), snap.frame.spacing);
  actions.setView(viewOf(snap));
  actions.click(400, 300);
  const Source s = posted.last<cmd::AddSource>().source;
  CHECK(s.rate == 0.002);  // the default scene's 2 L/s, not 20
  CHECK(s.radius == Approx(0.05));
}

TEST_CASE("a drag of a source's marker is one edit; Escape takes it back for good",
          "[app][actions]") {
  Snapshot snap = flatSnapshot();
  Source s;
  s.center = {0.5, 0.32, 0.5}, s.radius = 0.06, s.rate = 0.02;
  snap.sources.push_back(s);
  Posted posted;
  Actions actions(posted.post(), snap.frame.spacing);
  actions.setView(viewOf(snap));
  Eigen::Vector2f foot, top;
  REQUIRE(actions.sourceStem(s.center, foot, top));
  CHECK(actions.sourceUnder(top.x(), top.y()) == 0);
  CHECK(actions.sourceUnder(top.x() + 3 * kMarkerPixels, top.y()) == -1);
  CHECK_FALSE(actions.press(top.x() + 3 * kMarkerPixels, top.y()));
  REQUIRE(actions.press(top.x(), top.y()));
  for (int k = 1; k <= 4; ++k) actions.dragTo(top.x() + 20 * k, foot.y());
  const cmd::UpdateSource moved = posted.last<cmd::UpdateSource>();
  CHECK(moved.index == 0);
  CHECK(moved.source.center.x() > s.center.x() + 0.01);
  CHECK(moved.source.center.y() == Approx(s.center.y()));  // the same height over the terrain
  actions.release();
  CHECK(actions.drag().index == -1);
  CHECK(actions.log().back().rfind("source 0 moved to (", 0) == 0);
  // Four moves, one undo step back to where the drag began.
  actions.undo();
  CHECK(posted.last<cmd::UpdateSource>().source.center == s.center);
  CHECK(actions.history().nextUndo() == nullptr);
  // A cancelled drag goes back and leaves nothing to redo.
  actions.redo();
  REQUIRE(actions.press(top.x(), top.y()));
  actions.dragTo(top.x() - 60, foot.y());
  actions.cancelDrag();
  CHECK(posted.last<cmd::UpdateSource>().source.center == s.center);
  CHECK(actions.history().nextRedo() == nullptr);
  CHECK(actions.drag().index == -1);
}

TEST_CASE("a parameter edit undoes to the value before it, a slider drag being one edit",
          "[app][actions]") {
  Snapshot snap = flatSnapshot();
  snap.params.k_eps = 0.25;
  Posted posted;
  Actions actions(posted.post(), snap.frame.spacing);
  actions.setView(viewOf(snap));
  actions.setParameter("erosion.k_eps", "0.5");
  snap.params.k_eps = 0.5;  // the worker has applied the drag's first value
  actions.setView(viewOf(snap));
  actions.setParameter("erosion.k_eps", "0.75", true);
  CHECK(posted.last<cmd::SetParam>().value == "0.75");
  // The one edit names the value before the drag, not one from its middle.
  REQUIRE(actions.history().nextUndo() != nullptr);
  CHECK(actions.history().nextUndo()->what == "erosion.k_eps = 0.75 (was 0.25)");
  actions.undo();
  CHECK(posted.last<cmd::SetParam>().value == "0.25");
  CHECK(actions.history().nextUndo() == nullptr);
}

TEST_CASE("a replay plays through the actions: tool, click, a scripted drag of eight moves",
          "[app][actions][replay]") {
  Snapshot snap = flatSnapshot();
  Posted posted;
  Actions actions(posted.post(), snap.frame.spacing);
  std::vector<std::string> shots;
  ReplayPlayer replay(
      parseReplay("0 place on\n0 click 400 300\n2 press pause\n3 screenshot a.png\n",
                  "test.replay"),
      [&](const std::string& p) { shots.push_back(p); });
  for (long frame = 0; frame < 4; ++frame) {
    actions.setView(viewOf(snap));
    replay.play(frame, actions);
    if (frame == 0) snap.sources.push_back(posted.last<cmd::AddSource>().source);
  }
  CHECK(actions.tool == Tool::kSource);
  CHECK(std::holds_alternative<cmd::Pause>(posted.commands.back()));
  CHECK(shots == std::vector<std::string>{"a.png"});
  // A drag from the source's marker: a press, eight moves (one edit), a release.
  Eigen::Vector2f foot, top;
  REQUIRE(actions.sourceStem(snap.sources[0].center, foot, top));
  const std::string drag = "4 drag " + std::to_string(top.x()) + " " + std::to_string(top.y()) +
                           " " + std::to_string(top.x() + 100) + " " + std::to_string(foot.y());
  ReplayPlayer dragging(parseReplay(drag + "\n", "drag.replay"), nullptr);
  const size_t before = posted.commands.size();
  long frame = 4;
  for (; frame <= 4 + ReplayPlayer::kDragSteps; ++frame) {
    dragging.play(frame, actions);
    CHECK(dragging.holdsMouse() == (frame < 4 + ReplayPlayer::kDragSteps));
  }
  CHECK(posted.commands.size() - before == size_t(ReplayPlayer::kDragSteps));
  CHECK(actions.log().back().rfind("source 0 moved to (", 0) == 0);
  actions.undo();
  CHECK(posted.last<cmd::UpdateSource>().source.center == snap.sources[0].center);
  CHECK(actions.log().back() == "undo: move source 0");
}

TEST_CASE("the exit report counts the water near the last placed source and lists the log",
          "[app][actions]") {
  Snapshot snap = flatSnapshot();
  Posted posted;
  Actions actions(posted.post(), snap.frame.spacing);
  actions.setView(viewOf(snap));
  actions.toggle(Tool::kSource, true);
  actions.click(400, 300);
  const Source s = posted.last<cmd::AddSource>().source;
  snap.sources.push_back(s);
  snap.frame.position = {s.center.cast<float>(),
                         (s.center + Eigen::Vector3d(0.2, 0, 0)).cast<float>(),
                         (s.center + Eigen::Vector3d(0, 0, 0.4)).cast<float>()};
  SourceWatch watch;
  watch.see(snap, actions);
  snap.frame.position.front() += Eigen::Vector3f(0, -1, 0);  // the layer leaves the disk
  const std::string report = exitReport(snap, 7, actions, 0, watch.most());
  CHECK(report.rfind("closed after 7 frames; simulated 0 s, 0 steps; 1 sources at [(", 0) == 0);
  CHECK(report.find("particles within 0.25 m of the last placed or moved source 1, around its "
                    "disk 0 (at most 2 and 1 in one frame since it was placed or moved); GL "
                    "errors: 0\n") != std::string::npos);
  CHECK(report.find("\nlog: source placed at (") != std::string::npos);
  // A source placed elsewhere is counted afresh: no particle is around its disk yet, and what is
  // near it is this snapshot's count, not the old source's most.
  actions.click(560, 380);
  REQUIRE((actions.lastSource() - s.center).norm() > 0.1);
  watch.see(snap, actions);
  CHECK(watch.most().near == countNearSource(snap, actions).near);
  CHECK(watch.most().near < 2);
  CHECK(watch.most().atDisk == 0);
}
