#include "culling/visibility/FlagShaders.h"

#include <string>

#include "culling/visibility/OcclusionShaders.h"
#include "render/GlProgram.h"

namespace cdb {

namespace {

// What a batch draw draws: triangle, local frame and item of each vertex invocation.
constexpr const char* kBatchVertex = R"(
layout(std430, binding = 3) readonly buffer ListedTriangles { uint uListedTriangles[]; };
layout(std430, binding = 4) readonly buffer BoxMatrices { mat4 uBoxes[]; };
layout(location = 8) uniform int uListed;
layout(location = 9) uniform int uBoxBase;
layout(location = 10) uniform int uItemBase;
layout(location = 11) uniform int uItemPerTriangle;
flat out int vItem;
int batchTriangle(int k) { return uListed != 0 ? int(uListedTriangles[k]) : k; }
mat4 batchLocal() { return uBoxBase < 0 ? uLocal : uBoxes[uBoxBase + gl_InstanceID]; }
int batchItem(int k) { return uItemBase + uItemPerTriangle * k + gl_InstanceID; }
)";

// The same arithmetic as the occlusion programs' mains, on the batch's triangle and frame.
constexpr const char* kRawMain = R"(
void main() {
  int k = gl_VertexID / 3;
  vItem = batchItem(k);
  gl_Position = rawClipPosition(batchLocal(), pulledVertex(batchTriangle(k), gl_VertexID - 3 * k));
}
)";

constexpr const char* kConservativeMain = R"(
void main() {
  int k = gl_VertexID / 3;
  vItem = batchItem(k);
  conservativeCorner(uWorldToScreen * uModels[uObject] * batchLocal(), batchTriangle(k),
                     gl_VertexID - 3 * k);
}
)";

// Only fragments that passed the depth test (at or behind what is stored) are shaded. A plain
// store: every writer stores the same 1.
constexpr const char* kTestFragment = R"(
layout(early_fragment_tests) in;
flat in int vItem;
layout(std430, binding = 5) writeonly buffer ItemFlags { uint uFlags[]; };
)";

constexpr const char* kRawTestMain = R"(
void main() { uFlags[vItem] = 1u; }
)";

constexpr const char* kConservativeTestMain = R"(
void main() {
  if (coversPixel(gl_FragCoord.xy)) uFlags[vItem] = 1u;
}
)";

// The order-independent pass' vertex shader: segment, triangle, frame and item of each vertex
// (kSegment and place() come before it).
constexpr const char* kPassVertex = R"(
layout(std430, binding = 3) readonly buffer ListedTriangles { uint uListedTriangles[]; };
layout(std430, binding = 4) readonly buffer BoxMatrices { mat4 uBoxes[]; };
layout(std430, binding = 6) readonly buffer PassSegments { uvec4 uSegments[]; };
layout(location = 8) uniform int uSegmentBase;
layout(location = 9) uniform int uListedBase;
layout(location = 10) uniform int uBoxBase;
flat out int vItem;
flat out uint vObject;
void main() {
  int k = gl_VertexID / 3;
  uvec4 segment = uSegments[uSegmentBase + k / kSegment];
  int j = k % kSegment;
  int triangle = (segment.w & 2u) != 0u
                     ? int(uListedTriangles[uListedBase + int(segment.x) + j])
                     : int(segment.x) + j;
  vItem = int(segment.z) + ((segment.w & 1u) != 0u ? j : 0);
  vObject = segment.y;
  uint box = segment.w >> 2;
  place(int(segment.y), box == 0u ? mat4(1.0) : uBoxes[uBoxBase + int(box) - 1], triangle,
        gl_VertexID - 3 * k);
}
)";

// The same arithmetic as the other programs' mains.
constexpr const char* kPassRawPlace = R"(
void place(int object, mat4 local, int triangle, int corner) {
  gl_Position = rawClipPositionOf(object, local, pulledVertex(triangle, corner));
}
)";
constexpr const char* kPassConservativePlace = R"(
void place(int object, mat4 local, int triangle, int corner) {
  conservativeCorner(uWorldToScreen * uModels[object] * local, triangle, corner);
}
)";

