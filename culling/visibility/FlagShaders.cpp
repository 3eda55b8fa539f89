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

}  // namespace cdb
