// `scour stress`: the hard scenes, every invariant checked every step, a PASS/FAIL report.
#include <fstream>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "scene/output.h"
#include "scene/scene_json.h"
#include "study/stress.h"

namespace scour {

namespace {

struct StressOptions {
  std::vector<std::string> scenes;
  int threads = 0;
  bool list = false;
  bool quiet = false;
  std::string out;
  std::string trace;
  std::vector<std::string> sets;
  long paper = 0;
  double time = 0;  ///< > 0: --time given
};

// A name with a '/' or ending in .json is a scene file, reported under its file name and run
// as its "stress" section says; `time` > 0 (--time) sets the simulated seconds, which are
// otherwise the section's or 1.
StressScene stressSceneOrFile(const std::string& name, double time) {
  if (name.find('/') == std::string::npos && !name.ends_with(".json")) return stressScene(name);
  StressScene s = stressSceneFrom(loadSceneFile(name), std::filesystem::path(name).stem().string());
  if (s.description.empty()) s.description = name;
  double& duration = s.spec.stress.duration;
  if (time > 0) duration = time;
  if (!(duration > 0)) duration = 1.0;
  return s;
}

int stress(const StressOptions& o) {
  if (o.list) {
    for (const std::string& n : stressSceneNames())
      std::cout << n << "\t" << stressScene(n).description << "\n";
    return kExitOk;
  }
  setThreads(o.threads);
  std::vector<StressScene> scenes;
  try {
    if (o.paper > 0) {
      if (!o.scenes.empty()) throw InputError("--paper: runs the paper's scenes; drop --scene");
      scenes = paperStressScenes(o.paper);
    } else {
      for (const std::string& n : o.scenes.empty() ? stressSceneNames() : o.scenes)
        scenes.push_back(stressSceneOrFile(n, o.time));
    }
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("--scene: ") + e.what());
  }
  for (StressScene& s : scenes) applySets(s.spec.params, o.sets);
  const StressLimits limits;
  std::vector<StressResult> results;
  bool allPass = true;
  for (const StressScene& s : scenes) {
    if (!o.quiet) std::cerr << "stress: " << s.name << " (" << s.description << ")\n";
    std::ofstream trace;
    if (!o.trace.empty()) {
      trace.open(o.trace + "/" + s.name + ".csv");
      if (!trace) throw InputError("--trace: cannot write into '" + o.trace + "'");
    }
    StressResult r = runStress(
        s, limits,
        [&](const StressResult& so) {
          if (!o.quiet)
            std::cerr << "  step " << so.steps << ", t = " << so.simulated << " s, "
                      << so.particles_end << " particles\n";
        },
        o.trace.empty() ? nullptr : &trace);
    if (!r.pass) std::cerr << "stress: " << r.name << " FAILED: " << r.failure << "\n";
    allPass = allPass && r.pass;
    results.push_back(std::move(r));
  }
  const std::string table = stressTable(results, limits);
  std::cout << table;
  if (!o.out.empty()) {
    const std::filesystem::path dir(o.out);
    std::filesystem::create_directories(dir);
    writeAtomically(dir / "stress.csv", [&](std::ostream& f) { f << stressCsv(results); });
    writeAtomically(dir / "stress.md", [&](std::ostream& f) {
      f << table;
      for (const StressResult& r : results)
        if (!r.pass) f << "\n" << r.name << ": " << r.failure << "\n";
    });
  }
  std::cout << (allPass ? "stress: PASS" : "stress: FAIL") << " (" << results.size()
            << (results.size() == 1 ? " scene)\n" : " scenes)\n");
  return allPass ? kExitOk : kExitInvariant;
}

}  // namespace

Command addStressCommand(CLI::App& app) {
  auto o = std::make_shared<StressOptions>();
  CLI::App* c = app.add_subcommand(
      "stress", "Hard scenes with every invariant checked every step; exits 3 if one fails");
  c->add_option("--scene", o->scenes,
                "Run only this scene, or a scene file (.json) (repeatable; default: all)");
  c->add_option("--time", o->time,
                "Simulated seconds for a scene file (default: its stress section's, else 1)")
      ->check(kPositive);
  c->add_option("--set", o->sets, "Override a parameter in every scene: key=value (repeatable)");
  c->add_flag("--list", o->list, "List the scenes, one per line");
  c->add_option("--threads", o->threads, "OpenMP threads (default: all cores)")->check(kPositive);
  c->add_option("--out", o->out, "Also write stress.csv and stress.md into this directory");
  c->add_option("--trace", o->trace, "Write a per-step energy trace <scene>.csv into this directory");
  c->add_flag("--quiet", o->quiet, "No progress lines on stderr");
  c->add_option("--paper", o->paper,
                "Instead: the paper's canyon, lake and waterfall at full size for N steps each "
                "(minutes; not in CI)")
      ->check(kPositive);
  return [o] { return stress(*o); };
}

}  // namespace scour
