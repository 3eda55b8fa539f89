#include "culling/visibility/compute/ComputeShaders.h"

#include <cstdint>
#include <string>
#include <utility>

#include "culling/visibility/compute/ComputeLayout.h"

namespace cdb::compute {

namespace {

// Declarations every stage shares: the flags, the structs of ComputeLayout.h, the buffers (each
// stage declares those it uses by name: SCENE, FETCH, PIECES, BINS, ANSWERS, RETAINED) and the
// exact helpers.
std::string common(const char* buffers, bool nativeFma) {
  std::string s = R"(#version 450 core
)";
  s += nativeFma ? "#define CDB_NATIVE_FMA 1\n" : "#define CDB_NATIVE_FMA 0\n";
  s += buffers;
  // ComputeLayout.h's constants, under the same names.
  const std::pair<const char*, std::uint32_t> unsignedConstants[] = {
      {"kTest", kTest}, {"kAnswerEach", kAnswerEach}, {"kBoxes", kBoxes}, {"kListed", kListed},
      {"kConservative", kConservative}, {"kReversed", kReversed},
      {"kOrderIndependent", kOrderIndependent}, {"kWindingPositive", kWindingPositive},
      {"kWindingNegative", kWindingNegative}, {"kContinues", kContinues}, {"kRetained", kRetained},
      {"kChainOrderIndependent", kChainOrderIndependent}, {"kChunkSlots", kChunkSlots},
      {"kCutScan", kCutScan}, {"kCutSort", kCutSort}};
  s += "\n";
  for (const auto& [name, value] : unsignedConstants)
    s += "const uint " + std::string(name) + " = " + std::to_string(value) + "u;\n";
  s += "const int kTile = " + std::to_string(kTile) + ";\n";
  s += "const int kMaxTileColumns = " + std::to_string(kMaxTileColumns) + ";\n";
  s += R"(const uint kNoObject = 0xffffffffu;

struct Command {
  dvec4 row[3];
  uint flags; uint mesh; uint first; uint count; uint query; uint pass; uint firstChunk; uint object;
};
struct Pass {
  double depthEpsilon; double marginPx; double rawTestOffset;
  int resolution; float sign; float keyLo; float keyHi; uint flags; uint chain;
};
struct Chain {
  int resolution; int tilesX; uint firstTile; uint flags; float clearValue; uint u0; uint u1; uint u2;
};
// flags: bits 0-8 as the command's (kTest ...), bits 9 and up its chain.
struct Chunk { ivec4 rect; uint flags; uint answer; uint object; uint count; };

#ifdef SCENE
layout(std430, binding = 0) readonly buffer SceneVertices { float vertexData[]; };
layout(std430, binding = 1) readonly buffer SceneTriangles { uint triangleData[]; };
layout(std430, binding = 2) readonly buffer SceneMeshes { uvec4 meshData[]; };
#endif
#ifdef FETCH
layout(std430, binding = 3) readonly buffer Commands { Command commands[]; };
layout(std430, binding = 4) readonly buffer Passes { Pass passes[]; };
layout(std430, binding = 6) readonly buffer Listed { uint listed[]; };
layout(std430, binding = 7) readonly buffer Boxes { dvec4 boxRows[]; };
#endif
#ifdef CHAINS
layout(std430, binding = 5) readonly buffer Chains { Chain chains[]; };
#endif
#ifdef PIECES
// A piece's pixel box, and its edges' and depth plane's bounds (lo, hi); its edge functions and
// depth plane (a, b, c: three vec4 a piece, the plane in w). Two blocks of 48 bytes a piece, so
// that each stays within the 128 MiB llvmpipe binds for 2.8 million pieces.
struct PieceBound { ivec4 box; vec4 lo; vec4 hi; };
layout(std430, binding = 8) buffer PieceBounds { PieceBound pieceBound[]; };
layout(std430, binding = 9) buffer PieceEdges { vec4 pieceEdge[]; };
#endif
#ifdef CHUNKS
layout(std430, binding = 10) buffer Chunks { Chunk chunks[]; };
#endif
#ifdef BINS
layout(std430, binding = 11) buffer TileCounts { uint tileCount[]; };
layout(std430, binding = 12) buffer TileOffsets { uint tileOffset[]; };
// A tile's entries: the chunk, and which of its 64 pieces have a pixel in the tile (two words).
layout(std430, binding = 13) buffer TileLists { uint tileList[]; };
layout(std430, binding = 19) buffer TileMasks { uvec2 tileMask[]; };
#endif
#ifdef HEAVY
// Per tile with more entries than one evaluation dispatch takes: its index among those (binScan),
// and those tiles' pixel states between dispatches (value, object, others; 256 words each).
layout(std430, binding = 20) buffer TileHeavy { uint tileHeavy[]; };
layout(std430, binding = 21) buffer HeavyStates { uint heavyState[]; };
#endif
#ifdef ANSWERS
layout(std430, binding = 14) buffer Answers { uint answers[]; };
#endif
#ifdef STATUS
layout(std430, binding = 15) buffer Status {
  uint listCapacity; uint overflow; uint entries; uint pixelsTested; uint pixelsWritten;
  uint usedTiles; uint heavyTiles; uint mostEntries;
  uint tileGroups[3];  // the dispatch of binSort and evaluate: a workgroup a used tile
  uint heavyCapacity; uint truncated;
};
layout(std430, binding = 18) buffer UsedTiles { uint usedTile[]; };
#endif
#ifdef RETAINED
// The buffer a chain goes on in and the one the fetch's last chain leaves (the same buffer when
// that chain is the one going on): per pixel its value, object and others' value (planes of
// resolution^2 words), then per tile whether it is still uniform at the clear value (its pixels
// not stored).
layout(std430, binding = 16) readonly buffer RetainedIn { uint retainedIn[]; };
layout(std430, binding = 17) buffer RetainedOut { uint retainedOut[]; };
uniform float retainedInClear;
#endif

uniform uint commandCount;
uniform uint chunkCount;
uniform uint tileTotal;
uniform uint chainCount;
// Entries of a tile's list one evaluation dispatch takes (ComputeLayout.h: kLoopLimitedSegment
// where the driver limits loops), and whether it does.
uniform uint segmentEntries;
uniform uint loopLimited;

// The workgroup's index in a dispatch of (x, y) workgroups (more than 65535 in two dimensions).
uint workgroupIndex() { return gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x; }

// std::min and std::max as C++ defines them (the lesser / greater, the first when neither is).
double dmin(double a, double b) { return b < a ? b : a; }
double dmax(double a, double b) { return a < b ? b : a; }
float fminOf(float a, float b) { return b < a ? b : a; }
float fmaxOf(float a, float b) { return a < b ? b : a; }
bool finiteD(double v) { return !isinf(v) && !isnan(v); }
bool finiteF(float v) { return !isinf(v) && !isnan(v); }
float infinity() { return uintBitsToFloat(0x7f800000u); }

// raster_detail::nextUp, roundUp and roundDown: the float nearest v not below (above) it.
float nextUp(float f) {
  uint bits = floatBitsToUint(f);
  uint step = (bits >> 31) != 0u ? 0xffffffffu : 1u;
  return uintBitsToFloat((bits << 1) == 0u ? 1u : bits + step);
}
float roundUp(double v) {
  precise float f = float(v);
  return double(f) < v ? nextUp(f) : f;
}
float roundDown(double v) { return -roundUp(-v); }

// a * b + c rounded once, as the cpu backend's SIMD loops compute it (Highway's MulAdd, a fused
// multiply-add where the machine has one). Where the driver's fma() rounds twice (ComputeFma.h
// probes it), the exact product in double, the sum rounded to odd (so that rounding it to float
// once more is rounding the exact value), then to float.
float mulAdd(float a, float b, float c) {
#if CDB_NATIVE_FMA
  precise float r = fma(a, b, c);
  return r;
#else
  precise double p = double(a) * double(b);
  precise double cd = double(c);
  precise double t = p + cd;
  precise double bb = t - p;
  precise double err = (p - (t - bb)) + (cd - bb);
  if (err != 0.0lf && !isinf(t)) {
    uvec2 bits = unpackDouble2x32(t);
    if ((bits.x & 1u) == 0u) {
      // The odd one of t's two neighbours around the exact sum: away from zero when the error
      // has t's sign, toward it otherwise (t is not zero: a zero sum has no error).
      bool up = (err > 0.0lf) == (t > 0.0lf);
      uint low = up ? bits.x + 1u : bits.x - 1u;
      uint high = bits.y + (up && low == 0u ? 1u : 0u) - (!up && bits.x == 0u ? 1u : 0u);
      t = packDouble2x32(uvec2(low, high));
    }
  }
  return float(t);
#endif
}
)";
  return s;
}

