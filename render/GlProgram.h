#pragma once
// Compiling and linking GLSL programs; a compile or link failure is a RunError carrying the log.
#include <initializer_list>
#include <string_view>

#include "render/GlHandle.h"

namespace cdb {

struct ShaderStage {
  GLenum type = 0;  // GL_VERTEX_SHADER, GL_GEOMETRY_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER
  std::string_view source;
};

// `label` names the program in error messages.
[[nodiscard]] GlProgramName linkProgram(std::string_view label,
                                        std::initializer_list<ShaderStage> stages);

}  // namespace cdb
