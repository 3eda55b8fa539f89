// `cdbench snapshot` end to end on env3 with 50 tori at frame 46 (one contact, README "CI
// regression check"), replaying the poses `cdbench run` recorded (the object count read from the
// recording): the picture decodes at the size asked for, says what the run measured on that
// frame, each set's colour lies on its own objects (pixel counts per colour inside and outside the
// objects' boxes), pruned objects are grey, the colliding pair is outlined, and the same command
// writes the same bytes. Then a short sequence and its animation, a picture without a strategy,
// and the pieces that parse options and lay out the legend.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/Errors.h"
#include "harness/snapshot/SnapshotColouring.h"
#include "harness/snapshot/SnapshotLegend.h"
#include "harness/snapshot/SnapshotOptions.h"
#include "harness/snapshot/SnapshotPicture.h"
#include "harness/tables/FrameCsv.h"
#include "render/ImageText.h"
#include "scenes/ProceduralMeshes.h"
#include "tests/common/FreshTempDir.h"
#include "tests/common/PngImage.h"
#include "tests/common/ShellCommand.h"

namespace cdb {
namespace {

using test::runShellCommand;

const std::string kSnapshotConfig = std::string(CDBENCH_SOURCE_DIR) + "/configs/env3.yaml";
constexpr int kSnapshotFrame = 46;

test::CommandResult cdbenchCli(const std::string& args) {
  return runShellCommand(std::string(CDBENCH_BINARY_DIR) + "/cdbench " + args + " 2>&1");
}

std::string snapshotFileText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

nlohmann::json snapshotJsonOf(const std::filesystem::path& file) {
  return nlohmann::json::parse(snapshotFileText(file));
}

// The palette entry (or grey, kSetPaletteSize) a pixel's colour is a shade of: its colour divided
// by its brightest channel against each entry's, nearest within `tolerance`; none for dark pixels,
// the background's near-white and what lies between two entries.
std::optional<std::size_t> shadeOf(Rgb p, double tolerance = 0.12) {
  const int top = std::max({p.r, p.g, p.b});
  if (top < 45 || (p.r > 215 && p.g > 215 && p.b > 215)) return std::nullopt;
  const auto norm = [](Rgb c) {
    const double m = std::max({c.r, c.g, c.b});
    return std::array<double, 3>{c.r / m, c.g / m, c.b / m};
  };
  const auto q = norm(p);
  std::optional<std::size_t> best;
  double bestDistance = tolerance;
  for (std::size_t k = 0; k <= kSetPaletteSize; ++k) {
    const auto c = norm(k < kSetPaletteSize ? kSetPalette[k] : kPrunedColour);
    const double d = std::hypot(q[0] - c[0], q[1] - c[1], q[2] - c[2]);
    if (d < bestDistance) bestDistance = d, best = k;
  }
  return best;
}

struct PixelBox {
  double x0, y0, x1, y1;
  bool contains(int x, int y, double grow = 0) const {
    return x + 0.5 >= x0 - grow && x + 0.5 <= x1 + grow && y + 0.5 >= y0 - grow &&
           y + 0.5 <= y1 + grow;
  }
};

class Snapshot : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::filesystem::path(test::freshTempDir("snapshot"));
    // The run measures the frame and records the poses; the pictures replay them.
    const auto recording = *dir_ / "env3-50.poses";
    const auto run = cdbenchCli("run " + kSnapshotConfig + " --objects 50 --frames " +
                                std::to_string(kSnapshotFrame + 1) + " --frame-stride " +
                                std::to_string(kSnapshotFrame) +
                                " --strategies ours --resolutions 256 --repeats 1 --quiet --out " +
                                (*dir_ / "run").string() + " --record " + recording.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const std::string common = "snapshot " + kSnapshotConfig + " --replay " + recording.string() +
                               " --frame " + std::to_string(kSnapshotFrame) +
                               " --strategy ours --resolution 256 --size 640x480 --out ";
    for (const char* name : {"a.png", "b.png"}) {
      const auto r = cdbenchCli(common + (*dir_ / name).string());
      ASSERT_EQ(r.exitCode, 0) << r.output;
    }
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    std::filesystem::remove_all(*dir_, ec);
    delete dir_;
  }
  void SetUp() override {
    const auto png = test::readPng(*dir_ / "a.png");
    ASSERT_TRUE(png.error.empty()) << png.error;
    image = png.image;
    json = snapshotJsonOf(*dir_ / "a.json");
    sceneHeight = json["scene_height"].get<int>();
    for (const auto& o : json["objects"]) {
      const auto& b = o["pixel_box"];
      boxes.push_back(
          {b[0].get<double>(), b[1].get<double>(), b[2].get<double>(), b[3].get<double>()});
    }
    classifyShades();
  }

