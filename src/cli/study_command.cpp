// `scour study`: accuracy against cost. The engine studies (src/study/study.cpp) and the render
// density-grid study (here: it needs a GL context), written as study.csv, study.md and one SVG
// plot per study and reference.
#include <nanoflann.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "engine/step_driver.h"
#include "engine/frame.h"
#include "render/context.h"
#include "render/surface.h"
#include "scene/output.h"
#include "study/study.h"

namespace scour {

namespace {

struct StudyCommandOptions {
  bool quick = false;
  bool noRender = false;
  int threads = 0;
  std::string out = "out/study";
};

// Triangle centroids for nanoflann.
struct Centroids {
  std::vector<Eigen::Vector3f> c;
  size_t kdtree_get_point_count() const { return c.size(); }
  float kdtree_get_pt(size_t i, size_t d) const { return c[i][int(d)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};
using CentroidTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Centroids>, Centroids,
                                        3, uint32_t>;

// RMS distance of the vertices of `mesh` to the nearest triangle of `reference` (searched among
// the 16 triangles with the nearest centroids) [m].
double meshDistance(const std::vector<SurfaceTriangle>& mesh,
                    const std::vector<SurfaceTriangle>& reference) {
  Centroids cs;
  for (const SurfaceTriangle& t : reference)
    cs.c.push_back((t[0].position + t[1].position + t[2].position) / 3.0f);
  if (cs.c.empty() || mesh.empty()) return std::numeric_limits<double>::infinity();
  CentroidTree tree(3, cs, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();
  const size_t k = std::min<size_t>(16, cs.c.size());
  std::vector<uint32_t> idx(k);
  std::vector<float> d2(k);
  double sum = 0;
  long n = 0;
  for (const SurfaceTriangle& t : mesh)
    for (const SurfaceVertex& v : t) {
      const size_t found = tree.knnSearch(v.position.data(), k, idx.data(), d2.data());
      double best = std::numeric_limits<double>::infinity();
      for (size_t q = 0; q < found; ++q) {
        const SurfaceTriangle& r = reference[idx[q]];
        best = std::min(best, pointTriangleDistance(v.position.cast<double>(),
                                                    r[0].position.cast<double>(),
                                                    r[1].position.cast<double>(),
                                                    r[2].position.cast<double>()));
      }
      sum += best * best, ++n;
    }
  return std::sqrt(sum / double(n));
}

// The water surface of a dam break in full flow (T ≈ 2.5) extracted at several density-grid
// cells, against a grid of Δs/4: RMS vertex distance in Δs, and the wall time of the extraction
// (splat, occupancy, march; median of 5).
std::vector<StudyRow> renderGridStudy(bool quick, const std::function<void(const std::string&)>& log) {
  SceneSpec spec = presetSpec("dambreak", quick ? 0.3 : 1.0);
  World w(buildScene(spec).desc);
  const RunEnd end = runWhile(w, [&] { return w.time() < 0.14; }, [](const StepRecord&) {});
  if (!end.ok()) throw std::runtime_error("render grid study: the dam break stopped: " + end.message);
  const Frame frame = makeFrame(w);
  const double ds = spec.params.spacing;
  const auto context = createGlContext(GlBackend::kEgl);
  auto extract = [&](double cell, double* wall) {
    SurfaceSettings s;
    s.cell_over_spacing = cell;
    s.profile = true;
    WaterSurface surface(s);
    surface.update(frame);
    while (surface.growIfOverflowed()) surface.update(frame);
    std::vector<double> t;
    for (int k = 0; k < 5; ++k) {
      surface.update(frame);
      const WaterSurface::Timings tm = surface.readTimings();
      t.push_back(tm.splat + tm.occupancy + tm.march);
    }
    std::sort(t.begin(), t.end());
    if (wall) *wall = t[t.size() / 2];
    return surface.readTriangles();
  };
  const std::vector<SurfaceTriangle> fine = extract(0.25, nullptr);
  std::vector<StudyRow> rows;
  for (double cell : quick ? std::vector<double>{1.0, 0.5} : std::vector<double>{1.5, 1.0, 0.75, 0.5}) {
    double wall = 0;
    const std::vector<SurfaceTriangle> mesh = extract(cell, &wall);
    StudyRow r;
    r.study = "render_grid";
    r.reference = "surface vs a Δs/4 grid";
    r.choice = "cell = " + std::to_string(cell).substr(0, 4) + " Δs";
    r.error = meshDistance(mesh, fine) / ds;
    r.wall_seconds = wall;
    r.cost = wall;
    r.particles = long(frame.particles());
    if (log) log("render_grid / " + r.choice + ": error " + std::to_string(r.error) + " Δs");
    rows.push_back(r);
  }
  return rows;
}

int study(const StudyCommandOptions& o) {
  setThreads(o.threads);
  const auto start = std::chrono::steady_clock::now();
  StudyOptions so;
  so.quick = o.quick;
  so.log = [](const std::string& line) { std::cerr << "study: " << line << "\n"; };
  std::vector<StudyRow> rows = runEngineStudies(so);
  std::vector<std::string> studies = {"spacing", "time_step", "eos", "neighbor_search",
                                      "advection", "diffusion_form", "morphological_factor",
                                      "erosion_spacing", "solver"};
  if (!o.noRender) {
    for (StudyRow& r : renderGridStudy(o.quick, so.log)) rows.push_back(std::move(r));
    studies.push_back("render_grid");
  }
  markPareto(rows);
  const std::filesystem::path dir(o.out);
  std::filesystem::create_directories(dir);
  writeAtomically(dir / "study.csv", [&](std::ostream& f) { f << studyCsv(rows); });
  writeAtomically(dir / "study.md", [&](std::ostream& f) { f << studyMarkdown(rows); });
  std::vector<std::pair<std::string, std::string>> groups;
  for (const StudyRow& r : rows)
    if (std::find(groups.begin(), groups.end(), std::make_pair(r.study, r.reference)) == groups.end())
      groups.emplace_back(r.study, r.reference);
  for (const auto& [s, ref] : groups) {
    std::string name = s + "-" + ref;
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
    writeAtomically(dir / (name + ".svg"), [&](std::ostream& f) { f << studySvg(rows, s, ref); });
  }
  std::cout << studyMarkdown(rows);
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string problem = checkStudy(rows, studies);
  if (!problem.empty()) {
    std::cerr << "study: incomplete: " << problem << "\n";
    return kExitFailure;
  }
  std::cout << "\nstudy: " << rows.size() << " runs in " << total << " s; wrote " << (dir / "study.csv").string()
            << ", study.md and " << groups.size() << " plots\n";
  return kExitOk;
}

}  // namespace

Command addStudyCommand(CLI::App& app) {
  auto o = std::make_shared<StudyCommandOptions>();
  CLI::App* c = app.add_subcommand(
      "study", "Accuracy against cost: error against known answers and wall time per choice");
  c->add_flag("--quick", o->quick, "Fewer levels and shorter runs (a few minutes; CI)");
  c->add_flag("--no-render", o->noRender, "Skip the render density-grid study (needs EGL)");
  c->add_option("--threads", o->threads, "OpenMP threads (default: all cores)")->check(kPositive);
  c->add_option("--out", o->out, "Directory for study.csv, study.md and the plots (default out/study)");
  return [o] { return study(*o); };
}

}  // namespace scour
