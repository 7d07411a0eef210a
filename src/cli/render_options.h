#pragma once
// The picture options shared by `scour render` and `scour run --frames`.
#include <CLI/CLI.hpp>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "engine/frame.h"
#include "render/renderer.h"

namespace scour {

struct RenderOptions {
  std::string gl = "egl";
  std::string size = "960x540";
  std::string terrain = "erosion";
  std::string particles = "off";
  bool noWater = false, noReflections = false, noRefraction = false, noCaustics = false;
  std::vector<float> camera;  ///< eye x y z, target x y z (empty: the scene's, or the overview)
  double surfaceCell = 0.75;  ///< density grid cell / Δs
};

/// "WxH" with each side in [minSide, 8192]; InputError naming --size otherwise.
std::pair<int, int> parseSize(const std::string& text, int minSide);
/// "erosion", "shaded" or "sediment"; InputError naming --terrain otherwise.
RenderSettings::Terrain parseTerrain(const std::string& text);
/// A picture file name must end in .png; InputError naming the flag otherwise.
void requirePng(const std::string& flag, const std::string& path);

/// Registers --gl, --size, --terrain, --particles, --no-water, --no-reflections,
/// --no-refraction, --no-caustics and --camera on a subcommand.
void addRenderOptions(CLI::App* c, RenderOptions& o);

/// A GL context and renderer made from the options; writes pictures of frames. The options are
/// checked when it is made (InputError naming the flag).
class FrameWriter {
 public:
  explicit FrameWriter(const RenderOptions& o);
  ~FrameWriter();
  void write(const Frame& f, const std::string& path);
  /// The scene's camera, used unless --camera was given.
  void setSceneCamera(const Eigen::Vector3f& eye, const Eigen::Vector3f& target);
  /// The erosion map --terrain asked for ("" for none): make the frames with it (makeFrame).
  std::string map() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace scour
