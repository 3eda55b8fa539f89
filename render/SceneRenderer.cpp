#include "render/SceneRenderer.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <string>

#include "core/Errors.h"
#include "render/GlProgram.h"
#include "render/HeadlessGlContext.h"

namespace cdb {

namespace {

namespace uniform {
constexpr GLint kModel = 0;
constexpr GLint kView = 1;
constexpr GLint kProjection = 2;
constexpr GLint kColour = 3;
constexpr GLint kId = 4;
constexpr GLint kCue = 5;
}  // namespace uniform

constexpr const char* kVertex = R"(#version 450 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 0) uniform mat4 uModel;
layout(location = 1) uniform mat4 uView;
layout(location = 2) uniform mat4 uProjection;
out vec3 vViewPosition;
out vec3 vViewNormal;
void main() {
  vec4 view = uView * (uModel * vec4(aPosition, 1.0));
  vViewPosition = view.xyz;
  // Objects move rigidly, bars are scaled: the inverse transpose serves both.
  vViewNormal = mat3(uView) * (transpose(inverse(mat3(uModel))) * aNormal);
  gl_Position = uProjection * view;
}
)";

// Lambert from a light above and to the left of the camera plus a little specular, lit from
// whichever side faces the camera (the planes are one-sided meshes); then the depth cue darkens
// with distance, so that piles read as piles. Darkening keeps a colour's hue.
constexpr const char* kFragment = R"(#version 450 core
in vec3 vViewPosition;
in vec3 vViewNormal;
layout(location = 3) uniform vec3 uColour;
layout(location = 4) uniform uint uId;
layout(location = 5) uniform vec2 uCue;  // distances where the depth cue begins and ends
layout(location = 0) out vec4 oColour;
layout(location = 1) out uint oId;
void main() {
  vec3 n = normalize(vViewNormal);
  vec3 toEye = normalize(-vViewPosition);
  if (dot(n, toEye) < 0.0) n = -n;
  const vec3 light = normalize(vec3(-0.35, 0.65, 0.7));
  float diffuse = max(dot(n, light), 0.0);
  float specular = 0.15 * pow(max(dot(n, normalize(light + toEye)), 0.0), 40.0);
  float t = clamp((-vViewPosition.z - uCue.x) / (uCue.y - uCue.x), 0.0, 1.0);
  float cue = mix(1.0, 0.55, t);
  oColour = vec4(min((uColour * (0.3 + 0.7 * diffuse) + vec3(specular)) * cue, vec3(1.0)), 1.0);
  oId = uId;
}
)";

// A box [-1, 1]^3 with a normal per face (24 vertices), for segments.
void appendBar(std::vector<float>& vertices, std::vector<std::uint32_t>& indices) {
  const auto base = static_cast<std::uint32_t>(vertices.size() / 6);
  std::uint32_t v = 0;
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign = -1; sign <= 1; sign += 2) {
      Eigen::Vector3f n = Eigen::Vector3f::Zero();
      n[axis] = static_cast<float>(sign);
      const Eigen::Vector3f u = Eigen::Vector3f::Unit((axis + 1) % 3);
      const Eigen::Vector3f w = Eigen::Vector3f::Unit((axis + 2) % 3);
      for (const auto& [a, b] : {std::pair{-1.f, -1.f}, {1.f, -1.f}, {1.f, 1.f}, {-1.f, 1.f}}) {
        const Eigen::Vector3f p = n + a * u + b * w;
        vertices.insert(vertices.end(), {p.x(), p.y(), p.z(), n.x(), n.y(), n.z()});
      }
      indices.insert(indices.end(),
                     {base + v, base + v + 1, base + v + 2, base + v, base + v + 2, base + v + 3});
      v += 4;
    }
  }
}

// The matrix that maps the bar [-1, 1]^3 onto a segment of half width `half`.
Eigen::Matrix4f barMatrix(const Segment& s, double half) {
  const Eigen::Vector3d along = s.to - s.from;
  const double length = along.norm();
  const Eigen::Vector3d x = length > 0 ? Eigen::Vector3d(along / length) : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d helper =
      std::abs(x.y()) < 0.9 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d y = x.cross(helper).normalized();
  const Eigen::Vector3d z = x.cross(y);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<3, 1>(0, 0) = x * (length * 0.5 + half);
  m.block<3, 1>(0, 1) = y * half;
  m.block<3, 1>(0, 2) = z * half;
  m.block<3, 1>(0, 3) = (s.from + s.to) * 0.5;
  return m.cast<float>();
}

void setColour(GLuint program, Rgb c) {
  glProgramUniform3f(program, uniform::kColour, c.r / 255.f, c.g / 255.f, c.b / 255.f);
}

}  // namespace

