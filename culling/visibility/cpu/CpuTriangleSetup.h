#pragma once
// Triangle set-up of the CPU depth rasteriser: from a triangle in the pass' screen space to the
// per-pixel coverage and depth functions the SIMD loops evaluate (CpuRasteriser), for the
// conservative mode (every pixel whose closed square the triangle meets; the triangle's farthest
// depth there for a test, its nearest for a write) and for raw mode (pixel centres, as GL).
//
// Everything here is computed in double and rounded once to float for the loops; the bounds on the
// rounding of those float evaluations are added so that rounding can only add pixels and only
// move depths toward "occluded". Header-only so that every SIMD target inlines it.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace cdb {

// A triangle of the pass: x, y in pixels of the depth buffer (pixel (i, j) is the square
// [i, i + 1] x [j, j + 1]), k its depth key.
struct ScreenTriangle {
  static constexpr int kVertices = 3;
  double x[3];
  double y[3];
  double k[3];
};

// A face of a box in the same space, corners in order around it: a parallelogram up to the
// rounding of its corners' transforms (the pass' matrix is affine). Drawn as one piece instead of
// two triangles, it is set up once and its pixels are visited once (conservative mode only).
struct ScreenQuad {
  static constexpr int kVertices = 4;
  double x[4];
  double y[4];
  double k[4];
};

// Depth keys are stored depths times `sign` (+1, or -1 in a reversed pass): a smaller key is
// nearer in both depth orders, so "occluded" is key >= stored key and a write keeps the smaller.
struct RasterPass {
  int resolution = 0;
  float sign = 1.f;
  // The pass' part of the depth range, in keys: GL_DEPTH_CLAMP clamps every depth into it.
  float keyLo = 0.f;
  float keyHi = 1.f;
  // DepthPassSetup::depthEpsilon, in keys (= stored-depth units).
  double depthEpsilon = 0.0;
  // Conservative mode: how far a screen position may be off from the exact one (double rounding
  // of the vertex transforms), in pixels; pixel squares are grown by it.
  double marginPx = 0.0;
  // Raw mode: what tests add to their key (VisibilityOptions::rawDepthOffset in keys).
  double rawTestOffset = 0.0;
  bool conservative = true;
  // An order-independent pass (DepthUse::OrderIndependent; sign +1): the buffer keeps the nearest
  // value, its object and the nearest of the others, and a test reads the others' nearest.
  bool orderIndependent = false;
};

enum class RasterRole { Test, Write };

// What the loops evaluate. Pixel (x0 + dx, y0 + dy) is covered when, for each edge e,
// lo[e] <= a[e] dx + b[e] dy + c[e] <= hi[e]; its key is min(max(za dx + zb dy + zc, zLo), zHi).
struct TriangleRaster {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;  // pixel bounding box, inclusive, clipped to the buffer
  float a[3] = {}, b[3] = {}, c[3] = {};
  float lo[3] = {}, hi[3] = {};
  float za = 0.f, zb = 0.f, zc = 0.f;
  float zLo = 0.f, zHi = 0.f;
};

namespace raster_detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

// The next float above f, by its bits (std::nextafter is a library call, and this runs a few
// times per triangle): either zero gives the smallest subnormal, -infinity the lowest float; not
// for +infinity or NaN. Selects, not branches.
inline float nextUp(float f) {
  const auto bits = std::bit_cast<std::uint32_t>(f);
  const std::uint32_t step = (bits >> 31) != 0 ? ~0u : 1u;  // toward +infinity: -1 if negative
  return std::bit_cast<float>((bits << 1) == 0 ? 1u : bits + step);
}

