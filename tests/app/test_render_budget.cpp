// The window's render budget without a window: frames over the budget take the quality down
// (far over it, several levels at once), frames with room bring it back up without see-sawing,
// and a level the user pins stays whatever the frame times.
#include <catch2/catch.hpp>

#include "app/render_budget.h"

using namespace scour;

namespace {

// A scene whose frames cost `fine` seconds at the finest level, 2.5 times less a level down.
double cost(int level, double fine) {
  if (level == RenderBudget::kLevels - 1) return 0.004;
  double t = fine;
  for (int k = 0; k < level; ++k) t /= 2.5;
  return t;
}

}  // namespace

TEST_CASE("render budget: a slow scene goes down to a level that fits and stays there",
          "[app][budget]") {
  RenderBudget b(0.04);
  CHECK(b.level() == 0);
  // lake --scale 0.3 on llvmpipe: about 1 s a frame with the full surface.
  std::vector<int> levels;
  for (int frame = 0; frame < 400; ++frame) {
    b.measured(cost(b.level(), 1.0));
    levels.push_back(b.level());
  }
  // 1 s, 0.4, 0.16, 0.064, 0.026: level 4 is the finest within 40 ms.
  CHECK(b.level() == 4);
  CHECK(levels[0] >= 3);  // the first frame, 25 times over, jumps several levels at once
  int changes = 0;
  for (size_t k = 1; k < levels.size(); ++k) changes += levels[k] != levels[k - 1];
  CHECK(changes <= 3);  // no see-saw between 3 and 4
  CHECK(b.describe() == "auto: grid 3 Δs, no caustics or refraction, 26 ms a frame");
  const RenderSettings s = b.apply(RenderSettings{});
  CHECK(s.surface.cell_over_spacing == 3.0);
  CHECK_FALSE(s.caustics);
  CHECK(s.water);
}

TEST_CASE("render budget: with room again the quality comes back up", "[app][budget]") {
  RenderBudget b(0.04);
  for (int frame = 0; frame < 50; ++frame) b.measured(cost(b.level(), 1.0));
  REQUIRE(b.level() >= 4);
  // The water drained away: every level is now cheap.
  for (int frame = 0; frame < 2000; ++frame) b.measured(cost(b.level(), 0.01));
  CHECK(b.level() == 0);
  CHECK(b.apply(RenderSettings{}).surface.cell_over_spacing == 0.75);
}

TEST_CASE("render budget: a pinned level stays; particles only draws the particles",
          "[app][budget]") {
  RenderBudget b(0.04);
  b.choose(RenderBudget::kLevels - 1);
  for (int frame = 0; frame < 100; ++frame) b.measured(0.5);
  CHECK(b.level() == RenderBudget::kLevels - 1);
  RenderSettings s = b.apply(RenderSettings{});
  CHECK_FALSE(s.water);
  CHECK(s.particles == RenderSettings::Particles::kSediment);
  CHECK(b.describe() == "pinned: particles only, 500 ms a frame");
  b.choose(-1);  // back to automatic
  for (int frame = 0; frame < 10; ++frame) b.measured(0.001);
  CHECK(b.choice() == -1);
}
