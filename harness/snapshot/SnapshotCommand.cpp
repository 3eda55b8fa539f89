#include "harness/snapshot/SnapshotCommand.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "core/Errors.h"
#include "culling/DetectorRegistry.h"
#include "culling/exact/ExactPhase.h"
#include "culling/exact/GroundTruth.h"
#include "culling/visibility/BackendResources.h"
#include "culling/visibility/VisibilityBackendRegistry.h"
#include "harness/common/AtomicFile.h"
#include "harness/snapshot/AnimationWriter.h"
#include "harness/snapshot/PngWriter.h"
#include "harness/snapshot/SnapshotPicture.h"
#include "render/HeadlessGlContext.h"
#include "scenes/AssetPath.h"
#include "scenes/ConfigLoader.h"
#include "scenes/PoseRecording.h"
#include "scenes/SceneBuilder.h"

namespace cdb {

namespace {

namespace fs = std::filesystem;

// The options' errors, prefixed with the option they came from.
template <class Fn>
auto forOption(const std::string& option, Fn&& fn) {
  try {
    return fn();
  } catch (const InputError& e) {
    throw InputError(option + ": " + e.what());
  }
}

// Creates `dir` and writes a probe file into it, so that an unwritable output fails before the
// simulation, not after it.
void checkWritable(const fs::path& dir, const std::string& option) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec)
    throw InputError(option + ": cannot create the folder " + dir.string() + " (" + ec.message() +
                     ")");
  const fs::path probe = dir / (".cdbench-snapshot-probe." + std::to_string(::getpid()));
  {
    std::ofstream out(probe, std::ios::binary | std::ios::trunc);
    if (!out)
      throw InputError(option + ": cannot write into " + dir.string() + " (" +
                       std::strerror(errno) + ")");
  }
  fs::remove(probe, ec);
}

// Objects of the config outside its swept group.
int objectsOutsideCountedGroup(const ScenarioConfig& config) {
  int n = 0;
  for (const BodyGroup& g : config.bodies)
    if (g.name != config.sweep.countedGroup) n += g.count;
  return n;
}

struct Frames {
  ScenarioConfig config;
  SceneGeometry scene;
  PoseRecording recording;
};

// The scene and its poses up to the last wanted frame: read from --replay, or simulated.
Frames loadFrames(const SnapshotOptions& o, const std::vector<int>& wanted,
                  const std::string& frameOption) {
  Frames f;
  f.config = loadScenarioConfig(o.configPath);
  if (o.seed) f.config.seed = *o.seed;
  const auto pastTheEnd = [&](int frame, std::uint32_t count, const std::string& holder) {
    return InputError(frameOption + ": frame " + std::to_string(frame) +
                      " is past the simulation's end (" + holder + " frames 0.." +
                      std::to_string(static_cast<long long>(count) - 1) + ")");
  };
  const int last = *std::max_element(wanted.begin(), wanted.end());
  const auto assets = assetSearchPath(o.assetDirs);
  if (o.replayFile) {
    f.recording = readPoseRecording(*o.replayFile);
    if (o.objects) {
      f.config = withObjectCount(f.config, *o.objects);
    } else if (!f.config.sweep.countedGroup.empty()) {
      // The swept group's count the recording was made with.
      const long long count =
          static_cast<long long>(f.recording.objectCount) - objectsOutsideCountedGroup(f.config);
      if (count >= 1 && count <= 100000)
        f.config = withObjectCount(f.config, static_cast<int>(count));
    }
    // A run's --frames changes only how many frames there are, which the recording says itself.
    f.config.dynamics.frames = static_cast<int>(f.recording.frameCount());
    f.scene = buildScene(f.config, assets);
    if (f.recording.fingerprint != scenarioFingerprint(f.config, f.scene) ||
        f.recording.objectCount != f.scene.objectCount())
      throw InputError(
          o.replayFile->string() +
          ": recording was made from another config (fingerprint or object count differs)");
    if (static_cast<std::uint32_t>(last) >= f.recording.frameCount())
      throw pastTheEnd(last, f.recording.frameCount(),
                       "the recording " + o.replayFile->string() + " holds");
    return f;
  }
  if (o.objects) f.config = withObjectCount(f.config, *o.objects);
  const int simulated = f.config.dynamics.frames;
  if (last >= simulated)
    throw pastTheEnd(last, static_cast<std::uint32_t>(simulated),
                     o.configPath.string() + " simulates");
  f.scene = buildScene(f.config, assets);
  ScenarioConfig upToLast = f.config;  // frames after the last wanted one are not needed
  upToLast.dynamics.frames = last + 1;
  f.recording = recordSimulation(upToLast, f.scene, f.config.seed);
  return f;
}