// Set-up: CpuTriangleSetup's setupBounds and setupCoverage, the cube's faces of CpuPieces and the
// winding rule of chunkPieces, for one piece per invocation.
constexpr const char* kSetup = R"(
layout(local_size_x = 64) in;

// kFloatEvalError, kFloatDepthError, 2^-20 and 1e-9 (by its bits: a decimal literal is left to
// the compiler's parser).
const double kFloatEvalError = 1.0lf / 1048576.0lf;
const double kFloatDepthError = 1.0lf / 2097152.0lf;
double edgeOnFactor() { return packDouble2x32(uvec2(0xe826d695u, 0x3e112e0bu)); }

// A piece in the pass' screen space: up to four corners (x, y, key).
struct Corners { dvec3 p[4]; int n; };

// The screen position of object point (x, y, z): CpuPassSpace's screenPoint.
dvec3 screenPoint(dvec4 r0, dvec4 r1, dvec4 r2, double x, double y, double z) {
  precise double px = ((r0.x * x + r0.y * y) + r0.z * z) + r0.w;
  precise double py = ((r1.x * x + r1.y * y) + r1.z * z) + r1.w;
  precise double pk = (r2.x * x + (r2.y * y + r2.z * z)) + r2.w;
  return dvec3(px, py, pk);
}

// chunkPieces' drawnForRole.
bool drawnForRole(Corners t, double winding, bool test) {
  precise double e1x = t.p[1].x - t.p[0].x, e1y = t.p[1].y - t.p[0].y;
  precise double e2x = t.p[2].x - t.p[0].x, e2y = t.p[2].y - t.p[0].y;
  precise double facing = winding * (e1x * e2y - e1y * e2x);
  precise double edgeOn = edgeOnFactor() * (abs(e1x) + abs(e1y)) * (abs(e2x) + abs(e2y));
  return test ? facing >= -edgeOn : facing <= edgeOn;
}

// The pixel box, key bounds, edge functions and depth plane of CpuTriangleSetup's TriangleRaster:
// edges e in a[e], b[e], c[e], lo[e], hi[e]; the plane and key bounds in the w components.
ivec4 rBox;
vec4 rA, rB, rC, rLo, rHi;

