// The panels' layout without a window: at 1280 x 720 and at other sizes every panel lies inside
// the window, no two overlap, none covers the middle left free for the terrain; collapsed panels
// give their room to the others.
#include <catch2/catch.hpp>

#include "app/layout.h"

using namespace scour;

namespace {

using Wishes = std::array<PanelWish, size_t(PanelId::kCount)>;

Wishes wishes(float height) {
  Wishes w;
  for (PanelWish& p : w) p.height = height;
  return w;
}

void requireTidy(const Layout& l, float w, float h) {
  for (size_t i = 0; i < l.panels.size(); ++i) {
    const Rect& r = l.panels[i];
    INFO(panelTitle(PanelId(i)) << " at " << r.x << ", " << r.y << ", " << r.w << " x " << r.h);
    REQUIRE(r.x >= 0);
    REQUIRE(r.y >= 0);
    REQUIRE(r.right() <= w);
    REQUIRE(r.bottom() <= h + 1e-3f);
    REQUIRE(r.w > 0);
    REQUIRE(r.h > 0);
    REQUIRE_FALSE(r.overlaps(l.free));
    for (size_t j = i + 1; j < l.panels.size(); ++j) {
      INFO("and " << panelTitle(PanelId(j)));
      REQUIRE_FALSE(r.overlaps(l.panels[j]));
    }
  }
}

}  // namespace

TEST_CASE("layout: at 1280 x 720 the panels fit, overlap nothing and leave the middle free",
          "[layout]") {
  const Layout l = layOut(1280, 720, wishes(250));
  requireTidy(l, 1280, 720);
  // Each column asks for 3 x 250 px, more than 720: the panels are cut to the same height.
  CHECK(l[PanelId::kRun].h == Approx(l[PanelId::kFile].h));
  CHECK(l[PanelId::kRun].bottom() < l[PanelId::kParameters].y);
  // The middle keeps more than half the window's width for the terrain.
  CHECK(l.free.w > 0.5f * 1280);
  CHECK(l.free.h > 0.7f * 720);
}

TEST_CASE("layout: panels that fit keep their height; a short one is not stretched", "[layout]") {
  Wishes w = wishes(150);
  w[size_t(PanelId::kParameters)].height = 2000;  // the tall one is cut, the others stay whole
  const Layout l = layOut(1280, 720, w);
  requireTidy(l, 1280, 720);
  CHECK(l[PanelId::kRun].h == 150);
  CHECK(l[PanelId::kFile].h == 150);
  CHECK(l[PanelId::kParameters].bottom() + 6 == Approx(l[PanelId::kFile].y));
  CHECK(l[PanelId::kFile].bottom() == Approx(714));
  CHECK(l[PanelId::kDisplay].h == 150);
}

TEST_CASE("layout: a collapsed panel takes its title bar and gives the room to the others",
          "[layout]") {
  Wishes w = wishes(400);
  const float before = layOut(1280, 720, w)[PanelId::kParameters].h;
  w[size_t(PanelId::kRun)].collapsed = true;
  const Layout l = layOut(1280, 720, w);
  requireTidy(l, 1280, 720);
  CHECK(l[PanelId::kRun].h == 24);
  CHECK(l[PanelId::kParameters].h > before);
}

TEST_CASE("layout: the panels follow a resize, down to a small window", "[layout]") {
  for (auto [w, h] :
       {std::pair{1920.0f, 1080.0f}, std::pair{1280.0f, 720.0f}, std::pair{800.0f, 600.0f},
        std::pair{640.0f, 400.0f}, std::pair{300.0f, 200.0f}}) {
    INFO(w << " x " << h);
    const Layout l = layOut(w, h, wishes(300));
    requireTidy(l, w, h);
    CHECK(l[PanelId::kDisplay].right() == Approx(w - 6));
  }
  // Wider than the columns' maximum: the columns keep their width and the middle grows.
  CHECK(layOut(1920, 1080, wishes(100))[PanelId::kRun].w == 340);
}
