#pragma once
// The solver and contact parameters that the config does not set. They shape every frame, so
// scenarioFingerprint() includes them: a recording made with other values is refused.
namespace cdb::dynamics_model {

// Iterations of dWorldQuickStep's projected Gauss-Seidel solver. 20 (ODE's default) lets stacks
// of tori sink into each other; beyond ~50 the piles look the same and only cost time.
inline constexpr int kSolverIterations = 40;

// Global error reduction and constraint force mixing (ODE's defaults are 0.2 and 1e-5 for
// doubles); contacts override them with their own soft values below.
inline constexpr double kWorldErp = 0.2;
inline constexpr double kWorldCfm = 1e-5;

// Contacts: a little softness (CFM) keeps the iterative solver from ringing in piles of many
// contacts, ERP 0.2 removes a fifth of a penetration per step: firm but not explosive.
inline constexpr double kContactErp = 0.2;
inline constexpr double kContactCfm = 1e-4;
// Contacts asked of ODE per pair; the simulation keeps dynamics.maxContactsPerPair of them, spread
// over the touching area (ContactReduction.h).
inline constexpr int kContactsQueried = 64;
// Below this approach speed (m/s) contacts do not bounce, so resting bodies settle.
inline constexpr double kBounceVelocity = 0.1;
// Penetration (m) allowed to persist, so that resting contacts are not made and broken every step.
inline constexpr double kSurfaceLayer = 1e-3;
// Cap (m/s) on the speed at which the solver pushes penetrating bodies apart: trimesh contacts can
// report deep penetrations, and correcting those at full ERP shoots bodies away.
inline constexpr double kMaxCorrectingVelocity = 2.0;

// A body is unstable when its state is non-finite or leaves these bounds (world units, m/s).
inline constexpr double kMaxDistanceFromOrigin = 1e4;
inline constexpr double kMaxSpeed = 1e4;

// Changed whenever the way frames are computed changes without a config field changing.
inline constexpr int kRevision = 1;

}  // namespace cdb::dynamics_model
