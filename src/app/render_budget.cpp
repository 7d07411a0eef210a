#include "app/render_budget.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace scour {

namespace {

double median3(std::array<double, 3> v) {
  std::sort(v.begin(), v.end());
  return v[1];
}

// About how much cheaper each level is than the one before (the grid's nodes and the surface's
// triangles fall with the cell's size; the last levels also drop effects).
constexpr double kStep = 2.5;
// A level in use is left only for frames over the budget by more than this factor: a level whose
// frames sit at the budget (lake --scale 0.3 at grid 3 Δs, half resolution, on llvmpipe: 38–40 ms)
// would otherwise drop to the particles on a noisy median of three and come back frames later,
// the picture switching between the surface and the particles. 46 ms is still 21.7 frames a second.
constexpr double kKeep = 1.15;

}  // namespace

const std::array<RenderBudget::Level, RenderBudget::kLevels>& RenderBudget::levels() {
  static const std::array<Level, kLevels> l = {{
      {"fine", "fine", 0.75, true, true, 1.0},
      {"grid1", "grid 1 Δs", 1.0, true, true, 1.0},
      {"grid1.5", "grid 1.5 Δs", 1.5, true, true, 1.0},
      {"grid2.25", "grid 2.25 Δs, no caustics", 2.25, false, true, 1.0},
      {"grid3", "grid 3 Δs, no caustics or refraction", 3.0, false, false, 1.0},
      {"grid3-half", "grid 3 Δs, no caustics or refraction, half resolution", 3.0, false, false, 0.5},
      {"particles", "particles only, half resolution", 0.0, false, false, 0.5},
  }};
  return l;
}

int RenderBudget::parse(const std::string& key) {
  if (key == "auto") return -1;
  std::string keys = "auto";
  for (int k = 0; k < kLevels; ++k) {
    if (key == levels()[size_t(k)].key) return k;
    keys += std::string(", ") + levels()[size_t(k)].key;
  }
  throw std::invalid_argument("expected one of " + keys + ", found '" + key + "'");
}

void RenderBudget::choose(int level) {
  choice_ = std::clamp(level, -1, kLevels - 1);
  if (choice_ >= 0) moveTo(choice_);
  framesAtLevel_ = 0;
}

void RenderBudget::moveTo(int level) {
  level_ = std::clamp(level, 0, kLevels - 1);
  framesAtLevel_ = 0;
  build_ = {}, draw_ = {}, all_ = {};
  stale_ = true, sinceRebuild_ = kMaxEvery;  // a new grid: the renderer rebuilds at once
}

double RenderBudget::Recent::value() const {
  if (n == 0) return 0;
  if (n >= 3) return median3(t);
  double sum = 0;
  for (int k = 0; k < n; ++k) sum += t[size_t(k)];
  return sum / n;
}

int RenderBudget::everyFor(double b, double d, double budget) {
  if (b <= budget) return 1;
  if (d >= budget) return kMaxEvery;
  for (int k = 2; k < kMaxEvery; ++k)
    if (mean(b, d, k) <= budget) return k;
  return kMaxEvery;
}

double RenderBudget::frameMean(int level) const {
  const double b = seenBuild_[size_t(level)], d = seenDraw_[size_t(level)];
  if (b > 0 && d > 0) return mean(b, d, everyFor(b, d, budget_));
  return std::max(b, d);
}

int RenderBudget::every() const {
  if (levels()[size_t(level_)].cellOverSpacing == 0) return 1;
  const double b = seenBuild_[size_t(level_)];
  return b > 0 ? everyFor(b, seenDraw_[size_t(level_)], budget_) : 1;
}

bool RenderBudget::rebuild(bool newFrame) {
  stale_ = stale_ || newFrame;
  const bool surface = levels()[size_t(level_)].cellOverSpacing > 0;
  rebuilding_ = surface && stale_ && sinceRebuild_ + 1 >= every();
  if (rebuilding_)
    stale_ = false, sinceRebuild_ = 0;
  else
    ++sinceRebuild_;
  return rebuilding_;
}

std::pair<int, int> RenderBudget::viewSize(int w, int h) const {
  const double r = levels()[size_t(level_)].resolution;
  return {std::max(16, int(std::lround(w * r))), std::max(16, int(std::lround(h * r)))};
}

RenderSettings RenderBudget::apply(RenderSettings s) const {
  const Level& l = levels()[size_t(level_)];
  if (l.cellOverSpacing == 0) {
    if (s.water && s.particles == RenderSettings::Particles::kOff)
      s.particles = RenderSettings::Particles::kSediment;  // blue: clear water
    s.water = false;
    return s;
  }
  s.surface.cell_over_spacing = std::max(s.surface.cell_over_spacing, l.cellOverSpacing);
  s.caustics = s.caustics && l.caustics;
  s.refraction = s.refraction && l.refraction;
  return s;
}