bool setupBounds(Corners t, Pass ps, bool test) {
  for (int i = 0; i < t.n; ++i)
    if (!finiteD(t.p[i].x) || !finiteD(t.p[i].y) || !finiteD(t.p[i].z)) return false;
  bool conservative = (ps.flags & kConservative) != 0u;
  precise double m = conservative ? ps.marginPx : 0.0lf;
  precise double minX = t.p[0].x, maxX = t.p[0].x, minY = t.p[0].y, maxY = t.p[0].y;
  precise double kMin = t.p[0].z, kMax = t.p[0].z;
  for (int i = 1; i < t.n; ++i) {
    minX = dmin(minX, t.p[i].x), maxX = dmax(maxX, t.p[i].x);
    minY = dmin(minY, t.p[i].y), maxY = dmax(maxY, t.p[i].y);
    kMin = dmin(kMin, t.p[i].z), kMax = dmax(kMax, t.p[i].z);
  }
  precise double lowShift = conservative ? -m : -0.5lf;
  precise double highShift = conservative ? m : -0.5lf;
  precise double bx0 = ceil(minX + lowShift) - (conservative ? 1.0lf : 0.0lf);
  precise double by0 = ceil(minY + lowShift) - (conservative ? 1.0lf : 0.0lf);
  precise double bx1 = floor(maxX + highShift), by1 = floor(maxY + highShift);
  double last = double(ps.resolution - 1);
  bx0 = dmax(bx0, 0.0lf), by0 = dmax(by0, 0.0lf);
  bx1 = dmin(bx1, last), by1 = dmin(by1, last);
  if (bx0 > bx1 || by0 > by1) return false;
  if (!conservative) {
    precise double det = (t.p[1].x - t.p[0].x) * (t.p[2].y - t.p[0].y) -
                         (t.p[1].y - t.p[0].y) * (t.p[2].x - t.p[0].x);
    if (det == 0.0lf) return false;
  }
  rBox = ivec4(int(bx0), int(by0), int(bx1), int(by1));
  precise double shift = conservative ? (test ? ps.depthEpsilon : -ps.depthEpsilon)
                                      : (test ? ps.rawTestOffset : 0.0lf);
  float zLo = test ? roundUp(kMin + shift) : roundDown(kMin + shift);
  float zHi = test ? roundUp(kMax + shift) : roundDown(kMax + shift);
  // std::clamp(v, keyLo, keyHi)
  zLo = zLo < ps.keyLo ? ps.keyLo : (ps.keyHi < zLo ? ps.keyHi : zLo);
  zHi = zHi < ps.keyLo ? ps.keyLo : (ps.keyHi < zHi ? ps.keyHi : zHi);
  rLo.w = zLo, rHi.w = zHi;
  return true;
}

void unconstrainedEdge(int e) {
  rA[e] = 0.0, rB[e] = 0.0, rC[e] = 0.0;
  rLo[e] = -infinity(), rHi[e] = infinity();
}

void conservativeEdge(int e, double a, double b, double c, double spanLo, double spanHi, double m,
                      double spanX, double spanY) {
  precise double grow = m * (abs(a) + abs(b));
  precise double maxOff = dmax(a, 0.0lf) + dmax(b, 0.0lf) + grow;
  precise double minOff = dmin(a, 0.0lf) + dmin(b, 0.0lf) - grow;
  precise double lo = spanLo - maxOff, hi = spanHi - minOff;
  precise double tol =
      kFloatEvalError * (abs(a) * spanX + abs(b) * spanY + abs(c) + abs(lo) + abs(hi));
  precise float fa = float(a), fb = float(b), fc = float(c);
  rA[e] = fa, rB[e] = fb, rC[e] = fc;
  rLo[e] = roundDown(lo - tol), rHi[e] = roundUp(hi + tol);
  if (!finiteF(fa) || !finiteF(fb) || !finiteF(fc) || !finiteD(tol)) unconstrainedEdge(e);
}

