#include "culling/visibility/OcclusionShaders.h"

#include <string>

#include "render/GlProgram.h"

namespace cdb {

namespace {

constexpr const char* kVersion = "#version 450 core\n";

// Every vertex shader: the per-frame model matrices, the drawn object and the local frame of the
// drawn piece (a box) or identity.
constexpr const char* kCommonVertex = R"(
layout(std430, binding = 0) readonly buffer ModelMatrices { mat4 uModels[]; };
layout(location = 0) uniform int uObject;
layout(location = 1) uniform mat4 uLocal;
)";

// Triangles pulled from the shared buffers instead of a vertex array.
constexpr const char* kPulledVertex = R"(
layout(std430, binding = 1) readonly buffer Positions { float uPositions[]; };
layout(std430, binding = 2) readonly buffer Indices { uint uIndices[]; };
vec3 pulledVertex(int triangle, int corner) {
  uint v = 3u * uIndices[3 * triangle + corner];
  return vec3(uPositions[v], uPositions[v + 1u], uPositions[v + 2u]);
}
)";

// Local (or box) -> object pose from the per-frame matrix buffer -> the pass' view.
constexpr const char* kRawVertex = R"(
layout(location = 2) uniform mat4 uWorldToClip;
layout(location = 3) uniform float uNdcOffset;
vec4 rawClipPositionOf(int object, mat4 local, vec3 position) {
  vec4 clip = uWorldToClip * (uModels[object] * (local * vec4(position, 1.0)));
  // Tests are pushed away from the viewer by the thesis' small offset (NDC z grows along the view
  // in both depth orders; glDepthRange does the reversing).
  return vec4(clip.xy, clip.z + uNdcOffset, 1.0);
}
vec4 rawClipPosition(mat4 local, vec3 position) { return rawClipPositionOf(uObject, local, position); }
)";

constexpr const char* kRawQueryMain = R"(
layout(location = 0) in vec3 aPosition;
void main() { gl_Position = rawClipPosition(uLocal, aPosition); }
)";

// Conservative rasterisation without a geometry shader (slow on llvmpipe): each triangle is drawn
// as three vertices, and every one of them pulls the whole triangle from the storage buffers.
//
// Coverage: the triangle dilated by a pixel square grown by the margin g (the Minkowski sum) holds
// the centre of every pixel the triangle touches. It is the triangle's bounding box grown by g
// intersected with three slabs, one per edge: the triangle's extent along the edge normal grown by
// the square's support g (|nx| + |ny|). Slabs need no orientation, so edge-on and degenerate
// triangles are handled alike. The vertices span a region containing it (the triangle with its
// edges pushed out, or for slivers, whose pushed-out triangle is huge, a triangle holding the box)
// and the fragment shader keeps only what lies inside it.
//
// Depth: orthographic depth t is linear in screen space, so over a grown pixel square it stays
// within g (|dt/dx| + |dt/dy|) of its value at the centre. A test draws the plane moved back by
// that much, a write the plane moved forward, or the triangle's farthest (test) or nearest (write)
// vertex depth where that is tighter on average (steep and degenerate triangles); then a depth
// epsilon toward "occluded". Either is a valid bound of the triangle's depth anywhere in the pixel,
// and being linear it is interpolated by the rasteriser: no gl_FragDepth, so early depth tests
// stay on.
constexpr const char* kConservativeVertex = R"(
layout(location = 2) uniform mat4 uWorldToScreen;
layout(location = 4) uniform float uSide;          // +1 test (farthest), -1 write (nearest)
layout(location = 5) uniform float uDepthEpsilon;  // in units of t
layout(location = 6) uniform float uGrow;
layout(location = 7) uniform float uResolution;
flat out vec4 vBox;      // grown bounding box: min x, min y, max x, max y
flat out vec4 vSlab[3];  // unit edge normal, allowed range of dot(normal, pixel centre)

vec2 meet(vec3 a, vec3 b) {  // intersection of the lines dot(a.xy, x) = a.z and dot(b.xy, x) = b.z
  float det = a.x * b.y - a.y * b.x;
  return vec2(a.z * b.y - a.y * b.z, a.x * b.z - a.z * b.x) / det;
}

