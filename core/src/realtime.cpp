#include "vt/core/realtime.hpp"

#include <pthread.h>
#include <sched.h>

namespace vt {

bool requestRealtimePriority(int priority) noexcept {
  if (priority < 1 || priority > 99) return false;
  sched_param param{};
  param.sched_priority = priority;
  return pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) == 0;
}

}  // namespace vt