// The float nearest to v that is not below (above) it; infinities stay as they are. Round to
// nearest goes either way about half the time, so a branch on it mispredicts as often: the
// result is a select of both candidates' bits.
inline float roundUp(double v) {
  const float f = static_cast<float>(v);
  const bool below = static_cast<double>(f) < v;  // then f is finite or -infinity
  const auto bits = std::bit_cast<std::uint32_t>(f);
  const std::uint32_t up = std::bit_cast<std::uint32_t>(nextUp(f));
  // (Arithmetic on a mask: written as a conditional, the compiler makes it a branch again.)
  return std::bit_cast<float>(bits + ((up - bits) & (0u - static_cast<std::uint32_t>(below))));
}
inline float roundDown(double v) { return -roundUp(-v); }

// Bound on the error of evaluating a dx + b dy + c in float (a, b, c rounded to float, two or
// three fused multiply-adds) relative to the exact value, as a fraction of |a| W + |b| H + |c|
// over the evaluated pixels: about six roundings of 2^-24 each, with room to spare. It also
// covers the double rounding of the set-up itself (2^-52 relative).
inline constexpr double kFloatEvalError = 1.0 / (1 << 20);  // 2^-20
// The same for depths, whose magnitudes are about 1 (a key): tighter, so that it does not dwarf
// the depth epsilon; five roundings of 2^-24.
inline constexpr double kFloatDepthError = 1.0 / (1 << 21);  // 2^-21

template <class Piece>
inline bool allFinite(const Piece& t) {
  for (int i = 0; i < Piece::kVertices; ++i)
    if (!std::isfinite(t.x[i]) || !std::isfinite(t.y[i]) || !std::isfinite(t.k[i])) return false;
  return true;
}

// Smallest and largest of a piece's vertex values.
template <int N>
inline double smallest(const double (&v)[N]) {
  double m = v[0];
  for (int i = 1; i < N; ++i) m = std::min(m, v[i]);
  return m;
}
template <int N>
inline double largest(const double (&v)[N]) {
  double m = v[0];
  for (int i = 1; i < N; ++i) m = std::max(m, v[i]);
  return m;
}

}  // namespace raster_detail

// Set-up runs in two steps, so that a triangle whose tiles already decide it (a test nearer than
// everything stored under its box, a write behind it) costs only the first. Both are forced inline
// into the SIMD loops' targets (CpuRasteriser), which compile them with the target's instructions.
#define CDB_RASTER_INLINE [[gnu::always_inline]] inline

// Step 1: the pixel box and the key bounds r.zLo, r.zHi. False when the triangle covers no pixel
// of the buffer (off-screen, or a non-finite vertex, or in raw mode a zero-area triangle, which GL
// does not rasterise either). The same for a quad (conservative mode).
template <class Piece>
CDB_RASTER_INLINE bool setupBounds(const Piece& t, const RasterPass& pass, RasterRole role,
                                   TriangleRaster& r) {
  using namespace raster_detail;
  if (!allFinite(t)) return false;
  const bool conservative = pass.conservative;
  const double m = conservative ? pass.marginPx : 0.0;
  const double minX = smallest(t.x), maxX = largest(t.x);
  const double minY = smallest(t.y), maxY = largest(t.y);
  // Conservative: pixel i's grown square [i - m, i + 1 + m] meets [minX, maxX] exactly for
  // i in [ceil(minX - m) - 1, floor(maxX + m)] (a triangle touching a pixel border at a vertex
  // covers both pixels). Raw: the centre i + 1/2 lies in [minX, maxX].
  const double lowShift = conservative ? -m : -0.5, highShift = conservative ? m : -0.5;
  double bx0 = std::ceil(minX + lowShift) - (conservative ? 1.0 : 0.0);
  double by0 = std::ceil(minY + lowShift) - (conservative ? 1.0 : 0.0);
  double bx1 = std::floor(maxX + highShift), by1 = std::floor(maxY + highShift);
  const double last = pass.resolution - 1;
  bx0 = std::max(bx0, 0.0), by0 = std::max(by0, 0.0);
  bx1 = std::min(bx1, last), by1 = std::min(by1, last);
  if (bx0 > bx1 || by0 > by1) return false;
  if (!conservative) {
    const double det =
        (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.y[1] - t.y[0]) * (t.x[2] - t.x[0]);
    if (det == 0.0) return false;
  }
  r.x0 = static_cast<int>(bx0), r.y0 = static_cast<int>(by0);
  r.x1 = static_cast<int>(bx1), r.y1 = static_cast<int>(by1);

  // The key over the triangle lies within its vertex keys [kMin, kMax] (it is their convex
  // hull); then the depth epsilon toward "occluded" (conservative) or the raw offset (tests).
  const double kMin = smallest(t.k), kMax = largest(t.k);
  const bool test = role == RasterRole::Test;
  const double shift = conservative ? (test ? pass.depthEpsilon : -pass.depthEpsilon)
                                    : (test ? pass.rawTestOffset : 0.0);
  // Depth clamping (GL_DEPTH_CLAMP) of a value clamped to [lo, hi] is the value clamped to the
  // clamped bounds.
  const auto clampToPass = [&](float v) { return std::clamp(v, pass.keyLo, pass.keyHi); };
  if (test)
    r.zLo = clampToPass(roundUp(kMin + shift)), r.zHi = clampToPass(roundUp(kMax + shift));
  else
    r.zLo = clampToPass(roundDown(kMin + shift)), r.zHi = clampToPass(roundDown(kMax + shift));
  return true;
}

