#include "vt/core/stop.hpp"

#include <unistd.h>

#include <atomic>
#include <csignal>

#include "vt/core/error.hpp"

namespace vt {
namespace {

// Lock-free atomics are async-signal-safe; the handler does nothing else but store.
std::atomic<int> g_stop{0};
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void onStopSignal(int signal) {
  if (g_stop.exchange(signal) > 0) _exit(128 + signal);  // a second signal: the user insists
}

}  // namespace

void requestStop(int reason) noexcept {
  int none = 0;
  g_stop.compare_exchange_strong(none, reason);  // the first reason is the one reported
}

bool stopRequested() noexcept { return g_stop.load(std::memory_order_acquire) != 0; }

int stopSignal() noexcept { return g_stop.load(std::memory_order_acquire); }

void clearStop() noexcept { g_stop.store(0); }

void installStopSignals() {
  struct sigaction action {};
  action.sa_handler = onStopSignal;
  sigemptyset(&action.sa_mask);
  for (int signal : {SIGINT, SIGTERM}) {
    if (sigaction(signal, &action, nullptr) != 0) fail("stop: sigaction(", signal, ") failed");
  }
}

}  // namespace vt
