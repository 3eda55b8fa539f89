#include "culling/visibility/OcclusionShaders.h"

#include "render/GlProgram.h"

namespace cdb {

namespace {

// Every vertex: local (or box) -> object pose from the per-frame matrix buffer -> the pass' view.
constexpr const char* kRawVertex = R"(#version 450 core
layout(location = 0) in vec3 aPosition;
layout(std430, binding = 0) readonly buffer ModelMatrices { mat4 uModels[]; };
layout(location = 0) uniform int uObject;
layout(location = 1) uniform mat4 uLocal;
layout(location = 2) uniform mat4 uWorldToClip;
layout(location = 3) uniform float uNdcOffset;
void main() {
  vec4 clip = uWorldToClip * (uModels[uObject] * (uLocal * vec4(aPosition, 1.0)));
  // Tests are pushed away from the viewer by the thesis' small offset (NDC z grows along the view
  // in both depth orders; glDepthRange does the reversing).
  gl_Position = vec4(clip.xy, clip.z + uNdcOffset, 1.0);
}
)";

constexpr const char* kEmptyFragment = R"(#version 450 core
void main() {}
)";

constexpr const char* kScreenVertex = R"(#version 450 core
layout(location = 0) in vec3 aPosition;
layout(std430, binding = 0) readonly buffer ModelMatrices { mat4 uModels[]; };
layout(location = 0) uniform int uObject;
layout(location = 1) uniform mat4 uLocal;
layout(location = 2) uniform mat4 uWorldToScreen;
out vec3 vScreen;  // pixels x, y and view depth t in [0, 1]
void main() {
  vScreen = (uWorldToScreen * (uModels[uObject] * (uLocal * vec4(aPosition, 1.0)))).xyz;
}
)";

// Emits the triangle dilated by a pixel square grown by the margin (the Minkowski sum), which
// covers the centre of every pixel the triangle touches. It is the intersection of the triangle's
// bounding box grown by g and the three edge half-planes each pushed out by the square's support
// g (|nx| + |ny|) along the edge normal; clipping the box by the half-planes keeps every vertex
// finite even for slivers, whose offset-edge triangle would run off to infinity.
constexpr const char* kConservativeGeometry = R"(#version 450 core
layout(triangles) in;
layout(triangle_strip, max_vertices = 12) out;
in vec3 vScreen[];
flat out vec4 gPlane;     // t at the reference point, dt/dx, dt/dy, extent of t over a grown pixel
flat out vec4 gRefRange;  // reference point (pixels), smallest and largest vertex t
layout(location = 7) uniform float uGrow;
layout(location = 8) uniform float uResolution;

const int kMaxVertices = 12;
vec2 poly[kMaxVertices];
int count;

// Keeps the part of the polygon with dot(n, x) <= d (Sutherland-Hodgman).
void clipBy(vec2 n, float d) {
  vec2 kept[kMaxVertices];
  int m = 0;
  for (int i = 0; i < count; ++i) {
    vec2 a = poly[i];
    vec2 b = poly[i + 1 < count ? i + 1 : 0];
    float da = dot(n, a) - d;
    float db = dot(n, b) - d;
    if (da <= 0.0 && m < kMaxVertices) kept[m++] = a;
    if ((da <= 0.0) != (db <= 0.0) && m < kMaxVertices) kept[m++] = mix(a, b, da / (da - db));
  }
  poly = kept;
  count = m;
}

