// The shader files' bytes, included at assembly time (.incbin) straight from shaders/ with a
// terminating zero, so nothing is generated and the files stay the one copy.
#include "render/shaders.h"

#include <stdexcept>
#include <utility>

#define SCOUR_STR2(x) #x
#define SCOUR_STR(x) SCOUR_STR2(x)
#define SCOUR_SHADER(name)                                                              \
  asm(".section .rodata\n"                                                              \
      "scour_shader_" #name ":\n"                                                       \
      ".incbin \"" SCOUR_STR(SCOUR_SHADER_DIR) "/" #name ".glsl\"\n"                    \
      ".byte 0\n"                                                                       \
      ".previous\n");                                                                   \
  extern "C" const char scour_shader_##name[];

SCOUR_SHADER(splat)
SCOUR_SHADER(compact)
SCOUR_SHADER(finish)
SCOUR_SHADER(march)
SCOUR_SHADER(terrain_vs)
SCOUR_SHADER(terrain_fs)
SCOUR_SHADER(water_vs)
SCOUR_SHADER(water_fs)
SCOUR_SHADER(light_terrain_fs)
SCOUR_SHADER(light_water_fs)
SCOUR_SHADER(photon_vs)
SCOUR_SHADER(photon_fs)
SCOUR_SHADER(particles_vs)
SCOUR_SHADER(particles_fs)
SCOUR_SHADER(spray_vs)
SCOUR_SHADER(spray_fs)

namespace scour {

const char* shaderSource(const std::string& name) {
  static const std::pair<const char*, const char*> table[] = {
      {"splat", scour_shader_splat},
      {"compact", scour_shader_compact},
      {"finish", scour_shader_finish},
      {"march", scour_shader_march},
      {"terrain_vs", scour_shader_terrain_vs},
      {"terrain_fs", scour_shader_terrain_fs},
      {"water_vs", scour_shader_water_vs},
      {"water_fs", scour_shader_water_fs},
      {"light_terrain_fs", scour_shader_light_terrain_fs},
      {"light_water_fs", scour_shader_light_water_fs},
      {"photon_vs", scour_shader_photon_vs},
      {"photon_fs", scour_shader_photon_fs},
      {"particles_vs", scour_shader_particles_vs},
      {"particles_fs", scour_shader_particles_fs},
      {"spray_vs", scour_shader_spray_vs},
      {"spray_fs", scour_shader_spray_fs},
  };
  for (const auto& [n, src] : table)
    if (name == n) return src;
  throw std::invalid_argument("unknown shader '" + name + "'");
}

}  // namespace scour
