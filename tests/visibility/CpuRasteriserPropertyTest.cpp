// The CPU rasteriser's conservative guarantee against a brute-force reference in exact rational
// arithmetic (GMP): for random triangles (and box faces drawn as quads) at several resolutions
// (ordinary, sub-pixel, slivers, edge-on segments, points, vertices on pixel borders, partly
// off-screen), every pixel whose closed square the triangle meets is covered; a write stores at
// most the triangle's smallest depth over that part of the square, and a test uses at least its
// largest. Run with no depth epsilon and no margin, so the bounds hold by themselves; and coverage
// stays within a thousandth of a pixel of the exact one (small triangles: within their pixel box).
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "culling/visibility/cpu/CpuDepthBuffer.h"
#include "culling/visibility/cpu/CpuRasteriser.h"
#include "culling/visibility/cpu/CpuTriangleSetup.h"
#include "tests/common/RandomCases.h"

namespace cdb {
namespace {

// Points (u, v) of the triangle's parameter space: vertex 0 + u (v1 - v0) + v (v2 - v0).
using Param = std::array<mpq_class, 2>;

struct ExactBounds {
  mpq_class minKey, maxKey;
};

// The part of the (possibly edge-on or degenerate) triangle whose screen projection lies in the
// square [x0, x1] x [y0, y1]: the parameter triangle clipped by four half-planes that are linear
// in (u, v) (Sutherland-Hodgman, exact). The key is linear in (u, v) too, so its extremes over
// that part are at the clipped polygon's vertices. Empty: the triangle misses the square.
std::optional<ExactBounds> exactOverSquare(const ScreenTriangle& t, const mpq_class& x0,
                                           const mpq_class& x1, const mpq_class& y0,
                                           const mpq_class& y1) {
  const mpq_class ax = t.x[0], ux = mpq_class(t.x[1]) - ax, vx = mpq_class(t.x[2]) - ax;
  const mpq_class ay = t.y[0], uy = mpq_class(t.y[1]) - ay, vy = mpq_class(t.y[2]) - ay;
  std::vector<Param> poly = {{0, 0}, {1, 0}, {0, 1}};
  // Keep c0 + cu u + cv v >= 0.
  const auto clip = [&](const mpq_class& c0, const mpq_class& cu, const mpq_class& cv) {
    std::vector<Param> out;
    const std::size_t n = poly.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Param& p = poly[i];
      const Param& q = poly[(i + 1) % n];
      const mpq_class fp = c0 + cu * p[0] + cv * p[1];
      const mpq_class fq = c0 + cu * q[0] + cv * q[1];
      if (fp >= 0) out.push_back(p);
      if ((fp >= 0) != (fq >= 0)) {
        const mpq_class s = fp / (fp - fq);
        out.push_back({p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1])});
      }
    }
    poly = std::move(out);
  };
  clip(ax - x0, ux, vx);    // x >= x0
  clip(x1 - ax, -ux, -vx);  // x <= x1
  clip(ay - y0, uy, vy);
  clip(y1 - ay, -uy, -vy);
  if (poly.empty()) return std::nullopt;
  const mpq_class k0 = t.k[0], ku = mpq_class(t.k[1]) - k0, kv = mpq_class(t.k[2]) - k0;
  ExactBounds b{k0 + ku * poly[0][0] + kv * poly[0][1], 0};
  b.maxKey = b.minKey;
  for (const Param& p : poly) {
    const mpq_class k = k0 + ku * p[0] + kv * p[1];
    if (k < b.minKey) b.minKey = k;
    if (k > b.maxKey) b.maxKey = k;
  }
  return b;
}

// A quad (a box face) is what GL draws of it: its two triangles (0, 1, 2) and (0, 2, 3).
std::optional<ExactBounds> exactOverSquare(const ScreenQuad& q, const mpq_class& x0,
                                           const mpq_class& x1, const mpq_class& y0,
                                           const mpq_class& y1) {
  std::optional<ExactBounds> both;
  for (const std::array<int, 3>& corners : {std::array<int, 3>{0, 1, 2}, {0, 2, 3}}) {
    ScreenTriangle t{};
    for (int v = 0; v < 3; ++v)
      t.x[v] = q.x[corners[v]], t.y[v] = q.y[corners[v]], t.k[v] = q.k[corners[v]];
    const auto part = exactOverSquare(t, x0, x1, y0, y1);
    if (!part) continue;
    if (!both) {
      both = part;
      continue;
    }
    if (part->minKey < both->minKey) both->minKey = part->minKey;
    if (part->maxKey > both->maxKey) both->maxKey = part->maxKey;
  }
  return both;
}

