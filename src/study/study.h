#pragma once
// `scour study`: what accuracy costs in time. Each study varies one choice that trades accuracy
// for time, runs a validation scene with a known answer for each value, and records the error
// against that answer beside the wall time per simulated second. The errors (docs/accuracy.md):
//
//   dam-break front     worst |Z_sim − Z| / Z over Martin & Moyce's points with 1.2 ≤ T ≤ 5,
//                       Z_sim the water's edge (foremost centre + Δs/2) over a
//   hydrostatic         worst |p − ρ0 g (H − y)| / (ρ0 g (H − y)) over the layers of the lower
//                       80 % of the column, averaged over the last part of the run
//   settling speed      |v_centroid / |v_s| − 1|, v_s of eq. (17)
//   diffusion variance  |(dσ²/dt) / (2D) − 1|, averaged over the three axes
//   soil budget         worst |budget − initial| / initial over the run, counting sediment that a
//                       scheme created or destroyed (the naive advection) as error
//   neighbor lists      max |x_kd − x_grid| / Δs after the same steps (the two searches differ
//                       only in summation order)
//
// The engine part lives here (no GL); the render-grid study needs a GL context and is run by the
// command (src/cli/study_command.cpp) through addRow.

#include <functional>
#include <string>
#include <vector>

namespace scour {

struct StudyRow {
  std::string study;      ///< "spacing", "time_step", "eos", ...
  std::string reference;  ///< "dam-break front", ...
  std::string choice;     ///< the value of the choice, e.g. "Δs = a/16"
  double error = 0;       ///< relative error against the reference (see above)
  double wall_seconds = 0;
  double simulated_seconds = 0;  ///< 0 for the render study (cost per frame)
  double cost = 0;        ///< wall seconds per simulated second (render: per frame)
  long particles = 0;
  std::string status = "ok";  ///< "ok", or why the run stopped (an invariant broke)
  bool pareto = false;    ///< on the error–cost Pareto front of its study and reference
};

struct StudyOptions {
  bool quick = false;  ///< fewer levels and shorter runs (CI)
  std::function<void(const std::string&)> log;  ///< progress lines (may be empty)
};

/// Runs the engine studies.
std::vector<StudyRow> runEngineStudies(const StudyOptions& o);
/// Marks each row's `pareto` within its (study, reference) group: no other stable row there is
/// at most as costly and at most as wrong, and better in one.
void markPareto(std::vector<StudyRow>& rows);

std::string studyCsv(const std::vector<StudyRow>& rows);
std::string studyMarkdown(const std::vector<StudyRow>& rows);
/// An SVG plot of error against cost (log–log) for one (study, reference) group, the Pareto front
/// joined by a line and its points filled.
std::string studySvg(const std::vector<StudyRow>& rows, const std::string& study,
                     const std::string& reference);
/// Problems with a study's CSV rows (an expected study missing, a non-finite error for a stable
/// run, a stable run without a time); empty when complete.
std::string checkStudy(const std::vector<StudyRow>& rows, const std::vector<std::string>& studies);

}  // namespace scour
