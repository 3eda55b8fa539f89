#pragma once
// ODE's process-wide state. dInitODE2/dCloseODE are reference counted here so that simulations
// can come and go on any thread. The lock exists because this ODE build (no ODE_EXT_mt_collisions)
// keeps its trimesh collider cache in one global: two worlds must not collide or step at once.
#include <mutex>

namespace cdb {

class OdeRuntime {
 public:
  OdeRuntime();   // initialises ODE on the first live instance
  ~OdeRuntime();  // closes it with the last
  OdeRuntime(const OdeRuntime&) = delete;
  OdeRuntime& operator=(const OdeRuntime&) = delete;

  // Held while creating, stepping or destroying ODE objects.
  [[nodiscard]] static std::unique_lock<std::mutex> lock();
};

}  // namespace cdb
