// scour render: one picture of a checkpoint or of a scene's start; and the FrameWriter that
// `scour run --frames` uses.
#include <algorithm>
#include <cstdio>
#include <iostream>

#include "cli/commands.h"
#include "cli/render_options.h"
#include "engine/maps.h"
#include "render/context.h"
#include "render/renderer.h"
#include "scene/checkpoint.h"

namespace scour {

std::pair<int, int> parseSize(const std::string& text, int minSide) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < minSide ||
      h < minSide || w > 8192 || h > 8192)
    throw InputError("--size: expected WxH with each side in [" + std::to_string(minSide) + ", 8192], found '" +
                     text + "'");
  return {w, h};
}

RenderSettings::Terrain parseTerrain(const std::string& text) {
  if (text == "erosion") return RenderSettings::Terrain::kErosion;
  if (text == "shaded") return RenderSettings::Terrain::kShaded;
  if (text == "sediment") return RenderSettings::Terrain::kSediment;
  if (isErosionMap(text)) return RenderSettings::Terrain::kMap;
  std::string list;
  for (const std::string& m : erosionMapNames()) list += ", " + m;
  throw InputError("--terrain: expected erosion, shaded, sediment or an erosion map (" + list.substr(2) + "), found '" + text + "'");
}

void requirePng(const std::string& flag, const std::string& path) {
  if (path.size() < 5 || path.substr(path.size() - 4) != ".png")
    throw InputError(flag + ": expected a .png file name, found '" + path + "'");
}

void addRenderOptions(CLI::App* c, RenderOptions& o) {
  c->add_option("--gl", o.gl, "GL context: egl (default), osmesa, window");
  c->add_option("--size", o.size, "Picture size WxH (default 960x540)");
  c->add_option("--terrain", o.terrain, "Terrain colours: erosion (default), shaded, sediment, or an erosion map: wear, deposition, sediment, flow, wetness, shear_peak, shear_mean, flow_direction");
  c->add_option("--particles", o.particles, "Particle view: off (default), sediment, speed");
  c->add_flag("--no-water", o.noWater, "Leave out the water surface");
  c->add_flag("--no-reflections", o.noReflections, "Water without cube-map reflections");
  c->add_flag("--no-refraction", o.noRefraction, "Water without refraction");
  c->add_flag("--no-caustics", o.noCaustics, "No caustics under the water");
  c->add_option("--camera", o.camera, "Eye and target: ex ey ez tx ty tz [m]")->expected(6);
  c->add_option("--surface-cell", o.surfaceCell, "Density grid cell over the particle spacing (default 0.75)")
      ->check(CLI::Range(0.1, 8.0));
}

struct FrameWriter::Impl {
  std::unique_ptr<GlContext> context;
  std::unique_ptr<Renderer> renderer;
  RenderSettings settings;
  std::vector<float> camera;
};

FrameWriter::FrameWriter(const RenderOptions& o) : impl_(std::make_unique<Impl>()) {
  const auto [w, h] = parseSize(o.size, 16);
  RenderSettings& s = impl_->settings;
  s.terrain = parseTerrain(o.terrain);
  if (s.terrain == RenderSettings::Terrain::kMap) s.map = o.terrain;
  if (o.particles == "off") s.particles = RenderSettings::Particles::kOff;
  else if (o.particles == "sediment") s.particles = RenderSettings::Particles::kSediment;
  else if (o.particles == "speed") s.particles = RenderSettings::Particles::kSpeed;
  else throw InputError("--particles: expected off, sediment or speed, found '" + o.particles + "'");
  s.water = !o.noWater;
  s.reflections = !o.noReflections;
  s.refraction = !o.noRefraction;
  s.caustics = !o.noCaustics;
  for (float v : o.camera)
    if (!std::isfinite(v)) throw InputError("--camera: expected 6 finite numbers");
  impl_->camera = o.camera;
  s.surface.cell_over_spacing = o.surfaceCell;
  GlBackend backend;
  try {
    backend = parseGlBackend(o.gl);
  } catch (const std::invalid_argument& e) {
    throw InputError(std::string("--gl: ") + e.what());
  }
  impl_->context = createGlContext(backend, w, h);
  impl_->renderer = std::make_unique<Renderer>(w, h);
}

std::string FrameWriter::map() const {
  return impl_->settings.terrain == RenderSettings::Terrain::kMap ? impl_->settings.map : std::string();
}

FrameWriter::~FrameWriter() = default;

void FrameWriter::setSceneCamera(const Eigen::Vector3f& eye, const Eigen::Vector3f& target) {
  if (impl_->camera.empty()) impl_->camera = {eye.x(), eye.y(), eye.z(), target.x(), target.y(), target.z()};
}

void FrameWriter::write(const Frame& f, const std::string& path) {
  Camera c = overviewCamera(f);
  if (impl_->camera.size() == 6) {
    c.eye = {impl_->camera[0], impl_->camera[1], impl_->camera[2]};
    c.target = {impl_->camera[3], impl_->camera[4], impl_->camera[5]};
  }
  impl_->renderer->render(f, c, impl_->settings);
  for (int tries = 0; tries < 3 && impl_->renderer->surface().growIfOverflowed(); ++tries)
    impl_->renderer->render(f, c, impl_->settings);  // the whole surface, not a part of it
  impl_->renderer->writePng(path);
  if (impl_->context->errors() > 0)
    throw GlError("GL error while rendering " + path + ": " + impl_->context->lastError());
}

namespace {

struct RenderCommandOptions {
  std::string source, out;
  RenderOptions render;
  double scale = 1.0;
};

int renderPicture(const RenderCommandOptions& o) {
  Scene scene;
  std::unique_ptr<World> world;
  const bool checkpoint = o.source.size() > 5 && o.source.substr(o.source.size() - 5) == ".ckpt";
  try {
    if (checkpoint) {
      world = std::make_unique<World>(resumeWorld(readCheckpoint(o.source), scene));
    } else {
      scene = loadScene(o.source, o.scale, 0, {});
      world = std::make_unique<World>(scene.desc);
    }
  } catch (const CheckpointError& e) {
    throw InputError(e.what());
  } catch (const std::invalid_argument& e) {
    throw InputError(o.source + ": " + e.what());
  }
  requirePng("--out", o.out);
  FrameWriter writer(o.render);
  if (scene.spec.has_camera)
    writer.setSceneCamera(scene.spec.camera_eye.cast<float>(), scene.spec.camera_target.cast<float>());
  writer.write(makeFrame(*world, writer.map()), o.out);
  std::cout << "rendered step " << world->steps() << " (" << world->fluid().size() << " particles) to "
            << o.out << "\n";
  return kExitOk;
}

}  // namespace

Command addRenderCommand(CLI::App& app) {
  auto o = std::make_shared<RenderCommandOptions>();
  CLI::App* c = app.add_subcommand("render", "Render one picture of a checkpoint or of a scene's start");
  c->add_option("source", o->source, "A checkpoint (.ckpt), a built-in scene or a scene file")->required();
  c->add_option("--out", o->out, "The picture (.png)")->required();
  c->add_option("--scale", o->scale, "Scale the preset's particle count")->check(kPositive);
  addRenderOptions(c, o->render);
  return [o] { return renderPicture(*o); };
}

}  // namespace scour