void setupCoverage(Corners t, Pass ps, bool test) {
  bool quad = t.n == 4;
  bool conservative = (ps.flags & kConservative) != 0u;
  precise double m = conservative ? ps.marginPx : 0.0lf;
  precise double ox = double(rBox.x), oy = double(rBox.y);
  precise double spanX = double(rBox.z - rBox.x) + 8.0lf, spanY = double(rBox.w - rBox.y) + 8.0lf;
  precise double e1x = t.p[1].x - t.p[0].x, e1y = t.p[1].y - t.p[0].y;
  precise double e2x = t.p[2].x - t.p[0].x, e2y = t.p[2].y - t.p[0].y;
  precise double det = e1x * e2y - e1y * e2x;
  if (quad) {
    for (int s = 0; s < 2; ++s) {
      precise double a = t.p[s + 1].y - t.p[s].y, b = -(t.p[s + 1].x - t.p[s].x);
      precise double spanLo = 0.0lf, spanHi = 0.0lf;
      for (int v = 0; v < 4; ++v) {
        precise double f = a * (t.p[v].x - t.p[s].x) + b * (t.p[v].y - t.p[s].y);
        spanLo = dmin(spanLo, f), spanHi = dmax(spanHi, f);
      }
      precise double c = a * (ox - t.p[s].x) + b * (oy - t.p[s].y);
      conservativeEdge(s, a, b, c, spanLo, spanHi, m, spanX, spanY);
    }
    unconstrainedEdge(2);
  } else if (conservative) {
    for (int e = 0; e < 3; ++e) {
      int i = e, j = (e + 1) % 3, k = (e + 2) % 3;
      precise double a = t.p[j].y - t.p[i].y, b = -(t.p[j].x - t.p[i].x);
      precise double side = a * (t.p[k].x - t.p[i].x) + b * (t.p[k].y - t.p[i].y);
      precise double c = a * (ox - t.p[i].x) + b * (oy - t.p[i].y);
      conservativeEdge(e, a, b, c, dmin(0.0lf, side), dmax(0.0lf, side), m, spanX, spanY);
    }
  } else {
    precise double orient = det > 0.0lf ? 1.0lf : -1.0lf;
    for (int e = 0; e < 3; ++e) {
      int i = e, j = (e + 1) % 3;
      precise double a = -orient * (t.p[j].y - t.p[i].y), b = orient * (t.p[j].x - t.p[i].x);
      precise double c = a * (ox + 0.5lf - t.p[i].x) + b * (oy + 0.5lf - t.p[i].y);
      bool owns = a > 0.0lf || (a == 0.0lf && b > 0.0lf);
      precise float fa = float(a), fb = float(b), fc = float(c);
      rA[e] = fa, rB[e] = fb, rC[e] = fc;
      rLo[e] = owns ? 0.0 : uintBitsToFloat(0x00800000u);
      rHi[e] = infinity();
    }
  }
  float zLo = rLo.w, zHi = rHi.w;
  precise double scale = sqrt((e1x * e1x + e1y * e1y) * (e2x * e2x + e2y * e2y));
  if (!(abs(det) > scale * (1.0lf / 1048576.0lf))) {
    rA.w = 0.0, rB.w = 0.0, rC.w = test ? zHi : zLo;
    return;
  }
  precise double dk1 = t.p[1].z - t.p[0].z, dk2 = t.p[2].z - t.p[0].z;
  precise double gx = (dk1 * e2y - dk2 * e1y) / det;
  precise double gy = (dk2 * e1x - dk1 * e2x) / det;
  precise double zc;
  if (conservative) {
    precise double grow = m * (abs(gx) + abs(gy));
    precise double corner = test ? dmax(gx, 0.0lf) + dmax(gy, 0.0lf) + grow
                                 : dmin(gx, 0.0lf) + dmin(gy, 0.0lf) - grow;
    zc = t.p[0].z + gx * (ox - t.p[0].x) + gy * (oy - t.p[0].y) + corner;
  } else {
    zc = t.p[0].z + gx * (ox + 0.5lf - t.p[0].x) + gy * (oy + 0.5lf - t.p[0].y);
  }
  precise double shift = kFloatDepthError * (abs(zc) + abs(gx) * spanX + abs(gy) * spanY);
  if (quad)
    shift += abs(t.p[3].z - (t.p[0].z + gx * (t.p[3].x - t.p[0].x) + gy * (t.p[3].y - t.p[0].y)));
  if (conservative)
    shift += ps.depthEpsilon;
  else if (test)
    shift += ps.rawTestOffset;
  zc += test ? shift : -shift;
  precise float fzc = test ? roundUp(zc) : roundDown(zc);
  precise float za = float(gx), zb = float(gy);
  if (!finiteF(za) || !finiteF(zb) || !finiteF(fzc)) {
    za = 0.0, zb = 0.0, fzc = test ? zHi : zLo;
  }
  rA.w = za, rB.w = zb, rC.w = fzc;
}

// The unit cube's faces as two triangles each (CpuPieces' kCubeFaces).
const int kCubeFaces[36] = int[36](0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3, 0, 4, 5, 0, 5, 1,
                                   2, 3, 7, 2, 7, 6, 0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5);

dvec3 cubeCorner(uint box, int i) {
  return screenPoint(boxRows[3u * box], boxRows[3u * box + 1u], boxRows[3u * box + 2u],
                     (i & 1) != 0 ? 1.0lf : -1.0lf, (i & 2) != 0 ? 1.0lf : -1.0lf,
                     (i & 4) != 0 ? 1.0lf : -1.0lf);
}

shared int rectX0, rectY0, rectX1, rectY1;

