// The shader files' bytes, included at assembly time (.incbin) straight from shaders/ with a
// terminating zero, so nothing is generated and the files stay the one copy.
#include "render/shaders.h"

#include <stdexcept>

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
SCOUR_SHADER(march)
SCOUR_SHADER(finish)

namespace scour {

const char* shaderSource(const std::string& name) {
  if (name == "splat") return scour_shader_splat;
  if (name == "compact") return scour_shader_compact;
  if (name == "march") return scour_shader_march;
  if (name == "finish") return scour_shader_finish;
  throw std::invalid_argument("unknown shader '" + name + "'");
}

}  // namespace scour
