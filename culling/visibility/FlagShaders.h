#pragma once
// The programs the flag backend (GlFlagBackend) draws with: the occlusion programs' rasterisation
// (OcclusionShaders), with a batch of pieces in one draw, and tests that answer through a flag per
// piece in a storage buffer instead of an occlusion query.
//
// A draw numbers its triangles k = gl_VertexID / 3 (glDrawArrays' `first` included) and draws
// triangle k of the shared buffers, or with a list the triangle listed at k. Its pieces are items
// itemBase + itemPerTriangle * k + gl_InstanceID: one item per triangle, one per instance (boxes,
// an instanced cube, each instance's local matrix from the box buffer), or a single item. A test
// runs the depth test before its fragment shader (early fragment tests; depth writes off), so a
// fragment shaded by it lies at or behind the stored depth: the piece is not fully visible, and
// the shader sets its item's flag. Writes keep the late depth test, as what the conservative
// fragment shader discards must not be stored.
#include "render/GlHandle.h"

namespace cdb {

// Uniform locations beyond occlusion_uniform's, shared by the four programs.
namespace flag_uniform {
inline constexpr GLint kListed = 8;           // int: 1 = triangle k is listedTriangles[k]
inline constexpr GLint kBoxBase = 9;          // int: < 0 uLocal, else boxes[kBoxBase + instance]
inline constexpr GLint kItemBase = 10;        // int
inline constexpr GLint kItemPerTriangle = 11;  // int: 0 or 1
}  // namespace flag_uniform

// Shader storage binding points beyond the scene's (OcclusionShaders.h).
inline constexpr GLuint kListedTriangleBinding = 3;  // uint per listed triangle (global index)
inline constexpr GLuint kBoxMatrixBinding = 4;       // mat4 per box of a batch
inline constexpr GLuint kItemFlagBinding = 5;        // uint per item: 1 = not fully visible

// Tests (early fragment tests, set the flag) or writes, raw or conservative. Both modes pull
// triangles from the storage buffers, three vertices per triangle.
[[nodiscard]] GlProgramName makeFlagTestProgram(bool conservative);
[[nodiscard]] GlProgramName makeFlagWriteProgram(bool conservative);

}  // namespace cdb
