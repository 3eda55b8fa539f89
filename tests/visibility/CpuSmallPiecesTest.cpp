// Small triangles (smallBox: every pixel of a box of at most 3 x 3 at the key bound of step 1) on
// every SIMD target the machine runs: random writes and tests, in passes of both key orders and in
// an order-independent pass, against a model that writes and tests the same pixels one at a time.
// The depths left and the answers must be the model's, and they and the pixels counted the same on
// every target.
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "culling/visibility/cpu/CpuRasteriser.h"

namespace cdb::small_pieces_test {
namespace {

constexpr int kResolution = 64;  // the whole frame one window of 64 blocks

// The frame pixel by pixel: stored values, and in an order-independent pass each pixel's object
// and the others' nearest.
struct Model {
  std::vector<float> value, others;
  std::vector<std::uint32_t> object;
  explicit Model(float clear)
      : value(kResolution * kResolution, clear),
        others(kResolution * kResolution, clear),
        object(kResolution * kResolution, CpuDepthBuffer::kNoObject) {}
};

struct Box {
  int x0, y0, x1, y1;
  float zLo, zHi;
};

// The box and key bounds the set-up gives a piece (nothing when it has no pixel in the frame).
bool boxOf(const ScreenTriangle& t, const RasterPass& pass, RasterRole role, Box& box) {
  TriangleRaster r;
  if (!setupBounds(t, pass, role, r)) return false;
  EXPECT_TRUE(smallBox(pass, r));
  box = {r.x0, r.y0, r.x1, r.y1, r.zLo, r.zHi};
  return true;
}

void modelWrite(Model& m, const RasterPass& pass, const Box& b, std::uint32_t object) {
  const float v = pass.sign * b.zLo;
  for (int y = b.y0; y <= b.y1; ++y)
    for (int x = b.x0; x <= b.x1; ++x) {
      const std::size_t at = static_cast<std::size_t>(y) * kResolution + x;
      if (!pass.orderIndependent) {
        if (b.zLo < pass.sign * m.value[at]) m.value[at] = v;
      } else if (m.object[at] == object) {
        m.value[at] = std::min(m.value[at], v);
      } else if (v < m.value[at]) {
        m.others[at] = m.value[at], m.value[at] = v, m.object[at] = object;
      } else {
        m.others[at] = std::min(m.others[at], v);
      }
    }
}

// Whether the box has an occluded pixel; `pixels` counts those read up to it.
bool modelTest(const Model& m, const RasterPass& pass, const Box& b, std::uint32_t object,
               std::uint64_t& pixels) {
  for (int y = b.y0; y <= b.y1; ++y)
    for (int x = b.x0; x <= b.x1; ++x) {
      const std::size_t at = static_cast<std::size_t>(y) * kResolution + x;
      ++pixels;
      const float key =
          pass.orderIndependent && m.object[at] == object ? m.others[at] : pass.sign * m.value[at];
      if (b.zHi >= key) return true;
    }
  return false;
}

// A triangle inside a box of 2 x 2 pixels at a random place (across block borders too).
ScreenTriangle smallTriangle(std::mt19937& rng, const RasterPass& pass) {
  std::uniform_int_distribution<int> pixel(0, kResolution - 2);
  std::uniform_real_distribution<double> inside(0.05, 0.95), key(pass.keyLo, pass.keyHi);
  const int x = pixel(rng), y = pixel(rng);
  ScreenTriangle t;
  for (int v = 0; v < 3; ++v)
    t.x[v] = x + 0.5 + inside(rng), t.y[v] = y + 0.5 + inside(rng), t.k[v] = key(rng);
  return t;
}

struct Outcome {
  std::vector<std::uint8_t> visible;
  std::uint64_t pixelsTested = 0, pixelsWritten = 0;
  std::vector<float> depth;
  bool operator==(const Outcome&) const = default;
};

// Rounds of a few writes, then a batch of tests, by objects 0..3, with the buffer and the model
// side by side; every answer and the buffer's depths checked against the model's.
Outcome runPass(const RasterPass& pass, float clear, unsigned seed) {
  std::mt19937 rng(seed);
  CpuDepthBuffer buffer;
  buffer.place(kResolution, 0, 0, kResolution / 8, kResolution / 8, pass.orderIndependent);
  buffer.clear(clear);
  Model model(clear);
  Outcome out;
  std::uint64_t modelTested = 0;
  for (int round = 0; round < 60; ++round) {
    const auto object = static_cast<std::uint32_t>(round % 4);
    std::vector<ScreenTriangle> writes(1 + rng() % 6);
    for (ScreenTriangle& t : writes) t = smallTriangle(rng, pass);
    RasterWork work;
    writePieces<ScreenTriangle>(buffer, pass, writes, work, object);
    out.pixelsWritten += work.pixelsWritten;
    for (const ScreenTriangle& t : writes)
      if (Box b; boxOf(t, pass, RasterRole::Write, b)) modelWrite(model, pass, b, object);

    const auto tester = static_cast<std::uint32_t>((round + 1) % 4);
    std::vector<ScreenTriangle> tests(12);
    for (ScreenTriangle& t : tests) t = smallTriangle(rng, pass);
    std::vector<std::uint8_t> visible(tests.size(), 1);
    RasterWork tested;
    testEachTriangle(buffer, pass, tests, visible.data(), tested, tester);
    out.pixelsTested += tested.pixelsTested;
    for (std::size_t i = 0; i < tests.size(); ++i) {
      Box b;
      if (!boxOf(tests[i], pass, RasterRole::Test, b)) continue;
      const bool occluded = modelTest(model, pass, b, tester, modelTested);
      EXPECT_EQ(visible[i] == 0, occluded) << "round " << round << ", test " << i;
    }
    out.visible.insert(out.visible.end(), visible.begin(), visible.end());
  }
  for (int y = 0; y < kResolution; ++y)
    for (int x = 0; x < kResolution; ++x) {
      const float stored = buffer.at(x, y);
      EXPECT_EQ(stored, model.value[static_cast<std::size_t>(y) * kResolution + x])
          << "pixel " << x << ", " << y;
      out.depth.push_back(stored);
    }
  EXPECT_GT(modelTested, 0u);
  EXPECT_GT(out.pixelsTested, 0u);
  EXPECT_GT(out.pixelsWritten, 0u);
  return out;
}

struct PassCase {
  std::string name;
  RasterPass pass;
  float clear;
};

std::vector<PassCase> passCases() {
  RasterPass base;
  base.resolution = kResolution;
  base.conservative = true;
  RasterPass reversed = base;
  reversed.sign = -1.f, reversed.keyLo = -1.f, reversed.keyHi = 0.f;
  RasterPass independent = base;
  independent.orderIndependent = true;
  return {{"nearer is smaller", base, 1.f},
          {"nearer is larger", reversed, 0.f},
          {"order-independent", independent, 1.f}};
}

// Every target this build has and this machine runs.
std::vector<std::int64_t> targetsHere() { return hwy::SupportedAndGeneratedTargets(); }

TEST(CpuSmallPieces, MatchThePixelModelOnEverySimdTarget) {
  const std::vector<std::int64_t> targets = targetsHere();
  ASSERT_FALSE(targets.empty());
  for (const PassCase& c : passCases()) {
    std::vector<Outcome> outcomes;
    for (const std::int64_t target : targets) {
      hwy::SetSupportedTargetsForTest(target);
      SCOPED_TRACE(c.name + " on " + rasteriserTarget());
      outcomes.push_back(runPass(c.pass, c.clear, 7u));
    }
    hwy::SetSupportedTargetsForTest(0);
    for (std::size_t i = 1; i < outcomes.size(); ++i)
      EXPECT_TRUE(outcomes[i] == outcomes[0])
          << c.name << ": target " << hwy::TargetName(targets[i]) << " differs from "
          << hwy::TargetName(targets[0]);
  }
}

}  // namespace
}  // namespace cdb::small_pieces_test
