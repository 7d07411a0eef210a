#pragma once
// Pictures of a Frame: the terrain (height/slope ramp, erosion false colour or sediment), the
// water surface of the paper's §5 with cube-map reflections, refraction of the terrain behind it
// and caustics after Shah et al. 2007, and a particle view. Renders into its own framebuffer;
// readPixels / writePng take the picture, blitTo shows it in a window.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "engine/frame.h"
#include "render/gl.h"
#include "render/program.h"
#include "render/surface.h"

namespace scour {

struct Camera {
  Eigen::Vector3f eye{0, 1, 2}, target{0, 0, 0}, up{0, 1, 0};
  float fov_deg = 40.0f;
  Eigen::Matrix4f cameraFromWorld() const;  ///< the view (look-at) transform
  Eigen::Matrix4f clipFromCamera(float aspect, float near, float far) const;  ///< perspective
};

/// A three-quarter view of the whole terrain, from the south-west and above.
Camera overviewCamera(const Frame& f);

struct RenderSettings {
  /// kMap: the frame's erosion map (Frame::map), dark where it is 0, then blue to yellow by
  /// √(value / its largest); a direction map (Frame::map2 too) by hue.
  enum class Terrain { kShaded, kErosion, kSediment, kMap };
  enum class Particles { kOff, kSediment, kSpeed };
  Terrain terrain = Terrain::kErosion;
  /// With kMap: which erosion map the frames are made with (engine/maps.h).
  std::string map = "wetness";
  bool water = true;        ///< the marching-tetrahedra surface
  bool reflections = true;  ///< sky cube map in the water
  bool refraction = true;   ///< the terrain seen through the water
  bool caustics = true;     ///< light focused by the surface on the terrain under it
  Particles particles = Particles::kOff;
  /// With the surface on and the particles off: the water the surface does not cover (a jet in
  /// flight, drops) as sprites.
  bool spray = true;
  /// The frame is the one drawn last (the window between two steps): its terrain and, if the
  /// surface's settings are unchanged, its surface are kept, not built again.
  bool same_frame = false;
  /// Draw the surface built last even for a new frame (the window, when the frame budget allows
  /// a rebuild only every few frames): the terrain is the new frame's, and the new frame's
  /// particles outside the old surface show as spray. The caustics, which follow the surface,
  /// are kept with it. Ignored when nothing was built yet or the surface's settings changed.
  bool keep_surface = false;
  float change_scale = 0;   ///< |Δh| for full false colour [m]; 0: the frame's largest
  float refraction_strength = 0.05f;
  float caustic_strength = 0.7f;
  int caustic_map = 512;    ///< texels per side of the caustics maps
  Eigen::Vector3f sun{0.35f, 1.0f, 0.25f};  ///< towards the sun (normalised when used)
  SurfaceSettings surface;
};

class Renderer {
 public:
  Renderer(int width, int height);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  void resize(int width, int height);
  int width() const { return width_; }
  int height() const { return height_; }

  /// Renders the frame into the renderer's framebuffer.
  void render(const Frame& f, const Camera& c, const RenderSettings& s);
  /// The picture, RGBA, top row first.
  std::vector<unsigned char> readPixels() const;
  /// Writes the picture as an 8-bit RGB PNG (temporary file, then rename).
  void writePng(const std::string& path) const;
  /// Copies the picture to the default framebuffer (a window) of the given size.
  void blitTo(int width, int height) const;

  const WaterSurface& surface() const { return surface_; }
  WaterSurface& surface() { return surface_; }

 private:
  void uploadTerrain(const Frame& f);
  void drawTerrain(const Program& p, const Eigen::Matrix4f& clipFromWorld) const;
  void drawWater() const;
  void lightPass(const Frame& f, const RenderSettings& s, const Eigen::Matrix4f& lightClipFromWorld);
  void makeTargets();
  void makeLightTargets(int size);
  void makeSky();

  int width_, height_;
  WaterSurface surface_;
  /// The spray pass: the surface's particles outside it, as sprites.
  void drawSpray(const Frame& f, const Camera& c, const Eigen::Matrix4f& clipFromWorld,
                 float iso, bool keptSurface);
  /// Packs the frame's positions (w: `value(i)`, or 1) into particleBuffer_.
  template <class Value>
  void uploadParticles(const Frame& f, Value value);
  Program terrain_, water_, lightTerrain_, lightWater_, photon_, particles_, spray_;
  bool surfaceBuilt_ = false;  ///< with the settings below
  bool surfaceOld_ = false;   ///< the surface is of a frame before the one drawn last
  bool lightBuilt_ = false;    ///< the caustics maps are of the surface built last, in this sun
  Eigen::Vector3f litBy_ = Eigen::Vector3f::Zero();
  int litMap_ = 0;
  SurfaceSettings builtWith_;
  GLuint emptyVao_ = 0, waterVao_ = 0, particleVao_ = 0, particleBuffer_ = 0;
  size_t particleCap_ = 0;
  GLuint heights_ = 0, change_ = 0, map_ = 0, map2_ = 0;
  int terrainNx_ = 0, terrainNz_ = 0;
  float heightMin_ = 0, heightMax_ = 0, changeMax_ = 0, mapMax_ = 0;
  bool mapPair_ = false;
  // Background (terrain) and final pictures.
  GLuint backFbo_ = 0, backColour_ = 0, backDepth_ = 0, finalFbo_ = 0, finalColour_ = 0, finalDepth_ = 0;
  // Seen from the sun: receiver positions, water position + normal, photons.
  int lightSize_ = 0;
  GLuint receiverFbo_ = 0, receiver_ = 0, receiverDepth_ = 0;
  GLuint waterLightFbo_ = 0, waterPos_ = 0, waterNormal_ = 0, waterLightDepth_ = 0;
  GLuint causticFbo_ = 0, caustic_ = 0;
  GLuint sky_ = 0;
  Eigen::Matrix4f lightClipFromWorld_ = Eigen::Matrix4f::Identity();
};

/// Writes an RGBA picture, top row first, as an RGB PNG (all or nothing).
void writeRgbaPng(const std::string& path, int width, int height,
                  const std::vector<unsigned char>& rgba);
/// The window's back buffer (what the next swap shows: the picture and the panels), the rectangle
/// at (x, y) of width × height in window pixels from the top-left corner; top row first.
std::vector<unsigned char> readWindowPixels(int x, int y, int width, int height,
                                            int framebufferHeight);

}  // namespace scour