SceneRenderer::SceneRenderer(HeadlessGlContext& context) : context_(&context) {
  context.makeCurrent();
  program_ =
      linkProgram("scene picture", {{GL_VERTEX_SHADER, kVertex}, {GL_FRAGMENT_SHADER, kFragment}});
  GLint renderbufferMax = 0, viewportMax[2] = {0, 0};
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbufferMax);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewportMax);
  maxSize_ = std::min({renderbufferMax, viewportMax[0], viewportMax[1]});
  GLuint name = 0;
  glCreateFramebuffers(1, &name);
  framebuffer_ = GlFramebuffer(name);
  const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(framebuffer_.get(), 2, buffers);
}

SceneRenderer::~SceneRenderer() {
  try {
    context_->makeCurrent();
  } catch (const RunError&) {
    // The context is gone or unusable: its objects went with it.
  }
}

void SceneRenderer::attach(const SceneGeometry& scene) {
  checkSceneIndices(scene);
  context_->makeCurrent();
  std::vector<float> vertexData;  // position, normal
  std::vector<std::uint32_t> indexData;
  meshes_.clear();
  for (const Mesh& mesh : scene.meshes) {
    std::vector<Eigen::Vector3f> normals(mesh.vertices.size(), Eigen::Vector3f::Zero());
    for (const Triangle& t : mesh.triangles) {
      // Area-weighted: the cross product's length is twice the area.
      const Eigen::Vector3f n = (mesh.vertices[t[1]] - mesh.vertices[t[0]])
                                    .cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
      for (std::uint32_t i : t) normals[i] += n;
    }
    MeshSlot slot;
    slot.firstIndex = static_cast<std::uint32_t>(indexData.size());
    slot.indexCount = static_cast<std::uint32_t>(3 * mesh.triangles.size());
    slot.baseVertex = static_cast<std::int32_t>(vertexData.size() / 6);
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
      const Eigen::Vector3f& p = mesh.vertices[v];
      const float length = normals[v].norm();
      const Eigen::Vector3f n =
          length > 0 ? Eigen::Vector3f(normals[v] / length) : Eigen::Vector3f::UnitY();
      vertexData.insert(vertexData.end(), {p.x(), p.y(), p.z(), n.x(), n.y(), n.z()});
    }
    for (const Triangle& t : mesh.triangles) indexData.insert(indexData.end(), t.begin(), t.end());
    meshes_.push_back(slot);
  }
  MeshSlot bar;
  bar.firstIndex = static_cast<std::uint32_t>(indexData.size());
  bar.baseVertex = 0;
  const std::size_t barBase = indexData.size();
  appendBar(vertexData, indexData);
  bar.indexCount = static_cast<std::uint32_t>(indexData.size() - barBase);
  meshes_.push_back(bar);
  if (vertexData.size() / 6 > 0x7fffffffu)
    throw RunError("the scene has too many vertices for 32-bit indices");

  objectMesh_.clear();
  for (const SceneObject& o : scene.objects) objectMesh_.push_back(o.mesh);

  vertices_ = immutableBuffer(std::span<const float>(vertexData));
  indices_ = immutableBuffer(std::span<const std::uint32_t>(indexData));
  GLuint name = 0;
  glCreateVertexArrays(1, &name);
  vao_ = GlVertexArray(name);
  glVertexArrayVertexBuffer(vao_.get(), 0, vertices_.get(), 0, 6 * sizeof(float));
  for (GLuint attribute = 0; attribute < 2; ++attribute) {
    glVertexArrayAttribFormat(vao_.get(), attribute, 3, GL_FLOAT, GL_FALSE,
                              3 * sizeof(float) * attribute);
    glVertexArrayAttribBinding(vao_.get(), attribute, 0);
    glEnableVertexArrayAttrib(vao_.get(), attribute);
  }
  glVertexArrayElementBuffer(vao_.get(), indices_.get());
}

void SceneRenderer::ensureTarget(int width, int height) {
  if (width == targetWidth_ && height == targetHeight_) return;
  const auto make = [&](GLenum format, GLenum attachment) {
    GLuint name = 0;
    glCreateRenderbuffers(1, &name);
    GlRenderbuffer buffer(name);
    glNamedRenderbufferStorage(buffer.get(), format, width, height);
    glNamedFramebufferRenderbuffer(framebuffer_.get(), attachment, GL_RENDERBUFFER, buffer.get());
    return buffer;
  };
  colour_ = make(GL_RGBA8, GL_COLOR_ATTACHMENT0);
  ids_ = make(GL_R32UI, GL_COLOR_ATTACHMENT1);
  depth_ = make(GL_DEPTH_COMPONENT24, GL_DEPTH_ATTACHMENT);
  const GLenum status = glCheckNamedFramebufferStatus(framebuffer_.get(), GL_DRAW_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", status);
    throw RunError("the picture framebuffer of " + std::to_string(width) + "x" +
                   std::to_string(height) + " is incomplete (status " + code + ")");
  }
  targetWidth_ = width;
  targetHeight_ = height;
}