  // Per pixel of the scene area (above the legend): the palette entry it is a shade of, as are its
  // four neighbours (where two objects meet, the filtered colour may pass for a third); else none.
  void classifyShades() {
    std::vector<std::optional<std::size_t>> raw(static_cast<std::size_t>(image.width) *
                                                sceneHeight);
    for (int y = 0; y < sceneHeight; ++y)
      for (int x = 0; x < image.width; ++x) raw[y * image.width + x] = shadeOf(image.at(x, y));
    shades.assign(raw.size(), std::nullopt);
    for (int y = 1; y + 1 < sceneHeight; ++y) {
      for (int x = 1; x + 1 < image.width; ++x) {
        const auto s = raw[y * image.width + x];
        if (s && raw[y * image.width + x - 1] == s && raw[y * image.width + x + 1] == s &&
            raw[(y - 1) * image.width + x] == s && raw[(y + 1) * image.width + x] == s)
          shades[y * image.width + x] = s;
      }
    }
  }
  std::optional<std::size_t> shadeAt(int x, int y) const { return shades[y * image.width + x]; }

  // Pixels of palette entry `shade`, split by whether they lie in the box of one of `objects`.
  std::pair<int, int> countShade(std::size_t shade, const std::vector<std::size_t>& objects,
                                 double grow = 1) const {
    int inside = 0, outside = 0;
    for (int y = 0; y < sceneHeight; ++y) {
      for (int x = 0; x < image.width; ++x) {
        if (shadeAt(x, y) != shade) continue;
        bool in = false;
        for (std::size_t o : objects) in = in || boxes[o].contains(x, y, grow);
        ++(in ? inside : outside);
      }
    }
    return {inside, outside};
  }

  std::vector<std::optional<std::size_t>> shades;
  static std::filesystem::path* dir_;
  RgbImage image;
  nlohmann::json json;
  int sceneHeight = 0;
  std::vector<PixelBox> boxes;
};

std::filesystem::path* Snapshot::dir_ = nullptr;

TEST_F(Snapshot, DecodesAtTheSizeAskedForWithTheLegendUnderTheScene) {
  EXPECT_EQ(image.width, 640);
  EXPECT_EQ(image.height, 480);
  EXPECT_EQ(json["width"], 640);
  EXPECT_EQ(json["height"], 480);
  EXPECT_GT(sceneHeight, 300);
  EXPECT_LT(sceneHeight, 480);
  EXPECT_EQ(json["frame"], kSnapshotFrame);
  EXPECT_EQ(json["object_count"], 50);
  EXPECT_EQ(json["strategy"], "ours");
  EXPECT_EQ(json["visibility"], "cpu");
  EXPECT_EQ(json["resolution"], 256);
  EXPECT_FALSE(json["gl_renderer"].get<std::string>().empty());
  // The legend's text: dark glyph pixels below the scene, a swatch of the first set's colour.
  int glyphs = 0, swatch = 0;
  for (int y = sceneHeight; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const Rgb p = image.at(x, y);
      glyphs += p == Rgb{30, 30, 30} ? 1 : 0;
      swatch += p == kSetPalette[0] ? 1 : 0;
    }
  }
  EXPECT_GT(glyphs, 500);
  EXPECT_GT(swatch, 30);
}

TEST_F(Snapshot, TheSameCommandWritesTheSameBytes) {
  const std::string a = snapshotFileText(*dir_ / "a.png"), b = snapshotFileText(*dir_ / "b.png");
  ASSERT_FALSE(a.empty());
  EXPECT_TRUE(a == b) << "two runs of the same command gave different pictures";
}