// What detection says about one frame.
struct FrameAnswer {
  ObjectColouring colouring;
  std::optional<CullingResult> culled;
  std::vector<ObjectPair> colliding;
};

std::string plural(std::size_t n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

LegendContent legendFor(const SnapshotOptions& o, const Frames& f, const std::string& backend,
                        int frame, const FrameAnswer& a) {
  LegendContent l;
  const std::string objects = plural(f.scene.objectCount(), "object", "objects");
  const std::string pairs = plural(a.colliding.size(), "colliding pair", "colliding pairs");
  if (o.strategy) {
    l.lines.push_back(*o.strategy + " on " + f.config.environment + ", frame " +
                      std::to_string(frame) + ": " + objects + "; " + backend + " backend at " +
                      std::to_string(o.resolution) + " px");
    if (a.culled) {
      l.lines.push_back(plural(a.culled->sets.size(), "set", "sets") + ", PCS " +
                        plural(a.culled->counters.pcsSize, "object", "objects") + ", " + pairs +
                        " (outlined)");
      for (std::size_t k = 0; k < a.culled->sets.size(); ++k)
        l.swatches.push_back({setColour(k), "set " + std::to_string(k + 1) + ": " +
                                                std::to_string(a.culled->sets[k].members.size())});
      const auto pruned = std::count(a.colouring.setOf.begin(), a.colouring.setOf.end(), -1);
      l.swatches.push_back({kPrunedColour, "pruned: " + std::to_string(pruned)});
      // In the colour of the first fixed object, as drawn.
      const auto fixed = std::ranges::find_if(f.scene.objects, &SceneObject::fixed);
      if (fixed != f.scene.objects.end())
        l.swatches.push_back(
            {a.colouring.colour[static_cast<std::size_t>(fixed - f.scene.objects.begin())],
             "fixed: pale"});
    } else {
      l.lines.push_back(*o.strategy + " is a CPU peer (no culling sets): " + pairs + " (outlined)");
    }
  } else {
    l.lines.push_back(f.config.environment + ", frame " + std::to_string(frame) + ": " + objects +
                      ", coloured by body group");
    l.lines.push_back(pairs + " by the ground truth (outlined)");
  }
  if (!a.culled) {
    std::vector<std::string> seen;
    for (std::size_t i = 0; i < f.scene.objectCount(); ++i) {
      const std::string& g = f.scene.objects[i].group;
      if (std::find(seen.begin(), seen.end(), g) != seen.end()) continue;
      seen.push_back(g);
      l.swatches.push_back({a.colouring.colour[i], g.empty() ? "objects" : g});
    }
  }
  l.swatches.push_back({kOutlineColour, "in a colliding pair", LegendSwatch::Style::Frame});
  return l;
}

nlohmann::json rgbJson(Rgb c) { return {c.r, c.g, c.b}; }

nlohmann::json pictureJson(const SnapshotOptions& o, const Frames& f, const std::string& backend,
                           const std::string& renderer, int frame, const FrameAnswer& a,
                           const PictureSetup& setup, const Picture& picture) {
  nlohmann::json j;
  j["config"] = o.configPath.string();
  j["environment"] = f.config.environment;
  j["frame"] = frame;
  j["object_count"] = f.scene.objectCount();
  j["replay"] = o.replayFile ? nlohmann::json(o.replayFile->string()) : nlohmann::json(nullptr);
  j["seed"] = o.replayFile ? nlohmann::json(f.recording.seed) : nlohmann::json(f.config.seed);
  j["strategy"] = o.strategy ? nlohmann::json(*o.strategy) : nlohmann::json(nullptr);
  j["visibility"] = o.strategy ? nlohmann::json(backend) : nlohmann::json(nullptr);
  j["resolution"] = o.strategy ? nlohmann::json(o.resolution) : nlohmann::json(nullptr);
  j["view"] = o.view;
  j["width"] = setup.width;
  j["height"] = setup.height;
  j["scene_height"] = setup.sceneHeight;
  j["gl_renderer"] = renderer;
  j["colliding_pairs_by"] = o.strategy ? *o.strategy : std::string("ground truth");
  nlohmann::json pairs = nlohmann::json::array();
  for (const ObjectPair& p : a.colliding) pairs.push_back({p.a, p.b});
  j["colliding_pairs"] = pairs;
  if (a.culled) {
    nlohmann::json sets = nlohmann::json::array();
    for (std::size_t k = 0; k < a.culled->sets.size(); ++k) {
      nlohmann::json members = nlohmann::json::array();
      for (const SetMember& m : a.culled->sets[k].members) members.push_back(m.object);
      sets.push_back({{"colour", rgbJson(setColour(k))}, {"members", members}});
    }
    j["sets"] = sets;
    j["pcs_size"] = a.culled->counters.pcsSize;
  } else {
    j["sets"] = nullptr;
    j["pcs_size"] = nullptr;
  }
  j["pruned_colour"] = rgbJson(kPrunedColour);
  j["outline_colour"] = rgbJson(kOutlineColour);
  nlohmann::json objects = nlohmann::json::array();
  for (std::size_t i = 0; i < f.scene.objectCount(); ++i) {
    const auto& box = picture.pixelBoxes[i];
    objects.push_back({{"id", i},
                       {"group", f.scene.objects[i].group},
                       {"fixed", f.scene.objects[i].fixed},
                       {"set", a.colouring.setOf[i] >= 0 ? nlohmann::json(a.colouring.setOf[i] + 1)
                                                         : nlohmann::json(nullptr)},
                       {"colour", rgbJson(a.colouring.colour[i])},
                       {"colliding", static_cast<bool>(a.colouring.colliding[i])},
                       {"pixel_box", {box[0], box[1], box[2], box[3]}}});
  }
  j["objects"] = objects;
  j["command_line"] = o.commandLine;
  return j;
}

// The JSON, then the PNG; a PNG that cannot be written takes its JSON with it.
void writePicture(const fs::path& png, const Picture& picture, const nlohmann::json& json) {
  const fs::path sidecar = fs::path(png).replace_extension(".json");
  const std::string bytes = encodePng(picture.image);
  writeFileAtomically(sidecar, json.dump(2) + "\n");
  try {
    writeFileAtomically(png, bytes);
  } catch (...) {
    std::error_code ec;
    fs::remove(sidecar, ec);
    throw;
  }
}

}  // namespace