void main() {
  uint chunk = workgroupIndex();
  if (chunk >= chunkCount) return;
  uint lane = gl_LocalInvocationIndex;
  // The chunk's command: the last whose first chunk is at most this one.
  uint lo = 0u, hi = commandCount - 1u;
  while (lo < hi) {
    uint mid = (lo + hi + 1u) / 2u;
    if (commands[mid].firstChunk <= chunk) lo = mid; else hi = mid - 1u;
  }
  Command c = commands[lo];
  Pass ps = passes[c.pass];
  bool test = (c.flags & kTest) != 0u;
  bool boxes = (c.flags & kBoxes) != 0u;
  bool conservative = (ps.flags & kConservative) != 0u;
  uint perBox = conservative ? 6u : 12u;
  uint perChunk = boxes ? (kChunkSlots / perBox) * perBox : kChunkSlots;
  uint slots = boxes ? c.count * perBox : c.count;
  uint firstSlot = (chunk - c.firstChunk) * perChunk;
  uint count = min(perChunk, slots - firstSlot);
  if (lane == 0u) rectX0 = 0x7fffffff, rectY0 = 0x7fffffff, rectX1 = -1, rectY1 = -1;
  memoryBarrierShared();
  barrier();

  ivec4 box = ivec4(1, 1, 0, 0);  // no pixel
  rA = vec4(0.0), rB = vec4(0.0), rC = vec4(0.0), rLo = vec4(0.0), rHi = vec4(0.0);
  if (lane < count) {
    uint slot = firstSlot + lane;
    Corners t;
    t.n = 3;
    bool drawn = true;
    if (!boxes) {
      uint tri = (c.flags & kListed) != 0u ? listed[c.first + slot] : c.first + slot;
      uint base = (meshData[c.mesh].x + tri) * 3u;
      for (int v = 0; v < 3; ++v) {
        uint at = triangleData[base + uint(v)] * 3u;
        t.p[v] = screenPoint(c.row[0], c.row[1], c.row[2], double(vertexData[at]),
                             double(vertexData[at + 1u]), double(vertexData[at + 2u]));
      }
      double winding = (c.flags & kWindingPositive) != 0u ? 1.0lf
                     : (c.flags & kWindingNegative) != 0u ? -1.0lf : 0.0lf;
      if (winding != 0.0lf) drawn = drawnForRole(t, winding, test);
    } else {
      uint b = c.first + slot / perBox;
      int inBox = int(slot % perBox);
      int face = conservative ? inBox : inBox / 2;
      // decidingFaces: how the key changes going out through the + face of the face's axis.
      double outward = boxRows[3u * b + 2u][face / 2];
      double away = (face % 2) == 1 ? outward : -outward;
      drawn = away == 0.0lf || (test ? away > 0.0lf : away < 0.0lf);
      if (conservative) {
        t.n = 4;
        t.p[0] = cubeCorner(b, kCubeFaces[6 * face]);
        t.p[1] = cubeCorner(b, kCubeFaces[6 * face + 1]);
        t.p[2] = cubeCorner(b, kCubeFaces[6 * face + 2]);
        t.p[3] = cubeCorner(b, kCubeFaces[6 * face + 5]);
      } else {
        int first = 6 * face + 3 * (inBox % 2);
        for (int v = 0; v < 3; ++v) t.p[v] = cubeCorner(b, kCubeFaces[first + v]);
      }
    }
    if (drawn && setupBounds(t, ps, test)) {
      box = rBox;
      bool small = conservative && box.z - box.x < 3 && box.w - box.y < 3;
      if (!small) setupCoverage(t, ps, test);
    }
  }
  uint piece = chunk * kChunkSlots + lane;
  pieceBound[piece].box = box;
  pieceBound[piece].lo = rLo;
  pieceBound[piece].hi = rHi;
  pieceEdge[3u * piece] = rA;
  pieceEdge[3u * piece + 1u] = rB;
  pieceEdge[3u * piece + 2u] = rC;
  if (box.x <= box.z) {
    atomicMin(rectX0, box.x), atomicMin(rectY0, box.y);
    atomicMax(rectX1, box.z), atomicMax(rectY1, box.w);
  }
  memoryBarrierShared();
  barrier();
  if (lane == 0u) {
    Chunk k;
    k.rect = ivec4(rectX0, rectY0, rectX1, rectY1);
    k.flags = (c.flags & 0x1ffu) | (ps.flags & (kConservative | kReversed | kOrderIndependent)) |
              (ps.chain << 9);
    bool each = (c.flags & kAnswerEach) != 0u;
    k.answer = !test ? 0u : !each ? c.query : c.query + (boxes ? firstSlot / perBox : firstSlot);
    k.object = c.object;
    k.count = count;
    chunks[chunk] = k;
  }
}
)";

// A workgroup per chunk: which of its pieces reach each tile column and each tile row of its
// rectangle (a piece reaches a tile when it reaches both: its box is a rectangle), for binCount
// and binFill; an invocation per piece sets its bits, then the tiles are shared out. Loops per
// invocation: a piece's columns and rows (at most kMaxTileColumns each) and the rectangle's tiles
// over 64 (at most kMaxTileColumns^2 / 64): within llvmpipe's limit.
constexpr const char* kChunkTiles = R"(
layout(local_size_x = 64) in;
shared uint columnLow[kMaxTileColumns], columnHigh[kMaxTileColumns];
shared uint rowLow[kMaxTileColumns], rowHigh[kMaxTileColumns];
// The chunk's tile rectangle, its bits set.
ivec4 chunkMasks(uint chunk, Chunk k) {
  ivec4 tiles = k.rect / kTile;
  int lane = int(gl_LocalInvocationIndex);
  int columns = tiles.z - tiles.x + 1, rows = tiles.w - tiles.y + 1;
  for (int i = lane; i < columns; i += 64) columnLow[i] = 0u, columnHigh[i] = 0u;
  for (int i = lane; i < rows; i += 64) rowLow[i] = 0u, rowHigh[i] = 0u;
  memoryBarrierShared();
  barrier();
  if (uint(lane) < k.count) {
    ivec4 b = pieceBound[chunk * kChunkSlots + uint(lane)].box;
    if (b.x <= b.z && b.y <= b.w) {
      uint bit = 1u << uint(lane & 31);
      ivec4 at = b / kTile - tiles.xyxy;
      for (int c = at.x; c <= at.z; ++c)
        if (lane < 32) atomicOr(columnLow[c], bit); else atomicOr(columnHigh[c], bit);
      for (int r = at.y; r <= at.w; ++r)
        if (lane < 32) atomicOr(rowLow[r], bit); else atomicOr(rowHigh[r], bit);
    }
  }
  memoryBarrierShared();
  barrier();
  return tiles;
}
// Which of the chunk's pieces reach tile (column, row) of its rectangle.
uvec2 piecesInTile(int column, int row) {
  return uvec2(columnLow[column] & rowLow[row], columnHigh[column] & rowHigh[row]);
}
)";

constexpr const char* kBinCount = R"(
void main() {
  uint chunk = workgroupIndex();
  if (chunk >= chunkCount) return;
  Chunk k = chunks[chunk];
  if (k.rect.x > k.rect.z) return;
  Chain ch = chains[k.flags >> 9];
  ivec4 tiles = chunkMasks(chunk, k);
  int columns = tiles.z - tiles.x + 1, n = columns * (tiles.w - tiles.y + 1);
  for (int i = int(gl_LocalInvocationIndex); i < n; i += 64) {
    int column = i % columns, row = i / columns;
    if (piecesInTile(column, row) != uvec2(0u))
      atomicAdd(tileCount[ch.firstTile + uint((tiles.y + row) * ch.tilesX + tiles.x + column)], 1u);
  }
}
)";

