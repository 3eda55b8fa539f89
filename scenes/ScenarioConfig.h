#pragma once
// Typed form of a scenario YAML file (configs/env*.yaml). The loader (ConfigLoader) fills it and
// rejects unknown keys, wrong types and out-of-range values; everything else reads only this.
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scenes/ConfigLimits.h"
#include "scenes/CullingSpec.h"

namespace cdb {

using Vec3 = std::array<double, 3>;

// Where a body's mesh comes from.
struct MeshSpec {
  enum class Kind { Torus, Plane, Asset };
  Kind kind = Kind::Torus;
  // Torus: `rings` x `sides` grid, 2 triangles per cell (20 x 20 = 800 triangles).
  double majorRadius = 0.5;
  double minorRadius = 0.2;
  int rings = 20;
  int sides = 20;
  // Plane: a square in the local x-z plane (normal +y), `cells` x `cells` grid, 2 triangles a cell
  // (30 x 30 = 1,800 triangles).
  double planeSize = 10.0;
  int planeCells = 30;
  // Asset: a file stem looked up on the asset path (.ply or .obj), scaled so that the longest side
  // of its bounding box is `assetSize` and centred on its bounding-box centre.
  std::string asset;
  double assetSize = 1.0;
  long long maxTriangles = limits::kDefaultMeshTriangles;  // a larger file is refused
};

// The shape ODE uses for contact response. Trimesh is exact; the proxies exist for meshes where
// trimesh-trimesh contact is too slow (the dragons). Culling always uses the real mesh.
enum class CollisionProxy { Trimesh, Box, Sphere };

struct InitialPose {
  Vec3 position{0, 0, 0};
  Vec3 rotationDegrees{0, 0, 0};  // intrinsic X, then Y, then Z
};

// Random placement of a group's bodies: uniform positions in `regionMin`..`regionMax`, rejected
// while their bounding spheres overlap a body already placed (`minGap` apart), uniform random
// orientation if `randomOrientation`, linear velocity with a uniform random direction and a speed
// uniform in [speedMin, speedMax], angular speed uniform in [0, angularSpeedMax] (rad/s).
struct RandomPlacement {
  Vec3 regionMin{-1, -1, -1};
  Vec3 regionMax{1, 1, 1};
  double minGap = 0.0;
  bool randomOrientation = true;
  double speedMin = 0.0;
  double speedMax = 0.0;
  double angularSpeedMax = 0.0;
};

struct BodyGroup {
  std::string name;
  MeshSpec mesh;
  int count = 1;
  bool fixed = false;        // fixed bodies keep their initial pose and never move
  double density = 1.0;      // mass properties from the mesh volume (trimesh) or the proxy
  CollisionProxy collision = CollisionProxy::Trimesh;
  std::vector<InitialPose> poses;            // explicit poses (fixed bodies); size == count
  std::optional<RandomPlacement> placement;  // or random placement (moving bodies)
};

struct DynamicsSpec {
  Vec3 gravity{0, -9.81, 0};
  double timeStep = 0.01;    // seconds per ODE step
  int stepsPerFrame = 2;     // ODE steps between two collision-detection frames
  int frames = 300;          // frames recorded per run
  int warmupFrames = 0;      // frames simulated before recording starts
  // A closed cube of half extent `containerHalfExtent` centred at the origin (env3); 0 = none.
  double containerHalfExtent = 0.0;
  double friction = 0.6;     // Coulomb friction coefficient (ODE mu)
  double restitution = 0.2;  // ODE bounce
  int maxContactsPerPair = 8;
  double linearDamping = 0.0;
  double angularDamping = 0.0;
};

// What a run sweeps and how often; the command line can override every field.
struct SweepSpec {
  std::vector<int> resolutions{800};
  std::string countedGroup;      // body group whose count is swept (env3); empty = none
  std::vector<int> objectCounts;  // values for countedGroup's count
  int repeats = 1;               // independent simulations (seed, seed+1, ...)
  std::vector<std::string> strategies{"cullide"};
  // Strategies measured on only the first N of the repeats (N <= repeats): a costly strategy
  // outside the thesis' tables need not take as long as the tables' own (`--strategy-repeats`).
  std::map<std::string, int> strategyRepeats;
};

struct ScenarioConfig {
  std::string sourcePath;   // file it was read from (for messages)
  std::string environment;  // env1, env2, env3, ...
  std::string description;
  std::uint64_t seed = 1;
  DynamicsSpec dynamics;
  std::vector<BodyGroup> bodies;
  SweepSpec sweep;
  CullingSpec culling;
};

}  // namespace cdb
