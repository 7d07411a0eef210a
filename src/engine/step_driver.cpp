#include "engine/step_driver.h"

#include <algorithm>

namespace scour {

const char* RunEnd::statusName() const {
  switch (status) {
    case Status::kOk: return "ok";
    case Status::kInvariantViolated: return "invariant_violated";
    case Status::kLimitExceeded: return "limit_exceeded";
    case Status::kFailed: return "failed";
  }
  return "failed";
}

std::string RunEnd::describe() const {
  switch (status) {
    case Status::kOk: return "";
    case Status::kInvariantViolated: return "invariant violated at " + message;
    case Status::kLimitExceeded: return "limit reached at " + message;
    case Status::kFailed: return "the run failed: " + message;
  }
  return "the run failed: " + message;
}

void RunProgress::add(double wall, double at) {
  samples_.emplace_back(wall, at);
  // Keep the window, and always two samples to take a rate from.
  while (samples_.size() > 2 && samples_.back().first - samples_[1].first >= window_)
    samples_.pop_front();
}

double RunProgress::fraction() const {
  if (samples_.empty() || !(to_ > from_)) return 0;
  return std::clamp((samples_.back().second - from_) / (to_ - from_), 0.0, 1.0);
}

double RunProgress::etaSeconds() const {
  if (samples_.size() < 2) return -1;
  const auto& [w0, a0] = samples_.front();
  const auto& [w1, a1] = samples_.back();
  if (!(w1 > w0) || !(a1 > a0)) return -1;
  return std::max(to_ - a1, 0.0) * (w1 - w0) / (a1 - a0);
}

}  // namespace scour