SnapshotSummary runSnapshot(const SnapshotOptions& o) {
  // Everything that needs no config first.
  if (o.frame.has_value() == o.frames.has_value())
    throw InputError("--frame K or --frames A:B:STEP: expected exactly one of them");
  const CameraView view = forOption("--view", [&] { return parseCameraView(o.view); });
  const PictureSize size = parsePictureSize(o.size);
  if (o.resolution < 1 || o.resolution > 16384)
    throw InputError("--resolution " + std::to_string(o.resolution) + ": expected 1..16384 pixels");
  if (o.fps < 1 || o.fps > 60)
    throw InputError("--fps " + std::to_string(o.fps) + ": expected 1..60");
  std::vector<int> wanted;
  std::string frameOption;
  if (o.frame) {
    frameOption = "--frame " + std::to_string(*o.frame);
    if (*o.frame < 0) throw InputError(frameOption + ": expected a frame number >= 0");
    wanted = {*o.frame};
  } else {
    frameOption = "--frames " + *o.frames;
    wanted = parseFrameRange(*o.frames).frames();
  }
  const bool sequence = o.frames.has_value();
  const std::string outOption = "--out " + o.out.string();
  if (!sequence && o.out.extension() != ".png")
    throw InputError(outOption + ": expected a .png file");
  if (sequence) checkAnimationTool(o.out);
  if (fs::is_directory(o.out)) throw InputError(outOption + ": is a folder; expected a file name");
  if (o.strategy)
    forOption("--strategy", [&] { DetectorRegistry::builtin().validate({*o.strategy}); });
  if (o.visibility)
    forOption("--visibility",
              [&] { VisibilityBackendRegistry::builtin().validate(*o.visibility); });
  const GlPlatform platform = forOption("--gl", [&] { return parseGlPlatform(o.glPlatform); });
  const fs::path outDir = o.out.has_parent_path() ? o.out.parent_path() : fs::path(".");
  const fs::path pictureDir = sequence ? outDir / (o.out.stem().string() + "-frames") : outDir;
  checkWritable(pictureDir, outOption);

  Frames f = loadFrames(o, wanted, frameOption);
  if (o.visibility) f.config.culling.visibility.backend = *o.visibility;
  const std::string backendName = backendNameOf(f.config.culling);
  forOption(o.configPath.string() + ": culling.visibility.backend",
            [&] { VisibilityBackendRegistry::builtin().validate(backendName); });

  BackendResources resources(platform);
  std::unique_ptr<VisibilityBackend> backend;
  std::optional<ExactPhase> exact;
  std::unique_ptr<CollisionDetector> detector;
  std::optional<GroundTruth> truth;
  if (o.strategy) {
    backend = VisibilityBackendRegistry::builtin().create(backendName, resources,
                                                          visibilityOptionsOf(f.config.culling));
    if (o.resolution > backend->maxResolution())
      throw InputError("--resolution " + std::to_string(o.resolution) +
                       ": above the largest framebuffer the " + backendName + " backend renders (" +
                       std::to_string(backend->maxResolution()) + " pixels)");
    backend->attachScene(f.scene);
    exact.emplace(f.scene);
    DetectorOptions options;
    options.resolution = o.resolution;
    options.culling = f.config.culling;
    detector = DetectorRegistry::builtin().createDetector(*o.strategy, options, *backend, *exact);
    detector->attach(f.scene);
  } else {
    truth.emplace(f.scene);
  }
  SceneRenderer renderer(resources.gl());
  if (size.width * kSupersample > renderer.maxSize() ||
      size.height * kSupersample > renderer.maxSize())
    throw InputError("--size " + o.size + ": above what the GL renders (" +
                     std::to_string(renderer.maxSize() / kSupersample) + " pixels a side)");
  renderer.attach(f.scene);
  const std::string glRenderer = resources.gl().info().glRenderer;

  // One camera for every picture, so that a sequence does not jump.
  std::vector<Eigen::Vector3d> points;
  for (int frame : wanted)
    appendObjectCorners(f.scene, f.recording.frame(static_cast<std::uint32_t>(frame)), points);
  std::vector<Segment> segments;
  if (const double half = f.config.dynamics.containerHalfExtent; half > 0) {
    segments = cubeEdges(half);
    for (int k = 0; k < 8; ++k)
      points.emplace_back(k & 1 ? half : -half, k & 2 ? half : -half, k & 4 ? half : -half);
  }
  const PictureSetup setup = setUpPicture(points, view, size, std::move(segments));

  SnapshotSummary summary;
  for (int frame : wanted) {
    const auto poses = f.recording.frame(static_cast<std::uint32_t>(frame));
    FrameAnswer a;
    if (detector) {
      DetectedFrame detected = detector->detect({poses, frame});
      a.colliding = std::move(detected.report.collidingPairs);
      a.culled = std::move(detected.culled);
    } else {
      a.colliding = truth->compute(poses).collidingPairs;
    }
    if (a.culled) {
      a.colouring = colourBySets(f.scene.objectCount(), a.culled->sets, a.colliding);
      paleFixedObjects(f.scene, a.colouring);
    } else {
      a.colouring = colourByGroup(f.scene, a.colliding);
    }
    const Picture picture = paintPicture(renderer, f.scene, poses, a.colouring,
                                         legendFor(o, f, backendName, frame, a), setup);
    fs::path png = o.out;
    if (sequence) {
      char name[32];
      std::snprintf(name, sizeof name, "frame-%04d.png", frame);
      png = pictureDir / name;
    }
    writePicture(png, picture,
                 pictureJson(o, f, backendName, glRenderer, frame, a, setup, picture));
    summary.pictures.push_back(png);
    summary.width = picture.image.width;
    summary.height = picture.image.height;
    summary.sets = a.culled ? std::optional<std::size_t>(a.culled->sets.size()) : std::nullopt;
    summary.collidingPairs = a.colliding.size();
  }
  if (sequence) {
    writeAnimation(o.out, summary.pictures, o.fps);
    summary.animation = o.out;
  }
  return summary;
}

}  // namespace cdb