void main() {
  vec2 p[3] = vec2[3](vScreen[0].xy, vScreen[1].xy, vScreen[2].xy);
  vec3 t = vec3(vScreen[0].z, vScreen[1].z, vScreen[2].z);
  vec2 lo = min(min(p[0], p[1]), p[2]) - uGrow;
  vec2 hi = max(max(p[0], p[1]), p[2]) + uGrow;
  poly[0] = lo;
  poly[1] = vec2(hi.x, lo.y);
  poly[2] = hi;
  poly[3] = vec2(lo.x, hi.y);
  count = 4;
  for (int i = 0; i < 3; ++i) {
    vec2 a = p[i];
    vec2 e = p[(i + 1) % 3] - a;
    float len = length(e);
    if (len < 1e-6) continue;  // a point-like edge: the other edges and the box bound it
    vec2 n = vec2(e.y, -e.x) / len;
    float off = uGrow * (abs(n.x) + abs(n.y));
    float side = dot(n, p[(i + 2) % 3] - a);  // where the opposite vertex lies
    float base = dot(n, a);
    if (abs(side) < 1e-3) {
      // Edge-on: the orientation is not trustworthy, keep the slab around the edge's line.
      clipBy(n, base + off + abs(side));
      clipBy(-n, -base + off + abs(side));
    } else if (side < 0.0) {
      clipBy(n, base + off);
    } else {
      clipBy(-n, -base + off);
    }
  }
  if (count < 3) return;

  // Depth is linear in screen space (orthographic). Its extreme over a grown pixel square is the
  // value at the centre -/+ g (|dt/dx| + |dt/dy|). Near-degenerate triangles fall back on the
  // vertex range, which bounds their depth anyway.
  float tmin = min(min(t.x, t.y), t.z);
  float tmax = max(max(t.x, t.y), t.z);
  vec2 e1 = p[1] - p[0];
  vec2 e2 = p[2] - p[0];
  float det = e1.x * e2.y - e1.y * e2.x;
  vec4 plane = vec4(0.5 * (tmin + tmax), 0.0, 0.0, 2.0);
  if (abs(det) > 1e-6 * (dot(e1, e1) + dot(e2, e2))) {
    float dt1 = t.y - t.x;
    float dt2 = t.z - t.x;
    float a = (dt1 * e2.y - dt2 * e1.y) / det;
    float b = (dt2 * e1.x - dt1 * e2.x) / det;
    float extent = uGrow * (abs(a) + abs(b));
    if (!isinf(extent) && !isnan(extent)) plane = vec4(t.x, a, b, extent);
  }
  vec4 refRange = vec4(p[0], tmin, tmax);

  // The convex polygon as a strip: 0, 1, n-1, 2, n-2, ...
  for (int k = 0; k < count; ++k) {
    int idx = k == 0 ? 0 : ((k & 1) == 1 ? (k + 1) / 2 : count - k / 2);
    gPlane = plane;
    gRefRange = refRange;
    // z is unused: the fragment shader writes the depth, and z = 0 is never clipped.
    gl_Position = vec4(poly[idx] / uResolution * 2.0 - 1.0, 0.0, 1.0);
    EmitVertex();
  }
  EndPrimitive();
}
)";

// Writes the nearest depth of the triangle over the pixel (depth writes) or the farthest (tests),
// each clamped to the triangle's own vertex range (both bound the depth of any of its points in the
// pixel), moved by the epsilon toward "occluded", and kept inside the pass' half of the range.
constexpr const char* kConservativeFragment = R"(#version 450 core
flat in vec4 gPlane;
flat in vec4 gRefRange;
layout(location = 4) uniform vec4 uDepthMap;
layout(location = 5) uniform vec2 uDepthClamp;
layout(location = 6) uniform float uSide;
void main() {
  vec2 d = gl_FragCoord.xy - gRefRange.xy;
  float centre = gPlane.x + gPlane.y * d.x + gPlane.z * d.y;
  float t = uSide > 0.0 ? min(centre + gPlane.w, gRefRange.w) : max(centre - gPlane.w, gRefRange.z);
  float z = uDepthMap.x + uDepthMap.y * t + uSide * uDepthMap.z;
  gl_FragDepth = clamp(z, uDepthClamp.x, uDepthClamp.y);
}
)";

}  // namespace

GlProgramName makeRawOcclusionProgram() {
  return linkProgram("raw occlusion", {{GL_VERTEX_SHADER, kRawVertex},
                                       {GL_FRAGMENT_SHADER, kEmptyFragment}});
}

GlProgramName makeConservativeOcclusionProgram() {
  return linkProgram("conservative occlusion", {{GL_VERTEX_SHADER, kScreenVertex},
                                                {GL_GEOMETRY_SHADER, kConservativeGeometry},
                                                {GL_FRAGMENT_SHADER, kConservativeFragment}});
}

}  // namespace cdb
