#include "app/exit_report.h"

#include <algorithm>
#include <sstream>

namespace scour {

NearSource countNearSource(const Snapshot& snap, const Actions& actions) {
  NearSource n;
  const Eigen::Vector3d& source = actions.lastSource();
  if (source.allFinite())
    for (const auto& x : snap.frame.position) {
      const double d = (x.cast<double>() - source).norm();
      n.near += d < 0.25;
      n.atDisk += d < actions.lastRadius() + 3 * snap.frame.spacing;
    }
  return n;
}

void SourceWatch::see(const Snapshot& snap, const Actions& actions) {
  const Eigen::Vector3d& source = actions.lastSource();
  if (!source.allFinite()) return;
  if (source != source_) source_ = source, most_ = {};  // placed or moved: count afresh
  const NearSource now = countNearSource(snap, actions);
  most_.near = std::max(most_.near, now.near), most_.atDisk = std::max(most_.atDisk, now.atDisk);
}

std::string exitReport(const Snapshot& last, long frames, const Actions& actions, long glErrors,
                       const NearSource& most) {
  const NearSource n = countNearSource(last, actions);
  std::ostringstream where;
  for (const Source& s : last.sources)
    where << (where.tellp() > 0 ? " " : "") << formatPoint(s.center);
  std::ostringstream out;
  out << "closed after " << frames << " frames; simulated " << last.frame.time << " s, "
      << last.frame.step << " steps; " << last.sources.size() << " sources at [" << where.str()
      << "]; " << last.sinks.size() << " sinks, removed " << last.removedBySinks << "; "
      << last.snapshots.size() << " snapshots; erosion.k_eps " << last.params.k_eps << "; emitted "
      << last.emitted << "; painted " << last.painted
      << "; particles within 0.25 m of the last placed or moved source " << n.near
      << ", around its disk " << n.atDisk << " (at most " << std::max(most.near, n.near) << " and "
      << std::max(most.atDisk, n.atDisk) << " in one frame since it was placed or moved); GL errors: "
      << glErrors << "\n";
  for (const std::string& line : actions.log()) out << "log: " << line << "\n";
  return out.str();
}

}  // namespace scour