constexpr const char* kBinFill = R"(
void main() {
  uint chunk = workgroupIndex();
  if (chunk >= chunkCount || overflow != 0u) return;
  Chunk k = chunks[chunk];
  if (k.rect.x > k.rect.z) return;
  Chain ch = chains[k.flags >> 9];
  ivec4 tiles = chunkMasks(chunk, k);
  int columns = tiles.z - tiles.x + 1, n = columns * (tiles.w - tiles.y + 1);
  for (int i = int(gl_LocalInvocationIndex); i < n; i += 64) {
    int column = i % columns, row = i / columns;
    uvec2 mask = piecesInTile(column, row);
    if (mask == uvec2(0u)) continue;
    uint tile = ch.firstTile + uint((tiles.y + row) * ch.tilesX + tiles.x + column);
    uint at = tileOffset[tile] + atomicAdd(tileCount[tile], 1u);
    tileList[at] = chunk;
    tileMask[at] = mask;
  }
}
)";

// One workgroup: each invocation sums a run of counts, invocation 0 the runs, each writes its
// run's offsets and lists its tiles that have a chunk; the counts are zeroed for binFill to count
// again; the dispatch of the stages that run per such tile is written last.
constexpr const char* kBinScan = R"(
layout(local_size_x = 256) in;
shared uint runTotal[256];
void main() {
  uint id = gl_LocalInvocationIndex;
  uint per = (tileTotal + 255u) / 256u;
  if (loopLimited != 0u && per > 30000u) {  // two loops over a run, and invocation 0's 256
    if (id == 0u) atomicOr(truncated, kCutScan), overflow = 1u;
    return;
  }
  uint begin = min(id * per, tileTotal), end = min(begin + per, tileTotal);
  uint sum = 0u;
  for (uint t = begin; t < end; ++t) sum += tileCount[t];
  runTotal[id] = sum;
  memoryBarrierShared();
  barrier();
  if (id == 0u) {
    uint total = 0u;
    for (uint i = 0u; i < 256u; ++i) {
      uint n = runTotal[i];
      runTotal[i] = total;
      total += n;
    }
    entries = total;
    if (total > listCapacity) overflow = 1u;
    tileOffset[tileTotal] = total;
  }
  memoryBarrierShared();
  barrier();
  uint at = runTotal[id];
  for (uint t = begin; t < end; ++t) {
    tileOffset[t] = at;
    uint n = tileCount[t];
    if (n != 0u) usedTile[atomicAdd(usedTiles, 1u)] = t;
    if (n > segmentEntries) {
      tileHeavy[t] = atomicAdd(heavyTiles, 1u);
      atomicMax(mostEntries, n);
    }
    at += n;
    tileCount[t] = 0u;
  }
  memoryBarrierBuffer();
  barrier();
  if (id == 0u) {
    if (atomicAdd(heavyTiles, 0u) > heavyCapacity) overflow = 1u;
    uint used = overflow != 0u ? 0u : atomicAdd(usedTiles, 0u);
    uint x = min(used, 65535u);
    tileGroups[0] = x, tileGroups[1] = x == 0u ? 0u : (used + x - 1u) / x, tileGroups[2] = 1u;
  }
}
)";

// A tile's list sorted ascending (chunks are numbered in issue order): a bitonic network whose
// comparisons all go one way, so the list is padded with +infinity past its end without storing
// any (a pair reaching past the end stays as it is).
constexpr const char* kBinSort = R"(
layout(local_size_x = 256) in;
const uint kShared = 2048u;
shared uint keys[kShared];
shared uvec2 masks[kShared];

void main() {
  if (workgroupIndex() >= usedTiles) return;
  uint tile = usedTile[workgroupIndex()];
  uint begin = tileOffset[tile], n = tileOffset[tile + 1u] - begin;
  if (n <= 1u) return;
  uint id = gl_LocalInvocationIndex;
  if (n <= 256u) {
    // A short list, in nearly the order the chunks were numbered: one invocation's insertion sort
    // costs no barrier (at most 256 * 255 / 2 + 255 loop iterations: within llvmpipe's limit).
    if (id != 0u) return;
    for (uint i = begin + 1u; i < begin + n; ++i) {
      uint key = tileList[i];
      uvec2 m = tileMask[i];
      uint j = i;
      for (; j > begin && tileList[j - 1u] > key; --j) tileList[j] = tileList[j - 1u], tileMask[j] = tileMask[j - 1u];
      tileList[j] = key, tileMask[j] = m;
    }
    return;
  }
  uint size = 1u;
  while (size < n) size <<= 1;
  // The network's loops per invocation: log2(size) (log2(size) + 1) / 2 steps of size / 512
  // pairs each, and the copies; a list too long for llvmpipe's loop limit is not sorted.
  uint steps = uint(findMSB(size)) * uint(findMSB(size) + 1) / 2u;
  if (loopLimited != 0u && steps * (size / 512u + 2u) + 2u * (n / 256u + 1u) > 60000u) {
    if (id == 0u) atomicOr(truncated, kCutSort);
    return;
  }
  bool inShared = n <= kShared;
  if (inShared) {
    for (uint i = id; i < n; i += 256u) keys[i] = tileList[begin + i], masks[i] = tileMask[begin + i];
    memoryBarrierShared();
    barrier();
  }
  for (uint k = 2u; k <= size; k <<= 1) {
    for (uint j = k >> 1; j > 0u; j >>= 1) {
      for (uint i = id; i < size / 2u; i += 256u) {
        uint a, b;
        if (j == k >> 1) {  // the first step of a merge: each pair mirrored about the block's middle
          uint start = (i / j) * k, off = i % j;
          a = start + off, b = start + k - 1u - off;
        } else {
          a = (i / j) * 2u * j + (i % j), b = a + j;
        }
        if (b >= n) continue;
        if (inShared) {
          uint x = keys[a], y = keys[b];
          if (y < x) {
            keys[a] = y, keys[b] = x;
            uvec2 m = masks[a];
            masks[a] = masks[b], masks[b] = m;
          }
        } else {
          uint x = tileList[begin + a], y = tileList[begin + b];
          if (y < x) {
            tileList[begin + a] = y, tileList[begin + b] = x;
            uvec2 m = tileMask[begin + a];
            tileMask[begin + a] = tileMask[begin + b], tileMask[begin + b] = m;
          }
        }
      }
      memoryBarrierShared();
      memoryBarrierBuffer();
      barrier();
    }
  }
  if (inShared)
    for (uint i = id; i < n; i += 256u) tileList[begin + i] = keys[i], tileMask[begin + i] = masks[i];
}
)";