enum class Shape { Ordinary, SubPixel, Sliver, EdgeOn, Point, OnBorders, Large };

class TriangleMaker {
 public:
  explicit TriangleMaker(unsigned seed) : rng_(seed) {}

  ScreenTriangle make(Shape shape, int resolution) {
    // Centres anywhere on the buffer and a little beyond it (partly off-screen triangles).
    const double cx = u(-4, resolution + 4), cy = u(-4, resolution + 4);
    ScreenTriangle t{};
    const auto around = [&](double size) {
      for (int i = 0; i < 3; ++i) t.x[i] = cx + u(-size, size), t.y[i] = cy + u(-size, size);
    };
    switch (shape) {
      case Shape::Ordinary:
        around(std::exp(u(std::log(0.5), std::log(12.0))));
        break;
      case Shape::Large:
        around(std::exp(u(std::log(12.0), std::log(40.0))));
        break;
      case Shape::SubPixel:
        around(std::exp(u(std::log(0.005), std::log(0.6))));
        break;
      case Shape::Sliver: {
        const double angle = u(0, 6.283185307179586), length = u(2, 25);
        const double width = std::exp(u(std::log(1e-5), std::log(0.05)));
        const double dx = std::cos(angle), dy = std::sin(angle);
        t.x[0] = cx - dx * length / 2, t.y[0] = cy - dy * length / 2;
        t.x[1] = cx + dx * length / 2, t.y[1] = cy + dy * length / 2;
        const double along = u(-0.5, 0.5) * length;
        t.x[2] = cx + dx * along - dy * width, t.y[2] = cy + dy * along + dx * width;
        break;
      }
      case Shape::EdgeOn: {
        // Exactly collinear in screen: dyadic coordinates and a midpoint, or an axis-aligned
        // segment (both are exact in double).
        const double ex = dyadic(u(-10, 10)), ey = dyadic(u(-10, 10));
        t.x[0] = dyadic(cx), t.y[0] = dyadic(cy);
        t.x[1] = t.x[0] + ex, t.y[1] = t.y[0] + (u(0, 1) < 0.3 ? 0.0 : ey);
        const double s = u(0, 1) < 0.5 ? 0.5 : 0.25;
        t.x[2] = t.x[0] + s * (t.x[1] - t.x[0]), t.y[2] = t.y[0] + s * (t.y[1] - t.y[0]);
        break;
      }
      case Shape::Point:
        t.x[0] = t.x[1] = t.x[2] = u(0, 1) < 0.5 ? std::round(cx) : cx;
        t.y[0] = t.y[1] = t.y[2] = u(0, 1) < 0.5 ? std::round(cy) : cy;
        break;
      case Shape::OnBorders:
        // Vertices on pixel corners and borders: the closed-square rule decides.
        for (int i = 0; i < 3; ++i) {
          t.x[i] = std::round(cx + u(-6, 6)) + (u(0, 1) < 0.5 ? 0.0 : 0.5);
          t.y[i] = std::round(cy + u(-6, 6));
        }
        break;
    }
    for (int i = 0; i < 3; ++i) t.k[i] = u(0.05, 0.95);
    if (shape == Shape::Point || u(0, 1) < 0.1)  // face-on: one depth
      t.k[1] = t.k[2] = t.k[0];
    return t;
  }

 private:
  double u(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  static double dyadic(double v) { return std::round(v * 1024.0) / 1024.0; }
  std::mt19937 rng_;
};

// Box faces as the CPU backend draws them: parallelograms corner, corner + e1, corner + e1 + e2,
// corner + e2, each corner computed in double (so a little off a parallelogram), keys linear.
class QuadMaker {
 public:
  explicit QuadMaker(unsigned seed) : triangles_(seed), rng_(seed + 1u) {}

  ScreenQuad make(Shape shape, int resolution) {
    // Two edges from a triangle of the shape: its vertex 0 and the edges to vertices 1 and 2
    // (an edge-on triangle gives a collapsed face, a point a point).
    const ScreenTriangle t = triangles_.make(shape, resolution);
    ScreenQuad q{};
    const double e1x = t.x[1] - t.x[0], e1y = t.y[1] - t.y[0], e1k = t.k[1] - t.k[0];
    const double e2x = t.x[2] - t.x[0], e2y = t.y[2] - t.y[0], e2k = t.k[2] - t.k[0];
    // Keys that stay in [0.05, 0.95]: halve both depth edges.
    const double k0 = std::clamp(t.k[0], 0.3, 0.7);
    const double ks[4] = {k0, k0 + e1k / 4, k0 + e1k / 4 + e2k / 4, k0 + e2k / 4};
    const double xs[4] = {t.x[0], t.x[0] + e1x, t.x[0] + e1x + e2x, t.x[0] + e2x};
    const double ys[4] = {t.y[0], t.y[0] + e1y, t.y[0] + e1y + e2y, t.y[0] + e2y};
    for (int v = 0; v < 4; ++v) q.x[v] = xs[v], q.y[v] = ys[v], q.k[v] = ks[v];
    // Sometimes a far corner off by a few units in the last place, as transforms round.
    if (std::uniform_real_distribution<double>(0, 1)(rng_) < 0.3) {
      q.x[2] = std::nextafter(q.x[2], q.x[2] + 1.0);
      q.k[2] = std::nextafter(q.k[2], 0.0);
    }
    return q;
  }