TEST_F(Snapshot, SaysWhatTheRunMeasuresOnThatFrame) {
  const auto rows = readFrameCsv(*dir_ / "run" / "frames.csv");
  const FrameRecord* row = nullptr;
  for (const auto& r : rows) row = r.frame == kSnapshotFrame ? &r : row;
  ASSERT_NE(row, nullptr);
  ASSERT_GE(row->truthPairs, 1u) << "the frame was chosen for its contact";
  EXPECT_EQ(json["sets"].size(), row->sets);
  EXPECT_EQ(json["pcs_size"].get<std::uint64_t>(), row->pcsSize);
  EXPECT_EQ(json["colliding_pairs"].size(), row->collidingPairs);
  EXPECT_EQ(json["colliding_pairs"].size(), row->truthPairs);
  std::size_t members = 0;
  for (const auto& s : json["sets"]) members += s["members"].size();
  EXPECT_EQ(members, row->pcsSize);
}

TEST_F(Snapshot, EachSetsColourLiesOnItsOwnObjects) {
  const auto& sets = json["sets"];
  ASSERT_GE(sets.size(), 2u) << "a frame with several sets tests more";
  ASSERT_LE(sets.size(), kSetPaletteSize) << "colours would repeat";
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const auto colour = sets[k]["colour"];
    EXPECT_EQ((Rgb{colour[0], colour[1], colour[2]}), setColour(k));
    std::vector<std::size_t> members;
    for (const auto& m : sets[k]["members"]) {
      members.push_back(m.get<std::size_t>());
      EXPECT_EQ(json["objects"][m.get<std::size_t>()]["set"], k + 1);
    }
    const auto [inside, outside] = countShade(k, members);
    SCOPED_TRACE("set " + std::to_string(k + 1));
    // Visible unless hidden behind other objects; where it shows, it is in its members' boxes.
    EXPECT_GT(inside, 20);
    EXPECT_LE(outside, 3 + inside / 50);
  }
}

TEST_F(Snapshot, PrunedObjectsAreGrey) {
  std::vector<std::size_t> pruned, inSets;
  for (const auto& o : json["objects"]) (o["set"].is_null() ? pruned : inSets).push_back(o["id"]);
  ASSERT_FALSE(pruned.empty());
  const auto [inside, outside] = countShade(kSetPaletteSize, pruned);
  EXPECT_GT(inside, 50 * static_cast<int>(pruned.size()) / 2);
  EXPECT_LE(outside, 3 + inside / 50);
  // No set colour on a pruned object that no member's box overlaps.
  for (std::size_t o : pruned) {
    bool overlapped = false;
    for (std::size_t m : inSets)
      overlapped = overlapped || !(boxes[m].x1 < boxes[o].x0 || boxes[o].x1 < boxes[m].x0 ||
                                   boxes[m].y1 < boxes[o].y0 || boxes[o].y1 < boxes[m].y0);
    if (overlapped) continue;
    const PixelBox& b = boxes[o];
    for (int y = std::max(0, static_cast<int>(b.y0));
         y < std::min(sceneHeight, static_cast<int>(b.y1) + 1); ++y)
      for (int x = std::max(0, static_cast<int>(b.x0));
           x < std::min(image.width, static_cast<int>(b.x1) + 1); ++x)
        EXPECT_FALSE(shadeAt(x, y) && *shadeAt(x, y) < kSetPaletteSize)
            << "object " << o << " at " << x << "," << y;
  }
}

TEST_F(Snapshot, CollidingObjectsAreOutlined) {
  std::vector<std::size_t> colliding, others;
  for (const auto& o : json["objects"])
    (o["colliding"].get<bool>() ? colliding : others).push_back(o["id"]);
  ASSERT_EQ(colliding.size(), 2u * json["colliding_pairs"].size());
  const auto isOutline = [](Rgb p) { return p.r <= 18 && p.g <= 18 && p.b <= 18; };
  int near = 0, far = 0;
  for (int y = 0; y < sceneHeight; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (!isOutline(image.at(x, y))) continue;
      bool byColliding = false;
      for (std::size_t o : colliding) byColliding = byColliding || boxes[o].contains(x, y, 3);
      ++(byColliding ? near : far);
    }
  }
  EXPECT_GT(near, 20);
  EXPECT_EQ(far, 0);
}

