// scour: the one binary. No subcommand: the window; subcommands: run, bench, render, stress,
// study, export, presets.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <tuple>

#include "app/app.h"
#include "app/render_budget.h"
#include "cli/commands.h"
#include "cli/render_options.h"
#include "scene/builtin_scenes.h"
#include "scene/timelapse.h"

int main(int argc, char** argv) {
  using namespace scour;
  CLI::App app{"Scour: hydraulic erosion with SPH (Krištof et al. 2009)", "scour"};
  app.require_subcommand(0, 1);
  // No subcommand: the window, on a scene (default: the `default` preset).
  std::string windowScene = "default";
  AppOptions window;
  double windowScale = 1.0;
  std::string windowSize = "1280x720";
  app.add_option("scene", windowScene, "Open the window on this built-in scene or scene file (default: default)");
  app.add_option("--scale", windowScale, "Scale the preset's particle count (window)")->check(kPositive);
  app.add_option("--size", windowSize, "Window size WxH (default 1280x720)");
  app.add_option("--quit-after-frames", window.quitAfterFrames, "Close the window after N frames")->check(kPositive);
  app.add_option("--quit-after-seconds", window.quitAfterSeconds, "Close the window after S seconds")->check(kPositive);
  app.add_option("--screenshot", window.screenshot, "On closing, save the last frame's picture (.png)");
  app.add_option("--panel-shots", window.panelShots, "With --quit-after-frames: the last frame with its panels as DIR/window.png and each panel as DIR/panel_<name>.png");
  app.add_flag("--paused", window.paused, "Start paused");
  app.add_option("--replay", window.replay, "Play scripted input events from a file (docs/app.md)");
  std::string windowQuality = "auto";
  app.add_option("--quality", windowQuality, "The water's quality: auto (as the frame budget allows; default), fine, grid1, grid1.5, grid2.25, grid3, grid3-half, particles");
  std::string windowTerrain = "erosion";
  app.add_option("--terrain", windowTerrain, "Terrain colours at the start: erosion (default), shaded, sediment");
  std::string windowLapse, windowLapseVideo = "mp4";
  app.add_option("--timelapse", windowLapse, "Record a time-lapse from the start: a picture every K steps (250) or S seconds of bed time (0.5s); its video when the window closes");
  auto* lapseVideoOpt = app.add_option("--timelapse-video", windowLapseVideo, "The time-lapse's video: mp4 (default), gif or none");
  auto* lapseOutOpt = app.add_option("--timelapse-out", window.timelapseFolder, "The time-lapse's folder (default scour_out_timelapse; the video beside it)");
  Command run = addRunCommand(app);
  Command bench = addBenchCommand(app);
  Command render = addRenderCommand(app);
  Command stress = addStressCommand(app);
  Command study = addStudyCommand(app);
  Command exportMaps = addExportCommand(app);
  CLI::App* presets = app.add_subcommand("presets", "List the built-in scenes, one per line");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    const std::string hint = commandLineHint(app, argc, argv);
    std::cerr << "error: " << (hint.empty() ? std::string(e.what()) : hint) << "\n";
    return kExitInput;
  }
  try {
    if (presets->parsed()) {
      for (const BuiltinScene& b : builtinScenes()) std::cout << b.spec.name << "\t" << b.spec.description << "\n";
      return kExitOk;
    }
    if (app.got_subcommand("run")) return run();
    if (app.got_subcommand("bench")) return bench();
    if (app.got_subcommand("render")) return render();
    if (app.got_subcommand("stress")) return stress();
    if (app.got_subcommand("study")) return study();
    if (app.got_subcommand("export")) return exportMaps();
    // The window.
    std::tie(window.width, window.height) = parseSize(windowSize, 64);
    if (!window.screenshot.empty()) requirePng("--screenshot", window.screenshot);
    if (!window.panelShots.empty()) {
      if (window.quitAfterFrames <= 0)
        throw InputError("--panel-shots: needs --quit-after-frames (the shots are of the last frame)");
      createOutputDirectory("--panel-shots", window.panelShots);
    }
    if (!windowLapse.empty()) {
      try {
        parseTimelapseSpacing("--timelapse", windowLapse, window.timelapse);
        parseTimelapseVideo("--timelapse-video", windowLapseVideo, window.timelapse);
      } catch (const TimelapseError& e) {
        throw InputError(e.what());
      }
      if (const std::string missing = window.timelapse.video != "none" ? ffmpegMissing() : "";
          !missing.empty())
        throw InputError("--timelapse: " + missing);
      // The folder is made before the window opens, so a bad one is refused here.
      createOutputDirectory("--timelapse-out", window.timelapseFolder);
    } else if (lapseVideoOpt->count() > 0 || lapseOutOpt->count() > 0) {
      throw InputError(std::string(lapseVideoOpt->count() > 0 ? "--timelapse-video" : "--timelapse-out") +
                       ": needs --timelapse (the spacing of the pictures)");
    }
    window.terrain = int(parseTerrain(windowTerrain));
    try {
      window.quality = RenderBudget::parse(windowQuality);
    } catch (const std::invalid_argument& e) {
      throw InputError(std::string("--quality: ") + e.what());
    }
    Scene scene;
    try {
      scene = loadScene(windowScene, windowScale, 0, {});
    } catch (const InputError& e) {  // `scour runn`: a slip of a command, not a scene
      const std::string hint = commandHint(app, windowScene);
      if (hint.empty()) throw;
      throw InputError("unknown command or scene '" + windowScene + "'; " + hint);
    }
    if (!window.replay.empty()) {
      try {
        readReplay(window.replay);  // refused before any window opens
      } catch (const std::invalid_argument& e) {
        throw InputError(std::string("--replay: ") + e.what());
      }
    }
    return runApp(scene.spec, window);
  } catch (const InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitInput;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitFailure;
  }
  return kExitFailure;
}