RenderedScene SceneRenderer::render(const Camera& camera, const SceneDrawing& drawing, int width,
                                    int height) {
  if (!vao_) throw RunError("a picture was drawn before a scene was attached");
  if (width < 1 || height < 1 || width > maxSize_ || height > maxSize_)
    throw RunError("a picture of " + std::to_string(width) + "x" + std::to_string(height) +
                   " is outside the GL's 1.." + std::to_string(maxSize_) + " pixels a side");
  if (drawing.poses.size() != objectMesh_.size() || drawing.colours.size() != objectMesh_.size())
    throw RunError("got " + std::to_string(drawing.poses.size()) + " poses and " +
                   std::to_string(drawing.colours.size()) + " colours for a scene of " +
                   std::to_string(objectMesh_.size()) + " objects");
  context_->makeCurrent();
  while (glGetError() != GL_NO_ERROR) {
    // Errors of earlier work on the shared context are not this picture's.
  }
  ensureTarget(width, height);

  // Every piece of state this draw relies on: the visibility pipelines share the context.
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_.get());
  glViewport(0, 0, width, height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDepthRange(0.0, 1.0);
  glDisable(GL_DEPTH_CLAMP);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  const GLfloat black[] = {0.f, 0.f, 0.f, 1.f};
  const GLuint nothing[] = {RenderedScene::kNothing, 0, 0, 0};
  const GLfloat farthest = 1.f;
  glClearBufferfv(GL_COLOR, 0, black);
  glClearBufferuiv(GL_COLOR, 1, nothing);
  glClearBufferfv(GL_DEPTH, 0, &farthest);

  const GLuint program = program_.get();
  glUseProgram(program);
  glBindVertexArray(vao_.get());
  const Eigen::Matrix4f view = camera.view().cast<float>();
  const Eigen::Matrix4f projection = camera.projection().cast<float>();
  glProgramUniformMatrix4fv(program, uniform::kView, 1, GL_FALSE, view.data());
  glProgramUniformMatrix4fv(program, uniform::kProjection, 1, GL_FALSE, projection.data());
  glProgramUniform2f(program, uniform::kCue, static_cast<float>(camera.cueNear),
                     static_cast<float>(camera.cueFar));
  const auto draw = [](const MeshSlot& slot) {
    glDrawElementsBaseVertex(
        GL_TRIANGLES, static_cast<GLsizei>(slot.indexCount), GL_UNSIGNED_INT,
        reinterpret_cast<const void*>(std::uintptr_t{slot.firstIndex} * sizeof(std::uint32_t)),
        slot.baseVertex);
  };
  for (std::size_t o = 0; o < objectMesh_.size(); ++o) {
    const Eigen::Matrix4f model = drawing.poses[o].matrix().cast<float>();
    glProgramUniformMatrix4fv(program, uniform::kModel, 1, GL_FALSE, model.data());
    setColour(program, drawing.colours[o]);
    glProgramUniform1ui(program, uniform::kId, static_cast<GLuint>(o + 1));
    draw(meshes_[objectMesh_[o]]);
  }
  setColour(program, drawing.segmentColour);
  glProgramUniform1ui(program, uniform::kId, RenderedScene::kSegment);
  for (const Segment& s : drawing.segments) {
    const Eigen::Matrix4f model = barMatrix(s, drawing.segmentWidth * 0.5);
    glProgramUniformMatrix4fv(program, uniform::kModel, 1, GL_FALSE, model.data());
    draw(meshes_.back());
  }

  RenderedScene out;
  out.colour = RgbImage(width, height);
  out.ids.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  std::vector<std::uint8_t> rgba(out.ids.size() * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glNamedFramebufferReadBuffer(framebuffer_.get(), GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.get());
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  std::vector<std::uint32_t> ids(out.ids.size());
  glNamedFramebufferReadBuffer(framebuffer_.get(), GL_COLOR_ATTACHMENT1);
  glReadPixels(0, 0, width, height, GL_RED_INTEGER, GL_UNSIGNED_INT, ids.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glBindVertexArray(0);
  if (const GLenum error = glGetError(); error != GL_NO_ERROR) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", error);
    throw RunError(std::string("drawing the picture failed (GL error ") + code + ")");
  }
  // GL's rows run from the bottom.
  for (int y = 0; y < height; ++y) {
    const std::size_t from =
        static_cast<std::size_t>(height - 1 - y) * static_cast<std::size_t>(width);
    const std::size_t to = static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
    for (int x = 0; x < width; ++x) {
      const std::uint8_t* p = &rgba[(from + static_cast<std::size_t>(x)) * 4];
      out.colour.set(x, y, {p[0], p[1], p[2]});
      out.ids[to + static_cast<std::size_t>(x)] = ids[from + static_cast<std::size_t>(x)];
    }
  }
  return out;
}

}  // namespace cdb
