#include "app/exit_report.h"

#include <sstream>

namespace scour {

std::string exitReport(const Snapshot& last, long frames, const Actions& actions, long glErrors) {
  // Near the last placed or moved source, and around its disk within 3 Δs (there only what it
  // emits: it stands 6 Δs over the terrain; a layer it emits takes longer than the next to leave),
  // not water flowing past below.
  long near = 0, atDisk = 0;
  const Eigen::Vector3d& source = actions.lastSource();
  if (source.allFinite())
    for (const auto& x : last.frame.position) {
      const double d = (x.cast<double>() - source).norm();
      near += d < 0.25;
      atDisk += d < actions.lastRadius() + 3 * last.frame.spacing;
    }
  std::ostringstream where;
  for (const Source& s : last.sources)
    where << (where.tellp() > 0 ? " " : "") << formatPoint(s.center);
  std::ostringstream out;
  out << "closed after " << frames << " frames; simulated " << last.frame.time << " s, "
      << last.frame.step << " steps; " << last.sources.size() << " sources at [" << where.str()
      << "]; " << last.sinks.size() << " sinks, removed " << last.removedBySinks << "; "
      << last.snapshots.size() << " snapshots; erosion.k_eps " << last.params.k_eps << "; emitted "
      << last.emitted << "; painted " << last.painted
      << "; particles within 0.25 m of the last placed or moved source " << near
      << ", around its disk " << atDisk << "; GL errors: " << glErrors << "\n";
  for (const std::string& line : actions.log()) out << "log: " << line << "\n";
  return out.str();
}

}  // namespace scour