TEST(SnapshotCommand, ASequenceWritesNumberedPicturesAndAnAnimatedGif) {
  const auto dir = test::freshTempDir("snapshot_sequence");
  const auto r = cdbenchCli("snapshot " + kSnapshotConfig +
                            " --objects 20 --frames 40:50:5 --strategy cis --resolution 64 "
                            "--size 320x240 --out " +
                            (dir / "seq.gif").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* name : {"frame-0040", "frame-0045"}) {
    const auto png = test::readPng(dir / "seq-frames" / (std::string(name) + ".png"));
    EXPECT_TRUE(png.error.empty()) << name << ": " << png.error;
    EXPECT_EQ(png.image.width, 320);
    EXPECT_EQ(snapshotJsonOf(dir / "seq-frames" / (std::string(name) + ".json"))["strategy"],
              "cis");
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "seq-frames" / "frame-0050.png")) << "B is excluded";
  const std::string gif = snapshotFileText(dir / "seq.gif");
  EXPECT_EQ(gif.substr(0, 6), "GIF89a");
  // Nothing else is left (no temporary file): two pictures, their JSONs, the GIF and the two
  // folders.
  EXPECT_EQ(std::filesystem::remove_all(dir), 7u);
}

TEST(SnapshotCommand, WithoutAStrategyTheGroundTruthsPairsAreOutlined) {
  const auto dir = test::freshTempDir("snapshot_plain");
  const auto r = cdbenchCli("snapshot " + kSnapshotConfig + " --objects 50 --frame " +
                            std::to_string(kSnapshotFrame) + " --view z --size 320x240 --out " +
                            (dir / "plain.png").string());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto json = snapshotJsonOf(dir / "plain.json");
  EXPECT_TRUE(json["strategy"].is_null());
  EXPECT_TRUE(json["sets"].is_null());
  EXPECT_EQ(json["colliding_pairs_by"], "ground truth");
  EXPECT_EQ(json["view"], "z");
  EXPECT_GE(json["colliding_pairs"].size(), 1u);
  for (const auto& o : json["objects"]) EXPECT_TRUE(o["set"].is_null());
  std::filesystem::remove_all(dir);
}

TEST(SnapshotOptions, SizesAndFrameRanges) {
  const PictureSize s = parsePictureSize("960x720");
  EXPECT_EQ(s.width, 960);
  EXPECT_EQ(s.height, 720);
  for (const char* bad :
       {"0x300", "100000x300", "960", "960x", "x720", "-960x720", "960x720x3", "96ax720"})
    EXPECT_THROW((void)parsePictureSize(bad), InputError) << bad;
  EXPECT_EQ(parseFrameRange("0:300:10").frames().size(), 30u);
  EXPECT_EQ(parseFrameRange("5:6:1").frames(), std::vector<int>{5});
  EXPECT_EQ(parseFrameRange("10:31:10").frames(), (std::vector<int>{10, 20, 30}));
  for (const char* bad : {"10:10:1", "10:5:1", "0:10:0", "0:10", "a:b:c", "-1:10:1", "0:10:1:2"})
    EXPECT_THROW((void)parseFrameRange(bad), InputError) << bad;
}

TEST(SnapshotLegend, SwatchesThatDoNotFitAreSummedUp) {
  LegendContent content;
  content.lines = {"a line", "another line"};
  for (int k = 0; k < 60; ++k)
    content.swatches.push_back({setColour(k), "set " + std::to_string(k + 1) + ": 2"});
  const int height = legendBandHeight(400);
  const LegendLayout layout = layoutLegend(content, 400, height);
  EXPECT_EQ(layout.lines.size(), 2u);
  ASSERT_GE(layout.swatches.size(), 2u);
  ASSERT_LT(layout.swatches.size(), 60u);
  const auto& last = layout.swatches.back();
  EXPECT_EQ(last.swatch.style, LegendSwatch::Style::None);
  EXPECT_EQ(last.swatch.label, "+" + std::to_string(60 - (layout.swatches.size() - 1)) + " more");
  for (const auto& p : layout.swatches) {
    EXPECT_GE(p.x, 0);
    EXPECT_LE(p.y + textLineHeight(1), height);  // 400 pixels wide: glyphs at scale 1
  }
  // Few swatches: all of them, no summary.
  content.swatches.resize(3);
  EXPECT_EQ(layoutLegend(content, 400, height).swatches.size(), 3u);
}

