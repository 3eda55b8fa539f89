#include "scenes/OdeRuntime.h"

#include <cstdarg>
#include <cstdio>
#include <cstring>

#include <ode/ode.h>

namespace cdb {

namespace {

std::mutex& odeMutex() {
  static std::mutex mutex;
  return mutex;
}

int liveInstances = 0;                         // guarded by odeMutex()
dMessageFunction* previousHandler = nullptr;  // guarded by odeMutex()

// ODE reports when the trimesh-trimesh collider cannot merge some close contacts. That only means
// a few more contacts than necessary, which ContactPicker trims anyway; in piles of tori it fires
// dozens of times a run and would bury real messages, so it alone is dropped.
void filterMessages(int errnum, const char* format, va_list args) {
  if (format && std::strstr(format, "contach hash table bucket overflow")) return;
  if (previousHandler) {
    previousHandler(errnum, format, args);
    return;
  }
  std::fprintf(stderr, "\nODE Message %d: ", errnum);
  std::vfprintf(stderr, format, args);
  std::fprintf(stderr, "\n");
}

}  // namespace

OdeRuntime::OdeRuntime() {
  const auto guard = lock();
  if (liveInstances++ == 0) {
    dInitODE2(0);
    previousHandler = dGetMessageHandler();
    dSetMessageHandler(&filterMessages);
  }
  dAllocateODEDataForThread(dAllocateMaskAll);
}

OdeRuntime::~OdeRuntime() {
  const auto guard = lock();
  if (--liveInstances == 0) {
    dSetMessageHandler(previousHandler);
    dCloseODE();
  }
}

std::unique_lock<std::mutex> OdeRuntime::lock() { return std::unique_lock<std::mutex>(odeMutex()); }

}  // namespace cdb
