// scour: the one binary. Subcommands: run, bench, render, presets (later: the window, study, stress).
#include <cstdio>
#include <iostream>

#include "cli/commands.h"

int main(int argc, char** argv) {
  using namespace scour;
  CLI::App app{"Scour: hydraulic erosion with SPH (Krištof et al. 2009)", "scour"};
  app.require_subcommand(1);
  Command run = addRunCommand(app);
  Command bench = addBenchCommand(app);
  Command render = addRenderCommand(app);
  CLI::App* presets = app.add_subcommand("presets", "List the built-in scenes, one per line");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitInput;
  }
  try {
    if (presets->parsed()) {
      for (const auto& p : presetList()) std::cout << p.name << "\t" << p.description << "\n";
      return kExitOk;
    }
    if (app.got_subcommand("run")) return run();
    if (app.got_subcommand("bench")) return bench();
    if (app.got_subcommand("render")) return render();
  } catch (const InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitInput;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitFailure;
  }
  return kExitFailure;
}