TEST(SnapshotLegend, LongLinesWrapAfterASpace) {
  LegendContent content;
  content.lines = {"cullide_bvh on env2, frame 150: 14 objects; gl-queries backend at 1200 px"};
  const LegendLayout wide = layoutLegend(content, 960, legendBandHeight(960));
  ASSERT_EQ(wide.lines.size(), 1u);
  EXPECT_EQ(wide.lines[0].second, content.lines[0]);
  const LegendLayout narrow = layoutLegend(content, 720, legendBandHeight(720));
  ASSERT_EQ(narrow.lines.size(), 2u);
  std::string joined;
  for (const auto& [y, text] : narrow.lines) {
    EXPECT_LE(textWidth(text, narrow.scale), 720 - 2 * 12) << text;  // 12: the band's padding
    EXPECT_NE(text.front(), ' ');
    joined += (joined.empty() ? "" : " ") + text;
  }
  EXPECT_EQ(joined, content.lines[0]);
  EXPECT_GT(narrow.lines[1].first, narrow.lines[0].first);
  // A word wider than the band is cut between letters, and nothing is lost.
  content.lines = {std::string(100, 'x')};
  const LegendLayout cut = layoutLegend(content, 720, legendBandHeight(720));
  ASSERT_GE(cut.lines.size(), 2u);
  std::size_t letters = 0;
  for (const auto& [y, text] : cut.lines) letters += text.size();
  EXPECT_EQ(letters, 100u);
}

TEST(SnapshotColouring, SetsPrunedAndColliding) {
  PotentiallyCollidingSets sets(2);
  sets[0].members = {{1, {}}, {3, {}}};
  sets[1].members = {{4, {}}, {1, {}}};
  const std::vector<ObjectPair> pairs = {ObjectPair::of(3, 1)};
  const ObjectColouring c = colourBySets(6, sets, pairs);
  EXPECT_EQ(c.setOf, (std::vector<int>{-1, 0, -1, 0, 1, -1}));
  EXPECT_EQ(c.colour[4], setColour(1));
  EXPECT_EQ(c.colour[0], kPrunedColour);
  EXPECT_EQ(c.colliding, (std::vector<bool>{false, true, false, true, false, false}));
  EXPECT_EQ(setColour(kSetPaletteSize), setColour(0));
  sets[1].members.push_back({6, {}});
  EXPECT_THROW((void)colourBySets(6, sets, pairs), RunError);
}

TEST(SnapshotColouring, FixedObjectsArePaleAndTheCameraIsFittedToWhatMoves) {
  SceneGeometry scene;
  scene.meshes = {makePlane(10.0, 2), makeTorus(0.5, 0.2, 8, 6)};
  scene.objects = {{.mesh = 0, .fixed = true, .group = {}}, {.mesh = 1, .fixed = false, .group = {}},
                   {.mesh = 1, .fixed = false, .group = {}}};
  PotentiallyCollidingSets sets(1);
  sets[0].members = {{0, {}}, {1, {}}};
  ObjectColouring c = colourBySets(3, sets, {});
  paleFixedObjects(scene, c);
  EXPECT_EQ(c.colour[0], pale(setColour(0)));
  EXPECT_EQ(c.colour[1], setColour(0));
  EXPECT_EQ(c.colour[2], kPrunedColour);
  const Rgb p = pale(setColour(0));
  EXPECT_GT(p.r + p.g + p.b, setColour(0).r + setColour(0).g + setColour(0).b + 200);

  // The plane reaches 5 from the origin; the tori, 3 and 4 away along x, 0.7 from their centres.
  std::vector<Pose> poses(3);
  poses[1].translation = {3, 0, 0};
  poses[2].translation = {4, 0, 0};
  std::vector<Eigen::Vector3d> points;
  appendObjectCorners(scene, poses, points);
  ASSERT_EQ(points.size(), 16u);
  for (const Eigen::Vector3d& q : points) EXPECT_NEAR(q.x(), 3.5, 1.21);
  // Nothing moves: the fixed objects are what the camera sees.
  scene.objects[1].fixed = scene.objects[2].fixed = true;
  points.clear();
  appendObjectCorners(scene, poses, points);
  EXPECT_EQ(points.size(), 24u);
}

}  // namespace
}  // namespace cdb
