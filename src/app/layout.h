#pragma once
// Where the window's panels go: pure arithmetic over the window's size and what each panel asked
// for in the last frame (its content's height, whether it is collapsed). Two columns of stacked
// panels, one on each side, and the log at the foot of the middle, which stays free for the
// terrain. When a column's panels want more than the window's height, the tallest are cut to an
// equal height and scroll; collapsed ones take their title bar only. The panels follow the window
// when it is resized. No ImGui, no GL (tests/app/test_layout.cpp).

#include <array>
#include <cstddef>
#include <string>

namespace scour {

enum class PanelId { kRun, kParameters, kFile, kDisplay, kWater, kStats, kLog, kCount };

/// The panels' titles, by PanelId.
const char* panelTitle(PanelId id);

/// A rectangle in window pixels (x right, y down, from the top-left corner).
struct Rect {
  float x = 0, y = 0, w = 0, h = 0;
  float right() const { return x + w; }
  float bottom() const { return y + h; }
  bool overlaps(const Rect& o) const {
    return x < o.right() && o.x < right() && y < o.bottom() && o.y < bottom();
  }
};

/// What a panel asked for in the last frame.
struct PanelWish {
  float height = 200;      ///< its content's height with its title bar [pixels]
  bool collapsed = false;  ///< only the title bar shows
};

struct Layout {
  std::array<Rect, std::size_t(PanelId::kCount)> panels;
  Rect free;  ///< the middle, above the log: the picture not covered by any panel
  const Rect& operator[](PanelId id) const { return panels[std::size_t(id)]; }
};

/// Sizes of the layout [pixels].
struct LayoutStyle {
  float margin = 6;       ///< around and between panels
  float title = 24;       ///< a collapsed panel's height
  float minColumn = 250;  ///< a column's width
  float maxColumn = 340;
  float columnShare = 0.24f;  ///< of the window's width, within [minColumn, maxColumn]
  float logHeight = 110;      ///< the log, when it is open
};

/// The panels' rectangles for a window of w × h pixels. Each lies inside the window (a window too
/// small for the columns gets narrower ones), and no two overlap.
Layout layOut(float w, float h, const std::array<PanelWish, std::size_t(PanelId::kCount)>& wishes,
              const LayoutStyle& style = {});

/// How the panels were drawn: "layout at W x H: 7 panels inside the window, none overlapping
/// another or the middle, nothing cut", or which panel is outside, overlaps or cut something.
std::string checkLayout(const Layout& planned,
                        const std::array<Rect, std::size_t(PanelId::kCount)>& drawn,
                        const std::array<bool, std::size_t(PanelId::kCount)>& cut, float w,
                        float h);

}  // namespace scour
