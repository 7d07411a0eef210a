#include "engine/limits.h"

#include <algorithm>
#include <cmath>
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
  // Within the bound the slots are few: count them as Emitter makes them.
  const int r = int(std::ceil(s.radius / p.spacing));
  double exact = 0;
  for (int b = -r; b <= r; ++b)
    for (int a = -r; a <= r; ++a) {
      const double u = a * p.spacing, w = b * p.spacing;
      exact += u * u + w * w <= s.radius * s.radius + 1e-12;
    }
  return checkSourceSpeed(s, p, std::max(exact, 1.0), at);
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