// The evaluation: CpuRasteriser's coverage and depth rules per pixel, the plain evaluation of
// every write and test in issue order. A dispatch takes at most segmentEntries entries of a tile's
// list (at most 65 loop iterations each); a longer list's tile saves its pixels' state for the
// next dispatch.
constexpr const char* kEvaluate = R"(
layout(local_size_x = kTile, local_size_y = kTile) in;
uniform uint segment;

// CpuRasteriser's blockCover for the piece's box inside 8x8 block (bx, by): 0 none, 1 partial,
// 2 whole; an edge at a time (written out, not looped: llvmpipe counts loop iterations).
int edgeCover(float A, float B, float C, float LO, float HI, float dxA, float dxB, float dyA,
              float dyB) {
  precise float ax = A * dxA, bx2 = A * dxB, ay = B * dyA, by2 = B * dyB;
  precise float fMin = C + fminOf(ax, bx2) + fminOf(ay, by2);
  precise float fMax = C + fmaxOf(ax, bx2) + fmaxOf(ay, by2);
  if (fMax < LO || fMin > HI) return 0;
  return fMin >= LO && fMax <= HI ? 2 : 1;
}
int blockCover(ivec4 box, vec4 A, vec4 B, vec4 C, vec4 LO, vec4 HI, int bx, int by) {
  precise float dxA = float(max(box.x, bx * 8) - box.x), dxB = float(min(box.z, bx * 8 + 7) - box.x);
  precise float dyA = float(max(box.y, by * 8) - box.y), dyB = float(min(box.w, by * 8 + 7) - box.y);
  int e0 = edgeCover(A.x, B.x, C.x, LO.x, HI.x, dxA, dxB, dyA, dyB);
  if (e0 == 0) return 0;
  int e1 = edgeCover(A.y, B.y, C.y, LO.y, HI.y, dxA, dxB, dyA, dyB);
  if (e1 == 0) return 0;
  int e2 = edgeCover(A.z, B.z, C.z, LO.z, HI.z, dxA, dxB, dyA, dyB);
  if (e2 == 0) return 0;
  return min(min(e0, e1), e2);
}

bool edgeInside(float A, float B, float C, float LO, float HI, float dx, float dy) {
  precise float f = mulAdd(A, dx, mulAdd(B, dy, C));
  return f >= LO && f <= HI;
}

// Whether piece `piece` (box `box`) covers pixel (x, y) as the cpu backend draws it, and its key
// there: small pieces every pixel of their box at their key bound, others by block cover and the
// SIMD loops' fused edge and depth functions.
bool pieceAt(uint piece, ivec4 box, int x, int y, bool test, bool conservative, out float key) {
  vec4 LO = pieceBound[piece].lo, HI = pieceBound[piece].hi;
  if (conservative && box.z - box.x < 3 && box.w - box.y < 3) {
    key = test ? HI.w : LO.w;
    return true;
  }
  vec4 A = pieceEdge[3u * piece], B = pieceEdge[3u * piece + 1u], C = pieceEdge[3u * piece + 2u];
  bool oneBlock = (box.x >> 3) == (box.z >> 3) && (box.y >> 3) == (box.w >> 3);
  int cover = test && oneBlock ? 1 : blockCover(box, A, B, C, LO, HI, x >> 3, y >> 3);
  precise float dx = float(x - box.x), dy = float(y - box.y);
  if (!oneBlock && cover == 0) return false;
  if ((test || cover != 2) && !(edgeInside(A.x, B.x, C.x, LO.x, HI.x, dx, dy) &&
                                 edgeInside(A.y, B.y, C.y, LO.y, HI.y, dx, dy) &&
                                 edgeInside(A.z, B.z, C.z, LO.z, HI.z, dx, dy)))
    return false;
  precise float z = mulAdd(A.w, dx, mulAdd(B.w, dy, C.w));
  key = min(max(z, LO.w), HI.w);
  return true;
}

