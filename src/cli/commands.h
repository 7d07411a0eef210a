#pragma once
// The subcommands. Each registers its options on the CLI11 app and returns the exit code:
// 0 success, 1 failure while running (I/O), 2 bad input (flags, scene), 3 invariant violated.

#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/step_driver.h"
#include "scene/presets.h"

namespace scour {

constexpr int kExitOk = 0, kExitFailure = 1, kExitInput = 2, kExitInvariant = 3;

/// The exit code of a run of steps that ended so: 0, 1 (failed) or 3 (an invariant or a limit).
inline int exitCode(const RunEnd& end) {
  return end.ok() ? kExitOk : end.status == RunEnd::Status::kFailed ? kExitFailure : kExitInvariant;
}

/// An input error found after parsing; main prints "error: <what>" and exits with 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using Command = std::function<int()>;
Command addRunCommand(CLI::App& app);
Command addBenchCommand(CLI::App& app);
Command addRenderCommand(CLI::App& app);
Command addStressCommand(CLI::App& app);
Command addStudyCommand(CLI::App& app);
Command addExportCommand(CLI::App& app);

/// Shared by run and bench: builds the scene and applies `--set key=value` overrides.
Scene loadScene(const std::string& name, double scale, long particles,
                const std::vector<std::string>& sets);
/// The world a checkpoint holds (its scene into `scene`); InputError for a file that is not one
/// or does not fit its scene: prefix + the reader's message, or prefix + path + ": " + the scene's.
std::unique_ptr<World> resumeFromCheckpoint(const std::string& path, Scene& scene, const std::string& prefix);
/// Makes the directory `path` (and its parents); InputError naming `flag` when it cannot.
void createOutputDirectory(const std::string& flag, const std::string& path);
/// Applies `--set key=value` overrides; throws InputError naming the key for a bad one.
void applySets(SimParams& params, const std::vector<std::string>& sets);
/// For a command line CLI11 refused: "unknown option '--particle-every' for 'scour run'; did you
/// mean '--particles-every'?" for the first option the command does not have ("" if none).
std::string commandLineHint(const CLI::App& app, int argc, char** argv);
/// For a word taken as a scene that names no scene: "did you mean the command 'scour run'?" when
/// it is a slip of a command's name ("" if not).
std::string commandHint(const CLI::App& app, const std::string& word);
/// A CLI11 validator: a finite number > 0.
extern const CLI::Validator kPositive;
void setThreads(int threads);

}  // namespace scour
