#include "render/GlProgram.h"

#include <string>
#include <vector>

#include "core/Errors.h"

namespace cdb {

namespace {

std::string oneLine(std::string log) {
  for (char& c : log)
    if (c == '\n' || c == '\r') c = ' ';
  while (!log.empty() && log.back() == ' ') log.pop_back();
  return log;
}

std::string_view stageName(GLenum type) {
  switch (type) {
    case GL_VERTEX_SHADER:
      return "vertex";
    case GL_GEOMETRY_SHADER:
      return "geometry";
    case GL_FRAGMENT_SHADER:
      return "fragment";
    case GL_COMPUTE_SHADER:
      return "compute";
    default:
      return "shader";
  }
}

}  // namespace

GlProgramName linkProgram(std::string_view label, std::initializer_list<ShaderStage> stages) {
  GlProgramName program(glCreateProgram());
  std::vector<GlShaderName> shaders;
  for (const ShaderStage& stage : stages) {
    GlShaderName shader(glCreateShader(stage.type));
    const GLchar* text = stage.source.data();
    const auto length = static_cast<GLint>(stage.source.size());
    glShaderSource(shader.get(), 1, &text, &length);
    glCompileShader(shader.get());
    GLint ok = GL_FALSE;
    glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
      GLint size = 0;
      glGetShaderiv(shader.get(), GL_INFO_LOG_LENGTH, &size);
      std::string log(static_cast<std::size_t>(size > 0 ? size : 1), '\0');
      glGetShaderInfoLog(shader.get(), size, nullptr, log.data());
      throw RunError("the " + std::string(stageName(stage.type)) + " shader of '" +
                     std::string(label) + "' does not compile: " + oneLine(log.c_str()));
    }
    glAttachShader(program.get(), shader.get());
    shaders.push_back(std::move(shader));
  }
  glLinkProgram(program.get());
  GLint ok = GL_FALSE;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  for (const GlShaderName& s : shaders) glDetachShader(program.get(), s.get());
  if (ok != GL_TRUE) {
    GLint size = 0;
    glGetProgramiv(program.get(), GL_INFO_LOG_LENGTH, &size);
    std::string log(static_cast<std::size_t>(size > 0 ? size : 1), '\0');
    glGetProgramInfoLog(program.get(), size, nullptr, log.data());
    throw RunError("the program '" + std::string(label) +
                   "' does not link: " + oneLine(log.c_str()));
  }
  return program;
}

}  // namespace cdb
