#include "app/layout.h"

#include <algorithm>
#include <numeric>
#include <vector>

namespace scour {

namespace {

using std::size_t;
using Wishes = std::array<PanelWish, size_t(PanelId::kCount)>;

// Heights for a column's panels within `available` pixels (the margins already taken): each
// gets what it asks for if all fit; else the open ones are capped at one height c, the largest
// for which they fit (the short ones keep theirs), and if even the title bars do not fit, all
// shrink alike.
std::vector<float> columnHeights(const std::vector<PanelWish>& wishes, float available,
                                 float title) {
  std::vector<float> h;
  for (const PanelWish& w : wishes) h.push_back(w.collapsed ? title : std::max(w.height, title));
  const float total = std::accumulate(h.begin(), h.end(), 0.0f);
  if (total <= available) return h;
  float fixed = 0;
  std::vector<float> open;
  for (size_t i = 0; i < h.size(); ++i) {
    if (wishes[i].collapsed)
      fixed += h[i];
    else
      open.push_back(h[i]);
  }
  std::sort(open.begin(), open.end());
  // The cap: with the k shortest open panels whole, the rest share what is left equally.
  float cap = title, below = 0;
  for (size_t k = 0; k < open.size(); ++k) {
    const float share = (available - fixed - below) / float(open.size() - k);
    if (share <= open[k]) {
      cap = std::max(share, title);
      break;
    }
    below += open[k];
  }
  for (size_t i = 0; i < h.size(); ++i)
    if (!wishes[i].collapsed) h[i] = std::min(h[i], cap);
  const float capped = std::accumulate(h.begin(), h.end(), 0.0f);
  if (capped > available && capped > 0)
    for (float& v : h) v *= std::max(available, 0.0f) / capped;
  return h;
}

// Stacks the panels top-down in a column at x of width w, from y0 to y1.
void stack(Layout& out, const std::vector<PanelId>& ids, const Wishes& wishes, float x, float w,
           float y0, float y1, const LayoutStyle& s) {
  std::vector<PanelWish> column;
  for (PanelId id : ids) column.push_back(wishes[size_t(id)]);
  const float available = y1 - y0 - s.margin * float(ids.size() - 1);
  const std::vector<float> h = columnHeights(column, available, s.title);
  float y = y0;
  for (size_t i = 0; i < ids.size(); ++i) {
    out.panels[size_t(ids[i])] = {x, y, w, h[i]};
    y += h[i] + s.margin;
  }
}

}  // namespace

const char* panelTitle(PanelId id) {
  static const char* const titles[] = {"Run",   "Parameters", "File", "Display",
                                       "Water", "Stats",      "Log"};
  return titles[size_t(id)];
}

Layout layOut(float w, float h, const Wishes& wishes, const LayoutStyle& s) {
  Layout out;
  w = std::max(w, 1.0f), h = std::max(h, 1.0f);
  const float m = s.margin;
  float column = std::clamp(s.columnShare * w, s.minColumn, s.maxColumn);
  column = std::max(std::min(column, (w - 3 * m) / 2), 0.0f);
  const float middle = w - 2 * column - 4 * m;
  const float top = m, bottom = h - m;
  const PanelWish& log = wishes[size_t(PanelId::kLog)];
  const float logHeight = log.collapsed ? s.title : s.logHeight;
  std::vector<PanelId> left = {PanelId::kRun, PanelId::kParameters, PanelId::kFile};
  std::vector<PanelId> right = {PanelId::kDisplay, PanelId::kWater, PanelId::kStats};
  const float middleX = column + 2 * m;
  if (middle >= 160) {
    const float logTop = std::max(bottom - logHeight, top);
    out.panels[size_t(PanelId::kLog)] = {middleX, logTop, middle, bottom - logTop};
    out.free = {middleX, top, middle, std::max(logTop - m - top, 0.0f)};
  } else {  // too narrow for a middle: the log goes under the right column
    right.push_back(PanelId::kLog);
    out.free = {middleX, top, std::max(middle, 0.0f), bottom - top};
  }
  // The log is as tall as the style says, whatever its lines ask for.
  Wishes fixed = wishes;
  fixed[size_t(PanelId::kLog)].height = s.logHeight;
  stack(out, left, fixed, m, column, top, bottom, s);
  stack(out, right, fixed, w - m - column, column, top, bottom, s);
  return out;
}

std::string checkLayout(const Layout& planned,
                        const std::array<Rect, size_t(PanelId::kCount)>& drawn,
                        const std::array<bool, size_t(PanelId::kCount)>& cut, float w, float h) {
  std::string problems;
  auto note = [&](const std::string& p) { problems += (problems.empty() ? "" : "; ") + p; };
  for (size_t i = 0; i < drawn.size(); ++i) {
    const Rect& r = drawn[i];
    const std::string name = panelTitle(PanelId(i));
    if (r.x < -0.5f || r.y < -0.5f || r.right() > w + 0.5f || r.bottom() > h + 0.5f)
      note(name + " outside the window");
    if (r.overlaps(planned.free)) note(name + " over the middle");
    if (cut[i]) note(name + " cut");
    for (size_t j = i + 1; j < drawn.size(); ++j)
      if (r.overlaps(drawn[j])) note(name + " over " + panelTitle(PanelId(j)));
  }
  const std::string size = std::to_string(int(w)) + " x " + std::to_string(int(h));
  return "layout at " + size + ": " +
         (problems.empty() ? std::to_string(drawn.size()) +
                                 " panels inside the window, none overlapping another or the "
                                 "middle, nothing cut"
                           : problems);
}

}  // namespace scour
