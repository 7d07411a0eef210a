#pragma once
// The line the window prints when it closes, which the tests read (tests/cli/test_app.sh):
// what was simulated, the sources, sinks and snapshots, where the water is, and the log.

#include <string>

#include "app/actions.h"

namespace scour {

/// The report on `last`, the worker's final snapshot, after `frames` frames with `glErrors`
/// GL errors: one summary line, then the actions' log, a "log: " line each.
std::string exitReport(const Snapshot& last, long frames, const Actions& actions, long glErrors);

}  // namespace scour
