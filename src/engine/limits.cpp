#include "engine/limits.h"

#include <cstdio>

namespace scour {

std::string checkSourceWork(const Source& s, const SimParams& p, const std::string& at) {
  char msg[320];
  const double slots = sourceSlotBound(s.radius, p.spacing);
  if (slots > Limits::kMaxPlacedPerStep) {
    std::snprintf(msg, sizeof msg,
                  "%s.radius: a disk of radius %g m holds about %.3g particle slots at spacing %g m, "
                  "more than the %.3g one step may place",
                  at.c_str(), s.radius, slots, p.spacing, Limits::kMaxPlacedPerStep);
    return msg;
  }
  const double dt = longestStep(p);
  const double placed = sourcePlacedPerStep(s, p.spacing, slots, dt);
  if (placed > Limits::kMaxPlacedPerStep) {
    std::snprintf(msg, sizeof msg,
                  "%s.rate: %g m³/s is %.3g particles per step of %g s at spacing %g m, more than "
                  "the %.3g one step may place",
                  at.c_str(), s.rate, placed, dt, p.spacing, Limits::kMaxPlacedPerStep);
    return msg;
  }
  // Within the bound the slots are few: the exact count, as Emitter makes them.
  return checkSourceSpeed(s, p, double(diskLattice(s.radius, p.spacing).size()), at);
}

std::string checkRainWork(const Rain& r, double area, const SimParams& p, const std::string& at) {
  const double dt = longestStep(p);
  const double drops = rainPlacedPerStep(r, area, p.spacing, dt);
  if (drops <= Limits::kMaxPlacedPerStep) return {};
  char msg[400];
  std::snprintf(msg, sizeof msg,
                "%s.intensity_mm_h: %g mm/h over the rectangle's %.3g m² on the terrain is %.3g drops "
                "per step of %g s at spacing %g m, more than the %.3g one step may place",
                at.c_str(), r.intensity_mm_h, area, drops, dt, p.spacing, Limits::kMaxPlacedPerStep);
  return msg;
}

std::string checkSourceSpeed(const Source& s, const SimParams& p, double slots, const std::string& at) {
  const double speed = s.rate / (slots * p.spacing * p.spacing);
  if (speed <= p.sound_speed) return {};
  char msg[320];
  std::snprintf(msg, sizeof msg,
                "%s.rate: %g m³/s through %.0f slot(s) of %g m is an exit speed of %.3g m/s, faster "
                "than the sound speed %g m/s (fluid.sound_speed): widen the disk or lower the rate",
                at.c_str(), s.rate, slots, p.spacing, speed, p.sound_speed);
  return msg;
}

}  // namespace scour
