#pragma once
// The line the window prints when it closes, which the tests read (tests/cli/test_app.sh):
// what was simulated, the sources, sinks and snapshots, where the water is, and the log.

#include <limits>
#include <string>

#include "app/actions.h"

namespace scour {

/// Particles near the last placed or moved source: within 0.25 m of its centre, and around its
/// disk within 3 Δs (there only what it emits: it stands 6 Δs over the terrain, so water flowing
/// past below does not count). Both 0 when no source was placed or moved.
struct NearSource {
  long near = 0, atDisk = 0;
};
NearSource countNearSource(const Snapshot& snap, const Actions& actions);

/// The most particles near the last placed or moved source and around its disk, each in one
/// snapshot since it was placed or moved. A layer leaves the disk in about the time the next one
/// takes to come, and the water under it flows on, so the last snapshot alone may show none
/// although the source pours.
class SourceWatch {
 public:
  void see(const Snapshot& snap, const Actions& actions);
  const NearSource& most() const { return most_; }

 private:
  Eigen::Vector3d source_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  NearSource most_;
};

/// The report on `last`, the worker's final snapshot, after `frames` frames with `glErrors`
/// GL errors, `most` from a SourceWatch: one summary line, then the actions' log, a "log: " line
/// each.
std::string exitReport(const Snapshot& last, long frames, const Actions& actions, long glErrors,
                       const NearSource& most);

}  // namespace scour