void main() {
  if (workgroupIndex() >= usedTiles) return;
  uint tile = usedTile[workgroupIndex()];
  uint chain = 0u;
  while (chain + 1u < chainCount && chains[chain + 1u].firstTile <= tile) ++chain;
  Chain ch = chains[chain];
  uint local = tile - ch.firstTile;
  int x = int(local % uint(ch.tilesX)) * kTile + int(gl_LocalInvocationID.x);
  int y = int(local / uint(ch.tilesX)) * kTile + int(gl_LocalInvocationID.y);
  bool inside = x < ch.resolution && y < ch.resolution;
  bool oi = (ch.flags & kChainOrderIndependent) != 0u;
  uint planeSize = uint(ch.resolution) * uint(ch.resolution);
  uint pixel = uint(y) * uint(ch.resolution) + uint(x);
  // This dispatch's part of the tile's list: `segment`'s run of segmentEntries entries.
  uint begin = tileOffset[tile], end = tileOffset[tile + 1u];
  uint from = begin + segment * segmentEntries;
  if (from >= end) return;  // the tile was done by an earlier dispatch
  uint to = end - from > segmentEntries ? from + segmentEntries : end;
  uint lane = gl_LocalInvocationIndex;
  uint heavy = end - begin > segmentEntries ? 768u * tileHeavy[tile] : 0u;
  // The pixel's stored depth (a value, not a key) and an order-independent pass' planes.
  float value = ch.clearValue, others = ch.clearValue;
  uint object = kNoObject;
  if (segment != 0u) {
    value = uintBitsToFloat(heavyState[heavy + lane]);
    object = heavyState[heavy + 256u + lane];
    others = uintBitsToFloat(heavyState[heavy + 512u + lane]);
  } else if (inside && (ch.flags & kContinues) != 0u) {
    if (retainedIn[3u * planeSize + local] != 0u) {
      value = retainedInClear, others = retainedInClear;
    } else {
      value = uintBitsToFloat(retainedIn[pixel]);
      if (oi) object = retainedIn[planeSize + pixel], others = uintBitsToFloat(retainedIn[2u * planeSize + pixel]);
    }
  }
  uint tested = 0u, written = 0u;
  for (uint at = from; inside && at < to; ++at) {
    uint chunk = tileList[at];
    Chunk k = chunks[chunk];
    if (x < k.rect.x || x > k.rect.z || y < k.rect.y || y > k.rect.w) continue;
    bool test = (k.flags & kTest) != 0u;
    bool each = (k.flags & kAnswerEach) != 0u;
    bool conservative = (k.flags & kConservative) != 0u;
    float sign = (k.flags & kReversed) != 0u ? -1.0 : 1.0;
    if (test && !each && answers[k.answer] == 0u) continue;  // another pixel found it occluded
    uint perBox = conservative ? 6u : 12u;
    bool boxes = (k.flags & kBoxes) != 0u;
    // What a test of this chunk's object reads here.
    float storedKey = oi && object == k.object ? others : value * sign;
    uvec2 mask = tileMask[at];
    uint low = mask.x, high = mask.y;
    while ((low | high) != 0u) {
      uint s;
      if (low != 0u) {
        s = uint(findLSB(low));
        low &= low - 1u;
      } else {
        s = uint(findLSB(high)) + 32u;
        high &= high - 1u;
      }
      uint piece = chunk * kChunkSlots + s;
      ivec4 box = pieceBound[piece].box;
      if (x < box.x || x > box.z || y < box.y || y > box.w) continue;
      float key;
      if (!pieceAt(piece, box, x, y, test, conservative, key)) continue;
      if (test) {
        ++tested;
        if (key >= storedKey) {
          uint answer = !each ? k.answer : k.answer + (boxes ? s / perBox : s);
          atomicAnd(answers[answer], 0u);
          if (!each) break;
        }
      } else if (oi) {
        ++written;
        bool own = object == k.object;
        if (key < value) {
          if (!own) others = value, object = k.object;
          value = key;
        } else if (!own && key < others) {
          others = key;
        }
      } else {
        ++written;
        float stored = value * sign;
        if (key < stored) value = key * sign;
      }
    }
  }
  if (tested != 0u) atomicAdd(pixelsTested, tested);
  if (written != 0u) atomicAdd(pixelsWritten, written);
  if (to != end) {  // the next dispatch goes on from here
    heavyState[heavy + lane] = floatBitsToUint(value);
    heavyState[heavy + 256u + lane] = object;
    heavyState[heavy + 512u + lane] = floatBitsToUint(others);
    return;
  }
  // Every invocation has read the tile's flag before one marks it stored (the two buffers are one
  // when the chain goes on in the buffer it leaves).
  barrier();
  if ((ch.flags & kRetained) != 0u) retainedOut[3u * planeSize + local] = 0u;
  if (inside && (ch.flags & kRetained) != 0u) {
    retainedOut[pixel] = floatBitsToUint(value);
    if (oi) {
      retainedOut[planeSize + pixel] = object;
      retainedOut[2u * planeSize + pixel] = floatBitsToUint(others);
    }
  }
}
)";

}  // namespace

std::string setupShader(bool nativeFma) {
  return common("#define SCENE\n#define FETCH\n#define PIECES\n#define CHUNKS\n", nativeFma) + kSetup;
}
std::string binCountShader(bool nativeFma) {
  return common("#define CHAINS\n#define PIECES\n#define CHUNKS\n#define BINS\n", nativeFma) + kChunkTiles + kBinCount;
}
std::string binScanShader(bool nativeFma) {
  return common("#define BINS\n#define STATUS\n#define HEAVY\n", nativeFma) + kBinScan;
}
std::string binFillShader(bool nativeFma) {
  return common("#define CHAINS\n#define PIECES\n#define CHUNKS\n#define BINS\n#define STATUS\n", nativeFma) +
         kChunkTiles + kBinFill;
}
std::string binSortShader(bool nativeFma) {
  return common("#define BINS\n#define STATUS\n", nativeFma) + kBinSort;
}
std::string evaluateShader(bool nativeFma) {
  return common(
             "#define CHAINS\n#define PIECES\n#define CHUNKS\n#define BINS\n#define ANSWERS\n"
             "#define STATUS\n#define RETAINED\n#define HEAVY\n",
             nativeFma) +
         kEvaluate;
}

}  // namespace cdb::compute

namespace cdb::compute {

std::string fmaProbeShader(bool nativeFma) {
  return common("", nativeFma) + R"(
layout(local_size_x = 1) in;
layout(std430, binding = 0) buffer Probe { vec4 probe[]; };  // a, b, c in, a * b + c out in w
void main() {
  vec4 v = probe[gl_WorkGroupID.x];
  probe[gl_WorkGroupID.x].w = mulAdd(v.x, v.y, v.z);
}
)";
}

}  // namespace cdb::compute
