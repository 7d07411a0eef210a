#pragma once
// The GLSL sources of shaders/, built into the binary. Each file is the body of a shader; the
// "#version 450 core" line is added by the program builder.
#include <string>

namespace scour {

/// The source of shaders/<name>.glsl; throws std::invalid_argument for an unknown name.
const char* shaderSource(const std::string& name);

}  // namespace scour