// Small triangles (conservative mode only): when the pixel box of step 1 is at most
// kSmallBox x kSmallBox pixels, the loops skip step 2 and treat every pixel of the box as covered
// with the key bound of step 1 (r.zLo for a write, r.zHi for a test). The box holds every pixel
// the triangle meets and the bound is at least as far (test) or near (write) as the exact one at
// any of them, so this stays conservative: it can only add pixels and move keys toward
// "occluded". A triangle this small covers most of its box anyway.
inline constexpr int kSmallBox = 3;
[[nodiscard]] inline bool smallBox(const RasterPass& pass, const TriangleRaster& r) {
  return pass.conservative && r.x1 - r.x0 < kSmallBox && r.y1 - r.y0 < kSmallBox;
}

namespace raster_detail {

// Edge slot e left without a constraint (every pixel of the box passes it).
CDB_RASTER_INLINE void unconstrainedEdge(int e, TriangleRaster& r) {
  r.a[e] = r.b[e] = r.c[e] = 0.f;
  r.lo[e] = -std::numeric_limits<float>::infinity();
  r.hi[e] = std::numeric_limits<float>::infinity();
}

// One separating axis of a conservative piece, into edge slot e: n = (a, b), along which the
// piece spans [spanLo, spanHi] relative to a reference point on it, and c, the function
// n . (p - reference) at the box's pixel origin. The pixel square at the evaluated corner spans
// f(corner) + [minOff, maxOff] along n (grown by the margin m); the two overlap when f(corner)
// lies in [spanLo - maxOff, spanHi - minOff].
CDB_RASTER_INLINE void conservativeEdge(int e, double a, double b, double c, double spanLo,
                                        double spanHi, double m, double spanX, double spanY,
                                        TriangleRaster& r) {
  const double grow = m * (std::abs(a) + std::abs(b));
  const double maxOff = std::max(a, 0.0) + std::max(b, 0.0) + grow;
  const double minOff = std::min(a, 0.0) + std::min(b, 0.0) - grow;
  const double lo = spanLo - maxOff, hi = spanHi - minOff;
  // The loops evaluate f in float: widen by a bound of that error (only adds pixels).
  const double tol = kFloatEvalError * (std::abs(a) * spanX + std::abs(b) * spanY + std::abs(c) +
                                        std::abs(lo) + std::abs(hi));
  r.a[e] = static_cast<float>(a), r.b[e] = static_cast<float>(b), r.c[e] = static_cast<float>(c);
  r.lo[e] = roundDown(lo - tol), r.hi[e] = roundUp(hi + tol);
  if (!std::isfinite(r.a[e]) || !std::isfinite(r.b[e]) || !std::isfinite(r.c[e]) ||
      !std::isfinite(tol)) {
    // Coordinates beyond float's range (far off-screen vertices): drop this edge's
    // constraint; more pixels is the safe side for tests and writes alike.
    unconstrainedEdge(e, r);
  }
}

// Coverage of a quad (conservative mode): separating axes of a parallelogram and a square are the
// square's two axes (the bounding box of step 1) and the normals of two adjacent edges. Along the
// normal of edge s (corner s to s + 1) the quad spans the range of its four corners, which holds
// the convex hull of the corners as rounded (the two triangles GL would draw) even where rounding
// has made them a little off a parallelogram. The third edge slot stays unconstrained.
CDB_RASTER_INLINE void quadCoverage(const ScreenQuad& q, double m, double spanX, double spanY,
                                    TriangleRaster& r) {
  const double ox = r.x0, oy = r.y0;
  for (int s = 0; s < 2; ++s) {
    const double a = q.y[s + 1] - q.y[s], b = -(q.x[s + 1] - q.x[s]);
    double spanLo = 0.0, spanHi = 0.0;
    for (int v = 0; v < 4; ++v) {
      const double f = a * (q.x[v] - q.x[s]) + b * (q.y[v] - q.y[s]);
      spanLo = std::min(spanLo, f), spanHi = std::max(spanHi, f);
    }
    const double c = a * (ox - q.x[s]) + b * (oy - q.y[s]);
    conservativeEdge(s, a, b, c, spanLo, spanHi, m, spanX, spanY, r);
  }
  unconstrainedEdge(2, r);
}

}  // namespace raster_detail