void RenderBudget::measured(double seconds) {
  ++framesAtLevel_;
  (rebuilding_ ? build_ : draw_).add(seconds);
  all_.add(seconds);
  const double b = build_.value(), d = draw_.value();
  if (build_.n) seenBuild_[size_t(level_)] = b;
  if (draw_.n) seenDraw_[size_t(level_)] = d;
  if (choice_ >= 0) return;
  // Far over the hitch (a first frame of a big scene): down as many levels as it takes.
  if (framesAtLevel_ == 1 && seconds > 3 * hitch_ && level_ < kLevels - 1) {
    moveTo(level_ + std::max(1, int(std::ceil(std::log(seconds / hitch_) / std::log(kStep)))));
    return;
  }
  // Down a level when the drawing alone misses the budget, a rebuild stalls the picture, or even
  // the rarest rebuild leaves the mean over the budget (each by more than the noise, kKeep).
  const bool slowDraw = draw_.n >= 3 && d > kKeep * budget_;
  const bool slowBuild = build_.n >= 2 && b > hitch_;
  const bool slowMean = build_.n >= 2 && draw_.n >= 3 && mean(b, d, kMaxEvery) > kKeep * budget_;
  // For the budget (not a hitch), only if the level below was not seen costing about as much: then
  // what costs the time is not the water (the panels, the swap, the engine's threads on the same
  // cores) and going down would only take the surface away.
  const bool helps = level_ < kLevels - 1 && [&] {
    const double below = frameMean(level_ + 1);
    return below == 0 || below < 0.85 * frameMean(level_);
  }();
  if ((slowBuild || ((slowDraw || slowMean) && helps)) && level_ < kLevels - 1) {
    // A level that fails soon after it was tried waits twice as long for its next try; one that
    // held for long (the scene has changed since) is tried again soon.
    int& wait = retry_[size_t(level_)];
    wait = framesAtLevel_ < kRetryMax ? std::min(2 * wait, kRetryMax) : kRetryMin;
    moveTo(level_ + 1);
    return;
  }
  // Up a level when it has room: as last measured there, or as estimated from this one (a frame
  // that rebuilds bounds one that does not). The estimate misses what every frame costs besides
  // the water (the panels, the swap, the engine's threads on the same cores), so a finer level
  // last seen near its limits is tried again, for real, after a while: if it does not
  // fit, a few frames bring the quality back down. The first try comes soon (the first frames of
  // a window are slow: the engine starting, the shaders compiled), later ones ever later, up to
  // every kRetryMax frames.
  if (level_ > 0 && framesAtLevel_ >= 30) {
    const double here = all_.value();
    const double b0 = build_.n ? b : here, d0 = draw_.n ? d : here;
    const bool old = framesAtLevel_ >= retry_[size_t(level_ - 1)];  // the scene may have changed since
    const double seenB = seenBuild_[size_t(level_ - 1)], seenD = seenDraw_[size_t(level_ - 1)];
    const double fb = seenB > 0 && !old ? seenB : b0 * kStep, fd = seenD > 0 && !old ? seenD : d0 * kStep;
    const bool room = fb < 0.8 * hitch_ && fd < 0.8 * budget_ && mean(fb, fd, kMaxEvery) < 0.8 * budget_;
    const bool near = old && (seenB > 0 || seenD > 0) && seenB < 1.5 * hitch_ && seenD < 1.5 * budget_;
    if (room || near) moveTo(level_ - 1);
  }
}

std::string RenderBudget::describe() const {
  char buf[240];
  const char* mode = choice_ < 0 ? "auto" : "pinned";
  const char* name = levels()[size_t(level_)].name;
  const int k = every();
  if (k == 1) {
    const double ms = 1e3 * (all_.n ? all_.value() : std::max(seenBuild_[size_t(level_)], seenDraw_[size_t(level_)]));
    std::snprintf(buf, sizeof buf, "%s: %s, %.0f ms a frame", mode, name, ms);
    return buf;
  }
  const double b = seenBuild_[size_t(level_)], d = seenDraw_[size_t(level_)];
  static const char* const kOrdinal[] = {"", "", "2nd", "3rd", "4th", "5th", "6th", "7th", "8th"};
  std::snprintf(buf, sizeof buf, "%s: %s, surface every %s frame (rebuild %.0f ms, draw %.0f ms), %.0f ms a frame",
                mode, name, kOrdinal[k], 1e3 * b, 1e3 * d, 1e3 * mean(b, d, k));
  return buf;
}

}  // namespace scour
