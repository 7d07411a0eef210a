#include "engine/step_driver.h"

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

}  // namespace scour