// Corner `corner` (0, 1, 2) of the region drawn for `triangle` of the shared buffers.
void conservativeCorner(mat4 toScreen, int triangle, int corner) {
  vec2 p[3];
  vec3 t;
  for (int i = 0; i < 3; ++i) {
    vec3 s = (toScreen * vec4(pulledVertex(triangle, i), 1.0)).xyz;
    p[i] = s.xy;
    t[i] = s.z;
  }
  vec2 lo = min(min(p[0], p[1]), p[2]) - uGrow;
  vec2 hi = max(max(p[0], p[1]), p[2]) + uGrow;
  vBox = vec4(lo, hi);

  vec3 outward[3];  // pushed-out edge lines dot(n, x) = d, n pointing away from the triangle
  bool pushable = true;
  for (int i = 0; i < 3; ++i) {
    vec2 e = p[(i + 1) % 3] - p[i];
    float len = length(e);
    if (len < 1e-6) {  // a point-like edge: the other edges and the box bound it
      vSlab[i] = vec4(1.0, 0.0, -1e30, 1e30);
      pushable = false;
      continue;
    }
    vec2 n = vec2(e.y, -e.x) / len;
    float off = uGrow * (abs(n.x) + abs(n.y));
    float base = dot(n, p[i]);
    float side = dot(n, p[(i + 2) % 3]) - base;  // where the opposite vertex lies
    vSlab[i] = vec4(n, base + min(side, 0.0) - off, base + max(side, 0.0) + off);
    outward[i] = side < 0.0 ? vec3(n, base + off) : vec3(-n, -base + off);
    pushable = pushable && abs(side) > 1e-3;
  }

  // The pushed-out triangle when it is not much larger than the box, else one holding the box.
  vec2 size = hi - lo;
  vec2 q;
  bool pushed = false;
  if (pushable) {
    vec2 c0 = meet(outward[2], outward[0]);
    vec2 c1 = meet(outward[0], outward[1]);
    vec2 c2 = meet(outward[1], outward[2]);
    vec2 f1 = c1 - c0;
    vec2 f2 = c2 - c0;
    float area = 0.5 * abs(f1.x * f2.y - f1.y * f2.x);
    vec2 chosen = corner == 0 ? c0 : (corner == 1 ? c1 : c2);
    pushed = area < 2.0 * size.x * size.y && !isnan(area) && !isinf(area);
    q = chosen;
  }
  if (!pushed) {
    vec2 legs = 2.0 * size + 1.0;  // the box's far corner is then well inside
    q = corner == 0 ? lo : (corner == 1 ? vec2(lo.x + legs.x, lo.y) : vec2(lo.x, lo.y + legs.y));
  }

  float tmin = min(min(t.x, t.y), t.z);
  float tmax = max(max(t.x, t.y), t.z);
  float tBound = uSide > 0.0 ? tmax : tmin;
  float tq = tBound;
  vec2 e1 = p[1] - p[0];
  vec2 e2 = p[2] - p[0];
  float det = e1.x * e2.y - e1.y * e2.x;
  if (abs(det) > 1e-6 * (dot(e1, e1) + dot(e2, e2))) {
    float dt1 = t.y - t.x;
    float dt2 = t.z - t.x;
    float a = (dt1 * e2.y - dt2 * e1.y) / det;
    float b = (dt2 * e1.x - dt1 * e2.x) / det;
    float shift = uSide * uGrow * (abs(a) + abs(b));
    float meanMoved = (t.x + t.y + t.z) / 3.0 + shift;
    if (!isinf(shift) && !isnan(shift) && uSide * (tBound - meanMoved) > 0.0) {
      vec2 dq = q - p[0];
      tq = t.x + a * dq.x + b * dq.y + shift;
    }
  }
  tq += uSide * uDepthEpsilon;
  // NDC z = 2 t - 1; depth clamping keeps the result inside the pass' part of the depth range.
  gl_Position = vec4(q / uResolution * 2.0 - 1.0, 2.0 * tq - 1.0, 1.0);
}
)";

constexpr const char* kConservativeQueryMain = R"(
void main() {
  int triangle = gl_VertexID / 3;
  conservativeCorner(uWorldToScreen * uModels[uObject] * uLocal, triangle,
                     gl_VertexID - 3 * triangle);
}
)";

constexpr const char* kCoverage = R"(
flat in vec4 vBox;
flat in vec4 vSlab[3];
bool coversPixel(vec2 x) {
  bool inside = all(greaterThanEqual(x, vBox.xy)) && all(lessThanEqual(x, vBox.zw));
  for (int i = 0; i < 3; ++i) {
    float s = dot(vSlab[i].xy, x);
    inside = inside && s >= vSlab[i].z && s <= vSlab[i].w;
  }
  return inside;
}
)";

constexpr const char* kEmptyFragmentMain = R"(
void main() {}
)";

constexpr const char* kCoverageFragmentMain = R"(
void main() {
  if (!coversPixel(gl_FragCoord.xy)) discard;
}
)";

}  // namespace

std::string occlusionVertexHead(bool conservative) {
  std::string s = kVersion;
  s += kCommonVertex;
  s += kPulledVertex;
  s += conservative ? kConservativeVertex : kRawVertex;
  return s;
}

std::string occlusionFragmentHead(bool conservative) {
  std::string s = kVersion;
  if (conservative) s += kCoverage;
  return s;
}

std::string occlusionWriteFragmentShader(bool conservative) {
  return occlusionFragmentHead(conservative) +
         (conservative ? kCoverageFragmentMain : kEmptyFragmentMain);
}

GlProgramName makeRawOcclusionProgram() {
  const std::string vertex = occlusionVertexHead(false) + kRawQueryMain;
  const std::string fragment = occlusionWriteFragmentShader(false);
  return linkProgram("raw occlusion",
                     {{GL_VERTEX_SHADER, vertex}, {GL_FRAGMENT_SHADER, fragment}});
}

GlProgramName makeConservativeOcclusionProgram() {
  const std::string vertex = occlusionVertexHead(true) + kConservativeQueryMain;
  const std::string fragment = occlusionWriteFragmentShader(true);
  return linkProgram("conservative occlusion",
                     {{GL_VERTEX_SHADER, vertex}, {GL_FRAGMENT_SHADER, fragment}});
}

}  // namespace cdb