// Whether a fragment is the piece's: conservative, inside its coverage; raw, every fragment.
constexpr const char* kPassRawCovers = "bool covers() { return true; }\n";
constexpr const char* kPassConservativeCovers =
    "bool covers() { return coversPixel(gl_FragCoord.xy); }\n";

constexpr const char* kPassNearestFragment = R"(
flat in uint vObject;
layout(location = 0) out uint oObject;
void main() {
  if (!covers()) discard;
  oObject = vObject;
}
)";

constexpr const char* kPassOthersFragment = R"(
flat in uint vObject;
layout(binding = 0) uniform usampler2D uNearestObject;
void main() {
  if (!covers()) discard;
  if (texelFetch(uNearestObject, ivec2(gl_FragCoord.xy), 0).r == vObject) discard;
}
)";

// The test draw's depth test is a Fresh pass' (early, GEQUAL: at or behind = occluded) against
// d1, so only fragments at or behind d1 are shaded. Such a fragment is occluded unless the nearest
// depth there is its own object's, in which case it is compared with d2 (d2 >= d1: a fragment in
// front of d1 is in front of both), on its depth clamped into the range as depth clamping does.
constexpr const char* kPassTestFragment = R"(
layout(early_fragment_tests) in;
flat in int vItem;
flat in uint vObject;
layout(binding = 0) uniform usampler2D uNearestObject;
layout(binding = 2) uniform sampler2D uOthersDepth;
layout(std430, binding = 5) writeonly buffer ItemFlags { uint uFlags[]; };
void main() {
  if (!covers()) return;
  ivec2 p = ivec2(gl_FragCoord.xy);
  if (texelFetch(uNearestObject, p, 0).r != vObject ||
      clamp(gl_FragCoord.z, 0.0, 1.0) >= texelFetch(uOthersDepth, p, 0).r)
    uFlags[vItem] = 1u;
}
)";

std::string vertexShader(bool conservative) {
  return occlusionVertexHead(conservative) + kBatchVertex +
         (conservative ? kConservativeMain : kRawMain);
}

}  // namespace

GlProgramName makeFlagTestProgram(bool conservative) {
  const std::string vertex = vertexShader(conservative);
  const std::string fragment = occlusionFragmentHead(conservative) + kTestFragment +
                               (conservative ? kConservativeTestMain : kRawTestMain);
  return linkProgram(conservative ? "conservative flag test" : "raw flag test",
                     {{GL_VERTEX_SHADER, vertex}, {GL_FRAGMENT_SHADER, fragment}});
}

GlProgramName makeFlagWriteProgram(bool conservative) {
  const std::string vertex = vertexShader(conservative);
  const std::string fragment = occlusionWriteFragmentShader(conservative);
  return linkProgram(conservative ? "conservative flag write" : "raw flag write",
                     {{GL_VERTEX_SHADER, vertex}, {GL_FRAGMENT_SHADER, fragment}});
}

GlProgramName makePassProgram(PassStage stage, bool conservative) {
  const std::string vertex = occlusionVertexHead(conservative) + "const int kSegment = " +
                             std::to_string(kPassSegmentTriangles) + ";\n" +
                             (conservative ? kPassConservativePlace : kPassRawPlace) + kPassVertex;
  const char* main = stage == PassStage::Nearest  ? kPassNearestFragment
                     : stage == PassStage::Others ? kPassOthersFragment
                                                  : kPassTestFragment;
  const std::string fragment = occlusionFragmentHead(conservative) +
                               (conservative ? kPassConservativeCovers : kPassRawCovers) + main;
  const char* names[2][3] = {{"raw pass nearest", "raw pass others", "raw pass test"},
                             {"conservative pass nearest", "conservative pass others",
                              "conservative pass test"}};
  return linkProgram(names[conservative ? 1 : 0][static_cast<int>(stage)],
                     {{GL_VERTEX_SHADER, vertex}, {GL_FRAGMENT_SHADER, fragment}});
}

}  // namespace cdb