 private:
  TriangleMaker triangles_;
  std::mt19937 rng_;
};

constexpr float kFar = 2.f;  // beyond every key: untouched pixels never occlude

struct Window {
  int x0, y0, x1, y1;
};
template <class Piece>
Window windowOf(const Piece& t, int resolution) {
  const double minX = *std::min_element(t.x, t.x + Piece::kVertices);
  const double maxX = *std::max_element(t.x, t.x + Piece::kVertices);
  const double minY = *std::min_element(t.y, t.y + Piece::kVertices);
  const double maxY = *std::max_element(t.y, t.y + Piece::kVertices);
  return {std::max(0, static_cast<int>(std::floor(minX)) - 2),
          std::max(0, static_cast<int>(std::floor(minY)) - 2),
          std::min(resolution - 1, static_cast<int>(std::floor(maxX)) + 2),
          std::min(resolution - 1, static_cast<int>(std::floor(maxY)) + 2)};
}

void setPixel(CpuDepthBuffer& buffer, int x, int y, float value) {
  const std::size_t index = buffer.blockIndex(x / 8, y / 8);
  buffer.materialise(index);
  buffer.block(index)[(y % 8) * 8 + x % 8] = value;
  buffer.blockMin(index) = std::min(buffer.blockMin(index), value);
  buffer.blockMax(index) = std::max(buffer.blockMax(index), value);
}

// The smallest float not below q.
float floatAtLeast(const mpq_class& q) {
  float f = static_cast<float>(q.get_d());
  while (mpq_class(f) < q) f = std::nextafter(f, 10.f);
  while (mpq_class(std::nextafter(f, -10.f)) >= q) f = std::nextafter(f, -10.f);
  return f;
}

struct Tally {
  int triangles = 0, coveredPixels = 0, testPixels = 0;
};

void writePiece(CpuDepthBuffer& buffer, const RasterPass& pass, const ScreenTriangle& t,
                RasterWork& work) {
  writePieces(buffer, pass, std::span<const ScreenTriangle>(&t, 1), work);
}
void writePiece(CpuDepthBuffer& buffer, const RasterPass& pass, const ScreenQuad& q,
                RasterWork& work) {
  writePieces(buffer, pass, std::span<const ScreenQuad>(&q, 1), work);
}
bool testFindsOccluded(CpuDepthBuffer& buffer, const RasterPass& pass, const ScreenTriangle& t,
                       RasterWork& work) {
  return testTrianglesUntilOccluded(buffer, pass, std::span<const ScreenTriangle>(&t, 1), work) ==
         0u;
}
bool testFindsOccluded(CpuDepthBuffer& buffer, const RasterPass& pass, const ScreenQuad& q,
                       RasterWork& work) {
  return testQuadsUntilOccluded(buffer, pass, std::span<const ScreenQuad>(&q, 1), work) == 0u;
}

// Checks one piece (a triangle or a quad) at one resolution in a pass with sign +1 (or -1: keys
// negated).
template <class Piece>
void checkPiece(Piece t, int resolution, float sign, Tally& tally) {
  RasterPass pass;
  pass.resolution = resolution;
  pass.sign = sign;
  pass.keyLo = sign > 0 ? 0.f : -1.f;
  pass.keyHi = sign > 0 ? 1.f : 0.f;
  if (sign < 0)
    for (double& k : t.k) k -= 1.0;  // keys of a reversed pass: -stored, in [-1, 0]
  pass.depthEpsilon = 0.0;           // no help: the bounds must hold by construction
  pass.marginPx = 0.0;
  pass.conservative = true;
  const float farKey = kFar;  // in both orders
  const float farStored = sign * farKey;
  const Window w = windowOf(t, resolution);
  CpuDepthBuffer buffer;
  buffer.place(resolution, 0, 0, (resolution + 7) / 8, (resolution + 7) / 8);
  RasterWork work;

  // The pixel box, and whether the rasteriser takes all of it (smallBox).
  TriangleRaster box;
  const bool small = setupBounds(t, pass, RasterRole::Write, box) && smallBox(pass, box);

  // Write: every exactly covered pixel holds at most the exact nearest key.
  buffer.clear(farStored);
  writePiece(buffer, pass, t, work);
  ++tally.triangles;
  for (int y = w.y0; y <= w.y1; ++y) {
    for (int x = w.x0; x <= w.x1; ++x) {
      const float key = sign * buffer.at(x, y);
      const auto exact = exactOverSquare(t, x, x + 1, y, y + 1);
      if (exact) {
        ++tally.coveredPixels;
        ASSERT_LT(key, farKey) << "write missed pixel (" << x << ", " << y << ") at " << resolution;
        ASSERT_LE(mpq_class(key), exact->minKey)
            << "write stored a key farther than the triangle's nearest at (" << x << ", " << y
            << ")";
      } else if (key < farKey) {
        // A small triangle may cover its whole pixel box (smallBox); any other pixel it covers
        // is within a thousandth of a pixel of it.
        if (small && x >= box.x0 && x <= box.x1 && y >= box.y0 && y <= box.y1) continue;
        const mpq_class g(1, 1000);
        ASSERT_TRUE(exactOverSquare(t, x - g, x + 1 + g, y - g, y + 1 + g))
            << "write covered pixel (" << x << ", " << y << ") far from the triangle";
      }
    }
  }

  // Test: at each exactly covered pixel, a stored key equal to the exact farthest key over the
  // covered part (rounded up to a float) is found "at or behind", so the test reports occluded.
  for (int y = w.y0; y <= w.y1; ++y) {
    for (int x = w.x0; x <= w.x1; ++x) {
      const auto exact = exactOverSquare(t, x, x + 1, y, y + 1);
      if (!exact) continue;
      ++tally.testPixels;
      buffer.clear(farStored);
      const float storedKey = std::clamp(floatAtLeast(exact->maxKey), pass.keyLo, pass.keyHi);
      setPixel(buffer, x, y, sign * storedKey);
      ASSERT_TRUE(testFindsOccluded(buffer, pass, t, work))
          << "test used a key nearer than the triangle's farthest at (" << x << ", " << y << ") at "
          << resolution;
    }
  }
}

struct ShapeCase {
  Shape shape;
  const char* name;
  int count;
};
const ShapeCase kShapes[] = {
    {Shape::Ordinary, "ordinary", 60}, {Shape::SubPixel, "sub-pixel", 80},
    {Shape::Sliver, "sliver", 40},     {Shape::EdgeOn, "edge-on", 40},
    {Shape::Point, "point", 30},       {Shape::OnBorders, "on borders", 40},
    {Shape::Large, "large", 6}};

class CpuRasteriserProperty : public testing::TestWithParam<int> {
 protected:
  // Every shape at both signs, pieces from `Maker` (TriangleMaker or QuadMaker) seeded from
  // `seedFactor`.
  template <class Maker>
  void checkEveryShape(unsigned seedFactor, const char* piece) {
    const int resolution = GetParam();
    for (float sign : {1.f, -1.f}) {
      for (const ShapeCase& s : kShapes) {
        Maker maker(seedFactor * resolution + static_cast<unsigned>(s.shape) +
                    (sign < 0 ? 7u : 0u));
        Tally tally;
        for (int i = 0; i < test::randomCases(s.count); ++i) {
          checkPiece(maker.make(s.shape, resolution), resolution, sign, tally);
          if (HasFatalFailure()) {
            ADD_FAILURE() << s.name << " " << piece << " " << i << ", sign " << sign;
            return;
          }
        }
        EXPECT_GT(tally.coveredPixels, 0) << s.name;
      }
    }
  }
};

TEST_P(CpuRasteriserProperty, CoversEveryTouchedPixelWithSafeDepths) {
  checkEveryShape<TriangleMaker>(17u, "triangle");
}

// The same guarantee for box faces drawn as quads (their reference: the face's two triangles).
TEST_P(CpuRasteriserProperty, QuadsCoverEveryTouchedPixelWithSafeDepths) {
  checkEveryShape<QuadMaker>(29u, "quad");
}

// Named by resolution (not by index), so that a gtest filter and ctest (which shows the value)
// agree.
INSTANTIATE_TEST_SUITE_P(Resolutions, CpuRasteriserProperty, testing::Values(64, 256, 800),
                         [](const auto& param) { return std::to_string(param.param); });

}  // namespace
}  // namespace cdb
