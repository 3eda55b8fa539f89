#pragma once
// The programs the occlusion-query backend draws with: plain rasterisation (the thesis' raw mode)
// and conservative rasterisation (Hasselgren, Akenine-Moller and Ohlsson, "Conservative
// Rasterization", GPU Gems 2, ch. 42) with conservative depth. Their GLSL is also the head of the
// flag backend's programs (FlagShaders), so that both rasterise with one copy of the arithmetic.
#include <string>

#include "render/GlHandle.h"

namespace cdb {

// Uniform locations shared by both programs' sources (explicit, so no look-ups are needed).
namespace occlusion_uniform {
inline constexpr GLint kObject = 0;   // int: index into the model-matrix buffer
inline constexpr GLint kLocal = 1;    // mat4: local frame of the drawn piece (a box) or identity
inline constexpr GLint kWorldTo = 2;  // mat4: world -> clip (raw) or world -> screen (conservative)
inline constexpr GLint kNdcOffset = 3;  // float, raw: NDC depth offset of the draw
inline constexpr GLint kSide = 4;  // float, conservative: +1 test (farthest), -1 write (nearest)
inline constexpr GLint kDepthEpsilon = 5;  // float, conservative: depth epsilon in view-depth units
inline constexpr GLint kGrowPx = 6;        // float, conservative: half pixel plus margin
inline constexpr GLint kResolution = 7;    // float, conservative: pixels across the buffer
}  // namespace occlusion_uniform

// Shader storage binding points.
inline constexpr GLuint kModelMatrixBinding = 0;  // mat4 per object
inline constexpr GLuint kPositionBinding = 1;     // the shared vertex buffer, 3 floats per vertex
inline constexpr GLuint kIndexBinding = 2;        // the shared index buffer, 3 per triangle

// The conservative program draws triangle i as vertices [3 i, 3 i + 3) of glDrawArrays.
inline constexpr int kConservativeVerticesPerTriangle = 3;

// A vertex shader's start: the version line, the uniforms above, pulledVertex(triangle, corner)
// (a corner of a triangle of the shared buffers) and, raw, rawClipPosition(local, position) (of
// the object uObject; rawClipPositionOf(object, local, position) of another) or, conservative,
// conservativeCorner(toScreen, triangle, corner) (a corner of the region drawn for a triangle, with
// its outputs). A main() of the caller's follows.
[[nodiscard]] std::string occlusionVertexHead(bool conservative);
// A fragment shader's start: the version line and, conservative, coversPixel(gl_FragCoord.xy) on
// the vertex shader's outputs.
[[nodiscard]] std::string occlusionFragmentHead(bool conservative);
// The whole fragment shader of writes (and of tests counted by occlusion queries): conservative,
// what coversPixel rejects is discarded.
[[nodiscard]] std::string occlusionWriteFragmentShader(bool conservative);

[[nodiscard]] GlProgramName makeRawOcclusionProgram();
[[nodiscard]] GlProgramName makeConservativeOcclusionProgram();

}  // namespace cdb
