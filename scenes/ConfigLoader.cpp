#include "scenes/ConfigLoader.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "core/Errors.h"
#include "scenes/ConfigNode.h"
#include "scenes/PlacementCapacity.h"

namespace cdb {
namespace {

namespace L = limits;

std::string fileLine(const std::string& file, int line) {
  return file + ":" + std::to_string(line);
}

MeshSpec readMesh(const ConfigNode& node) {
  node.require("a mesh map with 'kind'");
  if (!node.isMap()) node.fail("a map with 'kind' (torus, plane or asset)");
  const ConfigNode kind = node["kind"];
  kind.require("torus, plane or asset");
  const std::string k = kind.string();
  MeshSpec mesh;
  if (k == "torus") {
    mesh.kind = MeshSpec::Kind::Torus;
    node.expectKeys({"kind", "major_radius", "minor_radius", "rings", "sides"});
    if (auto n = node["major_radius"]; n.present()) mesh.majorRadius = n.number(L::kLength);
    if (auto n = node["minor_radius"]; n.present()) {
      mesh.minorRadius = n.number(L::kLength);
      // A torus whose tube reaches its axis intersects itself.
      if (!(mesh.minorRadius < mesh.majorRadius)) {
        n.fail("a minor radius below the major radius (" + std::to_string(mesh.majorRadius) + ")");
      }
    } else if (!(mesh.minorRadius < mesh.majorRadius)) {
      node["major_radius"].fail("a major radius above the minor radius (" +
                                std::to_string(mesh.minorRadius) + ")");
    }
    if (auto n = node["rings"]; n.present()) mesh.rings = int(n.integer(L::kTorusSegments));
    if (auto n = node["sides"]; n.present()) mesh.sides = int(n.integer(L::kTorusSegments));
  } else if (k == "plane") {
    mesh.kind = MeshSpec::Kind::Plane;
    node.expectKeys({"kind", "plane_size", "plane_cells"});
    if (auto n = node["plane_size"]; n.present()) mesh.planeSize = n.number(L::kLength);
    if (auto n = node["plane_cells"]; n.present()) mesh.planeCells = int(n.integer(L::kPlaneCells));
  } else if (k == "asset") {
    mesh.kind = MeshSpec::Kind::Asset;
    node.expectKeys({"kind", "asset", "asset_size", "max_triangles"});
    node["asset"].require("an asset file stem like dragon_vrip_res3");
    mesh.asset = node["asset"].string();
    if (auto n = node["asset_size"]; n.present()) mesh.assetSize = n.number(L::kLength);
    if (auto n = node["max_triangles"]; n.present())
      mesh.maxTriangles = n.integer(L::kMeshTriangles);
  } else {
    kind.fail("torus, plane or asset");
  }
  return mesh;
}

CollisionProxy readCollision(const ConfigNode& node) {
  const std::string s = node.string();
  if (s == "trimesh") return CollisionProxy::Trimesh;
  if (s == "box") return CollisionProxy::Box;
  if (s == "sphere") return CollisionProxy::Sphere;
  node.fail("trimesh, box or sphere");
}

InitialPose readPose(const ConfigNode& node) {
  node.expectKeys({"position", "rotation_degrees"});
  InitialPose pose;
  if (auto n = node["position"]; n.present()) pose.position = n.vec3(L::kCoordinate);
  if (auto n = node["rotation_degrees"]; n.present())
    pose.rotationDegrees = n.vec3(L::kAngleDegrees);
  return pose;
}

RandomPlacement readPlacement(const ConfigNode& node) {
  node.expectKeys({"region_min", "region_max", "min_gap", "random_orientation", "speed_min",
                   "speed_max", "angular_speed_max"});
  RandomPlacement p;
  node["region_min"].require("a list of 3 numbers");
  node["region_max"].require("a list of 3 numbers");
  p.regionMin = node["region_min"].vec3(L::kCoordinate);
  p.regionMax = node["region_max"].vec3(L::kCoordinate);
  for (int i = 0; i < 3; ++i) {
    if (p.regionMax[i] < p.regionMin[i]) {
      node["region_max"].fail("each coordinate >= region_min's",
                              node["region_max"].describe() + " (axis " + "xyz"[i] + " below " +
                                  std::to_string(p.regionMin[i]) + ")");
    }
  }
  if (auto n = node["min_gap"]; n.present()) p.minGap = n.number(L::kGap);
  if (auto n = node["random_orientation"]; n.present()) p.randomOrientation = n.boolean();
  if (auto n = node["speed_min"]; n.present()) p.speedMin = n.number(L::kSpeed);
  if (auto n = node["speed_max"]; n.present()) p.speedMax = n.number(L::kSpeed);
  if (p.speedMax < p.speedMin) {
    (node["speed_max"].present() ? node["speed_max"] : node["speed_min"])
        .fail("speed_max >= speed_min (" + std::to_string(p.speedMin) + ")",
              std::to_string(p.speedMax));
  }
  if (auto n = node["angular_speed_max"]; n.present())
    p.angularSpeedMax = n.number(L::kAngularSpeed);
  return p;
}

BodyGroup readBody(const ConfigNode& node) {
  node.expectKeys({"name", "mesh", "count", "fixed", "density", "collision", "poses", "placement"});
  BodyGroup body;
  node["name"].require("a group name");
  body.name = node["name"].string();
  body.mesh = readMesh(node["mesh"]);
  const ConfigNode count = node["count"];
  if (count.present()) body.count = int(count.integer(L::kObjectCount));
  if (auto n = node["fixed"]; n.present()) body.fixed = n.boolean();
  if (auto n = node["density"]; n.present()) body.density = n.number(L::kDensity);
  if (auto n = node["collision"]; n.present()) body.collision = readCollision(n);

  const ConfigNode poses = node["poses"], placement = node["placement"];
  if (poses.present() == placement.present()) {
    (poses.present() ? placement : node)
        .fail("either 'poses' (explicit) or 'placement' (random), exactly one",
              poses.present() ? "both" : "neither");
  }
  if (poses.present()) {
    for (const auto& item : poses.items("a list of poses {position, rotation_degrees}")) {
      body.poses.push_back(readPose(item));
    }
    if (!count.present()) body.count = int(body.poses.size());
    if (body.poses.empty() || std::size_t(body.count) != body.poses.size()) {
      poses.fail(std::to_string(body.count) + " poses (count: " + std::to_string(body.count) + ")",
                 std::to_string(body.poses.size()));
    }
  } else {
    body.placement = readPlacement(placement);
  }
  return body;
}

DynamicsSpec readDynamics(const ConfigNode& node) {
  DynamicsSpec d;
  if (!node.present()) return d;
  node.expectKeys({"gravity", "time_step", "steps_per_frame", "frames", "warmup_frames",
                   "container_half_extent", "friction", "restitution", "max_contacts_per_pair",
                   "linear_damping", "angular_damping"});
  if (auto n = node["gravity"]; n.present()) d.gravity = n.vec3(L::kGravity);
  if (auto n = node["time_step"]; n.present()) d.timeStep = n.number(L::kTimeStep);
  if (auto n = node["steps_per_frame"]; n.present())
    d.stepsPerFrame = int(n.integer(L::kStepsPerFrame));
  if (auto n = node["frames"]; n.present()) d.frames = int(n.integer(L::kFrames));
  if (auto n = node["warmup_frames"]; n.present())
    d.warmupFrames = int(n.integer(L::kWarmupFrames));
  if (auto n = node["container_half_extent"]; n.present()) {
    d.containerHalfExtent = n.number(L::kContainerHalfExtent);
  }
  if (auto n = node["friction"]; n.present()) d.friction = n.number(L::kFriction);
  if (auto n = node["restitution"]; n.present()) d.restitution = n.number(L::kRestitution);
  if (auto n = node["max_contacts_per_pair"]; n.present()) {
    d.maxContactsPerPair = int(n.integer(L::kMaxContactsPerPair));
  }
  if (auto n = node["linear_damping"]; n.present()) d.linearDamping = n.number(L::kDamping);
  if (auto n = node["angular_damping"]; n.present()) d.angularDamping = n.number(L::kDamping);
  return d;
}

SweepSpec readSweep(const ConfigNode& node) {
  SweepSpec s;
  if (!node.present()) return s;
  node.expectKeys({"resolutions", "counted_group", "object_counts", "repeats", "strategies"});
  if (auto n = node["resolutions"]; n.present()) s.resolutions = n.intList(L::kResolution);
  if (auto n = node["counted_group"]; n.present()) s.countedGroup = n.string();
  if (auto n = node["object_counts"]; n.present()) s.objectCounts = n.intList(L::kObjectCount);
  if (s.countedGroup.empty() != s.objectCounts.empty()) {
    if (s.countedGroup.empty()) {
      node["object_counts"].fail("a counted_group beside object_counts", "no counted_group");
    }
    node["counted_group"].fail("object_counts beside counted_group", "no object_counts");
  }
  if (auto n = node["repeats"]; n.present()) s.repeats = int(n.integer(L::kRepeats));
  if (auto n = node["strategies"]; n.present()) {
    constexpr std::string_view expected = "a non-empty list of strategy names";
    const auto items = n.items(expected);
    if (items.empty()) n.fail(expected);
    s.strategies.clear();
    for (const auto& item : items) {
      const std::string name = item.string();
      if (std::find(s.strategies.begin(), s.strategies.end(), name) != s.strategies.end()) {
        item.fail("each strategy once", "'" + name + "' a second time");
      }
      s.strategies.push_back(name);
    }
  }
  return s;
}

VisibilitySpec readVisibility(const ConfigNode& node) {
  VisibilitySpec v;
  if (!node.present()) return v;
  node.expectKeys({"backend", "conservative", "raw_depth_offset", "threads"});
  if (auto n = node["backend"]; n.present()) v.backend = n.string();
  if (auto n = node["conservative"]; n.present()) v.conservative = n.boolean();
  if (auto n = node["raw_depth_offset"]; n.present()) v.rawDepthOffset = n.number(L::kDepthOffset);
  if (auto n = node["threads"]; n.present()) v.threads = int(n.integer(L::kThreads));
  return v;
}

// The keys given in `node` over `base`: a strategy's own hierarchy overrides the shared one key
// by key.
HierarchySpec readHierarchy(const ConfigNode& node, HierarchySpec base) {
  if (!node.present()) return base;
  node.expectKeys({"branching", "leaf_triangles", "offset"});
  if (auto n = node["branching"]; n.present()) {
    base.branching = int(n.integer(L::kBranching));
    if (base.branching != 2 && base.branching != 4 && base.branching != 8) n.fail("2, 4 or 8");
  }
  if (auto n = node["leaf_triangles"]; n.present())
    base.leafTriangles = int(n.integer(L::kLeafTriangles));
  if (auto n = node["offset"]; n.present()) base.offset = n.number(L::kBvhOffset);
  return base;
}

AxisChoice readAxis(const ConfigNode& node) {
  const std::string s = node.string();
  if (s == "x") return 0;
  if (s == "y") return 1;
  if (s == "z") return 2;
  if (s == "auto") return std::nullopt;
  node.fail("x, y, z or auto");
}

StrategySpecs readStrategies(const ConfigNode& node, const HierarchySpec& hierarchy) {
  StrategySpecs s;
  s.ours.hierarchy = hierarchy;
  s.cullideBvh.hierarchy = hierarchy;
  if (!node.present()) return s;
  node.expectKeys({"cis", "cullide_bvh", "ours"}, "a strategy with options");
  if (auto cis = node["cis"]; cis.present()) {
    cis.expectKeys({"axis"});
    if (auto n = cis["axis"]; n.present()) s.cis.axis = readAxis(n);
  }
  if (auto ours = node["ours"]; ours.present()) {
    ours.expectKeys({"first_axis", "hierarchy"});
    if (auto n = ours["first_axis"]; n.present()) s.ours.firstAxis = readAxis(n);
    s.ours.hierarchy = readHierarchy(ours["hierarchy"], hierarchy);
  }
  if (auto bvh = node["cullide_bvh"]; bvh.present()) {
    bvh.expectKeys({"hierarchy"});
    s.cullideBvh.hierarchy = readHierarchy(bvh["hierarchy"], hierarchy);
  }
  return s;
}

CullingSpec readCulling(const ConfigNode& node) {
  CullingSpec c;
  if (!node.present()) return c;
  node.expectKeys({"visibility", "hierarchy", "strategies"});
  c.visibility = readVisibility(node["visibility"]);
  c.strategies = readStrategies(node["strategies"], readHierarchy(node["hierarchy"], {}));
  return c;
}

// Random placement must be able to succeed: inside the container when there is one, and with room
// for the largest count the sweep asks for.
void checkPlacement(const BodyGroup& body, int largestCount, const DynamicsSpec& dynamics,
                    const ConfigNode& node) {
  const RandomPlacement& p = *body.placement;
  const double r = boundingRadius(body.mesh);
  const double h = dynamics.containerHalfExtent;
  if (h > 0) {
    for (int i = 0; i < 3; ++i) {
      const bool minOut = p.regionMin[i] - r<-h, maxOut = p.regionMax[i] + r> h;
      if (minOut || maxOut) {
        const ConfigNode at = node["placement"][minOut ? "region_min" : "region_max"];
        std::ostringstream expected;
        expected << "a region whose bodies (bounding radius " << r
                 << ") fit inside the container (half extent " << h << ")";
        at.fail(expected.str(), at.describe());
      }
    }
  }
  const double fill = placementFill(body, largestCount);
  if (fill > L::kMaxPlacementFill) {
    std::ostringstream expected, got;
    expected << "a region where " << largestCount << " bodies of bounding radius " << r
             << " fill at most " << L::kMaxPlacementFill * 100 << "% (random placement jams)";
    got << std::llround(100 * fill) << "%";
    node["placement"].fail(expected.str(), got.str());
  }
}

ScenarioConfig readScenario(const ConfigNode& root, const std::string& file) {
  root.expectKeys({"environment", "description", "seed", "dynamics", "bodies", "sweep", "culling"});
  ScenarioConfig config;
  config.sourcePath = file;
  root["environment"].require("an environment name like env1");
  config.environment = root["environment"].string();
  if (auto n = root["description"]; n.present()) config.description = n.string(true);
  if (auto n = root["seed"]; n.present()) config.seed = n.unsignedInteger();
  config.dynamics = readDynamics(root["dynamics"]);

  const ConfigNode bodies = root["bodies"];
  bodies.require("a list of body groups");
  const auto groups = bodies.items("a non-empty list of body groups");
  if (groups.empty()) bodies.fail("a non-empty list of body groups");
  std::set<std::string> names;
  for (const auto& group : groups) {
    config.bodies.push_back(readBody(group));
    if (!names.insert(config.bodies.back().name).second) {
      group["name"].fail("a group name used once", "'" + config.bodies.back().name + "' again");
    }
  }

  config.sweep = readSweep(root["sweep"]);
  if (!config.sweep.countedGroup.empty()) {
    const ConfigNode at = root["sweep"]["counted_group"];
    const auto it =
        std::find_if(config.bodies.begin(), config.bodies.end(),
                     [&](const BodyGroup& b) { return b.name == config.sweep.countedGroup; });
    if (it == config.bodies.end()) {
      std::string list;
      for (const auto& b : config.bodies) list += (list.empty() ? "" : ", ") + b.name;
      at.fail("the name of a body group (" + list + ")", at.describe());
    }
    if (!it->placement)
      at.fail("a group with random placement (explicit poses cannot grow)", at.describe());
  }
  for (std::size_t i = 0; i < config.bodies.size(); ++i) {
    const BodyGroup& body = config.bodies[i];
    if (!body.placement) continue;
    int largest = body.count;
    if (body.name == config.sweep.countedGroup) {
      largest = std::max(largest, *std::max_element(config.sweep.objectCounts.begin(),
                                                    config.sweep.objectCounts.end()));
    }
    checkPlacement(body, largest, config.dynamics, groups[i]);
  }

  config.culling = readCulling(root["culling"]);
  return config;
}

}  // namespace

ScenarioConfig loadScenarioConfig(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::ifstream in(file, std::ios::binary);
  std::error_code ec;
  if (!in || std::filesystem::is_directory(file, ec)) {
    const std::string got = std::filesystem::is_directory(file, ec) ? "a directory"
                            : std::filesystem::exists(file, ec)     ? "a file that cannot be read"
                                                                    : "no such file";
    throw InputError(name + ": expected a readable scenario file, got " + got);
  }
  std::stringstream text;
  text << in.rdbuf();
  return loadScenarioConfigFromText(text.str(), name);
}

ScenarioConfig loadScenarioConfigFromText(std::string_view text, const std::string& name) {
  YAML::Node document;
  try {
    document = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    throw InputError(fileLine(name, e.mark.line + 1) + ": expected valid YAML, got " + e.msg +
                     " (column " + std::to_string(e.mark.column + 1) + ")");
  }
  if (!document.IsDefined() || document.IsNull()) {
    throw InputError(fileLine(name, 1) +
                     ": (top level): expected a scenario map with environment and bodies, got an "
                     "empty file");
  }
  return readScenario(ConfigNode::root(document, name), name);
}

}  // namespace cdb
