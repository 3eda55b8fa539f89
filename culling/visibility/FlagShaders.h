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
#include <cstdint>

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

// The order-independent pass (DepthUse::OrderIndependent): every write of the pass in two draws,
// then every test in one, each a multi-draw over a table of segments of one object's pieces.
//
// A segment is up to kPassSegmentTriangles triangles of one object: triangle k of a draw is
// triangle j = k % kPassSegmentTriangles of segment uSegmentBase + k / kPassSegmentTriangles, so
// segment s is drawn at vertex 3 kPassSegmentTriangles s (the segments of a multi-draw, as
// GlVisibilityPipeline::drawNumbered splits a large draw for llvmpipe). Its uvec4:
//   x: its first triangle's global index, or (listed) its first entry of the listed triangles
//      from uListedBase;
//   y: its object (the model matrix, and the id the pass keeps per pixel);
//   z: its item (tests), plus j when items are per triangle;
//   w: bit 0 items per triangle, bit 1 listed, bits 2..31 a box + 1 (the local frame
//      boxes[uBoxBase + box] of the cube's triangles), 0 for none.
//
// Draw 1 (nearest): depth test LESS with writes into the nearest depth d1, and the object into an
// R32UI colour attachment (id1). Draw 2 (others): the same into a second depth buffer d2, the
// fragments of the object id1 at their pixel discarded. Tests: a fragment of object i sets its
// item's flag where its depth is not in front of (id1 == i ? d2 : d1); d1 is compared by the depth
// test of a Fresh pass' tests (early, GEQUAL, no writes), d2 by the fragment shader, which only
// fragments at or behind d1 reach. Rasterisation, conservative coverage and depths are the other
// programs' (OcclusionShaders).
inline constexpr int kPassSegmentTriangles = 32;
namespace pass_uniform {
inline constexpr GLint kSegmentBase = 8;  // int
inline constexpr GLint kListedBase = 9;   // int
inline constexpr GLint kBoxBase = 10;     // int
}  // namespace pass_uniform
inline constexpr GLuint kPassSegmentBinding = 6;  // uvec4 per segment
// Texture units the pass' buffers are read from.
inline constexpr GLuint kNearestObjectUnit = 0;  // R32UI: id1
inline constexpr GLuint kOthersDepthUnit = 2;    // d2
inline constexpr std::uint32_t kPassPerTriangleBit = 1;
inline constexpr std::uint32_t kPassListedBit = 2;
inline constexpr std::uint32_t kPassBoxShift = 2;

enum class PassStage : std::uint8_t { Nearest, Others, Test };
[[nodiscard]] GlProgramName makePassProgram(PassStage stage, bool conservative);

}  // namespace cdb