// Step 2: edge functions and the depth plane, for a triangle (or, in conservative mode, a quad)
// step 1 accepted.
template <class Piece>
CDB_RASTER_INLINE void setupCoverage(const Piece& t, const RasterPass& pass, RasterRole role,
                                     TriangleRaster& r) {
  constexpr bool quad = Piece::kVertices == 4;
  using namespace raster_detail;
  const bool conservative = pass.conservative;
  const double m = conservative ? pass.marginPx : 0.0;
  const double ox = r.x0, oy = r.y0;
  // Pixels and SIMD lanes evaluated lie within the box grown by a tile (lanes past the box are
  // masked, but their values are computed): the extent the float error bounds use.
  const double spanX = r.x1 - r.x0 + 8.0, spanY = r.y1 - r.y0 + 8.0;

  const double e1x = t.x[1] - t.x[0], e1y = t.y[1] - t.y[0];
  const double e2x = t.x[2] - t.x[0], e2y = t.y[2] - t.y[0];
  const double det = e1x * e2y - e1y * e2x;

  // Coverage.
  if constexpr (quad) {
    quadCoverage(t, m, spanX, spanY, r);
  } else if (conservative) {
    // Separating axes of a triangle and a square: the square's two axes (the bounding box
    // above) and the three edge normals. Along edge e's normal n = (a, b) the triangle spans
    // [min(0, side), max(0, side)] relative to the edge's line (side: where the opposite vertex
    // lies), and the pixel square spans f(corner) + [minOff, maxOff]; the triangle meets the
    // square exactly when all five projections overlap. This needs no orientation, so degenerate
    // triangles (segments, points) are tested exactly too: their edge normals are the segment's
    // normal, or zero (no constraint) for a point.
    for (int e = 0; e < 3; ++e) {
      const int i = e, j = (e + 1) % 3, k = (e + 2) % 3;
      const double a = t.y[j] - t.y[i], b = -(t.x[j] - t.x[i]);
      const double side = a * (t.x[k] - t.x[i]) + b * (t.y[k] - t.y[i]);
      const double c = a * (ox - t.x[i]) + b * (oy - t.y[i]);
      conservativeEdge(e, a, b, c, std::min(0.0, side), std::max(0.0, side), m, spanX, spanY, r);
    }
  } else {
    // Pixel centres strictly inside, or on an edge that owns its boundary (a top-left style rule:
    // of two triangles sharing an edge, exactly one owns it, as GL's rasterisers).
    const double orient = det > 0 ? 1.0 : -1.0;
    for (int e = 0; e < 3; ++e) {
      const int i = e, j = (e + 1) % 3;
      // Inside is f >= 0: n = orient * (-(yj - yi), xj - xi).
      const double a = -orient * (t.y[j] - t.y[i]), b = orient * (t.x[j] - t.x[i]);
      const double c = a * (ox + 0.5 - t.x[i]) + b * (oy + 0.5 - t.y[i]);
      const bool owns = a > 0.0 || (a == 0.0 && b > 0.0);
      r.a[e] = static_cast<float>(a), r.b[e] = static_cast<float>(b),
      r.c[e] = static_cast<float>(c);
      r.lo[e] = owns ? 0.f : std::numeric_limits<float>::min();
      r.hi[e] = std::numeric_limits<float>::infinity();
    }
  }

  // Depth: the plane k0 + gx (x - x0) + gy (y - y0) of the keys, clamped to [zLo, zHi].
  const bool test = role == RasterRole::Test;
  // A usable plane: the triangle is not too close to edge-on (sine of its screen angle above
  // 2^-20), so the gradient is well conditioned; otherwise the vertex bound alone is used.
  const double scale = std::sqrt((e1x * e1x + e1y * e1y) * (e2x * e2x + e2y * e2y));
  if (!(std::abs(det) > scale * (1.0 / (1 << 20)))) {
    r.za = r.zb = 0.f;
    r.zc = test ? r.zHi : r.zLo;
    return;
  }
  const double dk1 = t.k[1] - t.k[0], dk2 = t.k[2] - t.k[0];
  const double gx = (dk1 * e2y - dk2 * e1y) / det;
  const double gy = (dk2 * e1x - dk1 * e2x) / det;
  double zc;
  if (conservative) {
    // The plane over the grown pixel square at (x, y) lies within its values at the square's
    // corners: the farthest corner bounds a test, the nearest a write. Its maximum over the
    // covered part of the square is at most that, and at most kMax (the clamp).
    const double grow = m * (std::abs(gx) + std::abs(gy));
    const double corner = test ? std::max(gx, 0.0) + std::max(gy, 0.0) + grow
                               : std::min(gx, 0.0) + std::min(gy, 0.0) - grow;
    zc = t.k[0] + gx * (ox - t.x[0]) + gy * (oy - t.y[0]) + corner;
  } else {
    zc = t.k[0] + gx * (ox + 0.5 - t.x[0]) + gy * (oy + 0.5 - t.y[0]);
  }
  // The float evaluation's error (and the gradient's, 2^-32 relative at this conditioning),
  // then the epsilon or offset toward "occluded".
  double shift = kFloatDepthError * (std::abs(zc) + std::abs(gx) * spanX + std::abs(gy) * spanY);
  if constexpr (quad) {
    // The plane is that of corners 0, 1, 2. The second triangle (0, 2, 3) has its own as rounded:
    // the two differ over it by at most their difference at corner 3, which widens the bound.
    shift += std::abs(t.k[3] - (t.k[0] + gx * (t.x[3] - t.x[0]) + gy * (t.y[3] - t.y[0])));
  }
  if (conservative)
    shift += pass.depthEpsilon;  // transform rounding and float32 storage, as GL's bound
  else if (test)
    shift += pass.rawTestOffset;
  zc += test ? shift : -shift;
  r.zc = test ? roundUp(zc) : roundDown(zc);
  r.za = static_cast<float>(gx), r.zb = static_cast<float>(gy);
  if (!std::isfinite(r.za) || !std::isfinite(r.zb) || !std::isfinite(r.zc)) {
    r.za = r.zb = 0.f;  // the vertex bound alone
    r.zc = test ? r.zHi : r.zLo;
  }
}

}  // namespace cdb
