#pragma once
// The accepted range of every bounded value of a scenario config (documented in configs/README.md).
// The command line checks its overrides against the same limits.
namespace cdb {

// Closed integer range.
struct IntLimits {
  long long min;
  long long max;
};

// Number range; `minExclusive` makes the lower end open (a time step of 0 is not a time step).
struct NumberLimits {
  double min;
  double max;
  bool minExclusive = false;
};

namespace limits {
// A frame buffer side in pixels: GL_MAX_RENDERBUFFER_SIZE is 16384 on current drivers.
inline constexpr IntLimits kResolution{1, 16384};
// Bodies in one group and the swept object counts.
inline constexpr IntLimits kObjectCount{1, 100000};
inline constexpr IntLimits kRepeats{1, 10000};
inline constexpr IntLimits kFrames{1, 1000000};
inline constexpr IntLimits kWarmupFrames{0, 1000000};
inline constexpr IntLimits kStepsPerFrame{1, 10000};
inline constexpr IntLimits kMaxContactsPerPair{1, 256};
// Grid sizes of the procedural meshes: a torus needs 3 segments per circle to enclose volume.
inline constexpr IntLimits kTorusSegments{3, 1024};
inline constexpr IntLimits kPlaneCells{1, 1024};
inline constexpr IntLimits kLeafTriangles{1, 1024};
// OBB tree children per split; of the range only 2, 4 and 8 are accepted.
inline constexpr IntLimits kBranching{2, 8};
inline constexpr IntLimits kThreads{0, 1024};
// Triangles of one asset mesh (mesh.max_triangles). The default, about 170 times the thesis'
// dragon, holds every common scan up to the 7.2 M-triangle XYZ RGB dragon; beyond it the loader,
// the hierarchies and the GL buffers need gigabytes. The maximum keeps three vertices per triangle
// below 2^31, as GL draw offsets are 32-bit.
inline constexpr long long kDefaultMeshTriangles = 8'000'000;
inline constexpr IntLimits kMeshTriangles{1, 500'000'000};

// Seconds; ODE is unstable long before one second per step.
inline constexpr NumberLimits kTimeStep{0.0, 1.0, true};
// Scene units. Lengths beyond 1e4 would waste float precision of the meshes and depth buffer.
inline constexpr NumberLimits kLength{0.0, 1e4, true};
inline constexpr NumberLimits kCoordinate{-1e4, 1e4};
inline constexpr NumberLimits kGap{0.0, 1e4};
inline constexpr NumberLimits kContainerHalfExtent{0.0, 1e4};  // 0 = no container
inline constexpr NumberLimits kAngleDegrees{-360.0, 360.0};
inline constexpr NumberLimits kGravity{-1000.0, 1000.0};  // per component, units/s^2
inline constexpr NumberLimits kDensity{0.0, 1e6, true};
inline constexpr NumberLimits kSpeed{0.0, 1e4};         // units/s
inline constexpr NumberLimits kAngularSpeed{0.0, 1e3};  // rad/s
inline constexpr NumberLimits kFriction{0.0, 1e3};      // ODE mu; >= 1 is effectively no sliding
inline constexpr NumberLimits kRestitution{0.0, 1.0};   // ODE bounce
inline constexpr NumberLimits kDamping{0.0, 1.0};       // ODE damping scales, per step
inline constexpr NumberLimits kDepthOffset{0.0, 1.0};   // NDC depth units
inline constexpr NumberLimits kBvhOffset{0.0, 1.0};     // fraction of the mesh's size

// Random placement gives up long before random sequential packing jams (about 38% of the volume
// in 3D): a group may fill at most this fraction of its region with its bounding spheres.
inline constexpr double kMaxPlacementFill = 0.3;
}  // namespace limits

}  // namespace cdb
