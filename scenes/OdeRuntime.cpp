#include "scenes/OdeRuntime.h"

#include <ode/ode.h>

namespace cdb {

namespace {

std::mutex& odeMutex() {
  static std::mutex mutex;
  return mutex;
}

int liveInstances = 0;  // guarded by odeMutex()

}  // namespace

OdeRuntime::OdeRuntime() {
  const auto guard = lock();
  if (liveInstances++ == 0) dInitODE2(0);
  dAllocateODEDataForThread(dAllocateMaskAll);
}

OdeRuntime::~OdeRuntime() {
  const auto guard = lock();
  if (--liveInstances == 0) dCloseODE();
}

std::unique_lock<std::mutex> OdeRuntime::lock() { return std::unique_lock<std::mutex>(odeMutex()); }

}  // namespace cdb
