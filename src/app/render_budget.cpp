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

}  // namespace

const std::array<RenderBudget::Level, RenderBudget::kLevels>& RenderBudget::levels() {
  static const std::array<Level, kLevels> l = {{
      {"fine", "fine", 0.75, true, true},
      {"grid1", "grid 1 Δs", 1.0, true, true},
      {"grid1.5", "grid 1.5 Δs", 1.5, true, true},
      {"grid2.25", "grid 2.25 Δs, no caustics", 2.25, false, true},
      {"grid3", "grid 3 Δs, no caustics or refraction", 3.0, false, false},
      {"particles", "particles only", 0.0, false, false},
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
  if (choice_ >= 0) level_ = choice_;
  framesAtLevel_ = 0;
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
  recent_[size_t(framesAtLevel_ % 3)] = seconds;
  ++framesAtLevel_;
  if (framesAtLevel_ >= 3) seen_[size_t(level_)] = median3(recent_);
  if (choice_ >= 0) return;
  auto moveTo = [&](int level) {
    level_ = std::clamp(level, 0, kLevels - 1);
    framesAtLevel_ = 0;
    recent_ = {};
  };
  // Far over the budget (a first frame of a big scene): down as many levels as it takes.
  if (framesAtLevel_ == 1 && seconds > 3 * budget_ && level_ < kLevels - 1) {
    moveTo(level_ + std::max(1, int(std::ceil(std::log(seconds / budget_) / std::log(kStep)))));
    return;
  }
  const double now = framesAtLevel_ >= 3 ? median3(recent_) : 0;
  if (framesAtLevel_ >= 3 && now > budget_ && level_ < kLevels - 1) {
    moveTo(level_ + 1);
    return;
  }
  // Up a level when it has room: as last measured there, or as estimated from this one. An old
  // measurement (the scene may have changed since) is tried again after a few hundred frames.
  if (level_ > 0 && framesAtLevel_ >= 30 && now < 0.5 * budget_) {
    const double finer = seen_[size_t(level_ - 1)];
    const double estimate = finer > 0 && framesAtLevel_ < 300 ? finer : now * kStep;
    if (estimate < 0.8 * budget_) moveTo(level_ - 1);
  }
}

std::string RenderBudget::describe() const {
  char buf[160];
  const double ms = 1e3 * (framesAtLevel_ >= 3 ? median3(recent_) : seen_[size_t(level_)]);
  std::snprintf(buf, sizeof buf, "%s: %s, %.0f ms a frame", choice_ < 0 ? "auto" : "pinned",
                levels()[size_t(level_)].name, ms);
  return buf;
}

}  // namespace scour
