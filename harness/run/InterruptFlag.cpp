#include "harness/run/InterruptFlag.h"

#include <csignal>

namespace cdb {

namespace {
volatile std::sig_atomic_t received = 0;

extern "C" void onSignal(int signal) {
  if (received != 0) {  // a second signal: stop now
    std::signal(signal, SIG_DFL);
    std::raise(signal);
    return;
  }
  received = signal;
}
}  // namespace

void installInterruptHandlers() {
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool interruptRequested() { return received != 0; }
int interruptSignal() { return received; }

}  // namespace cdb
