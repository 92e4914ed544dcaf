#include "vt/core/realtime.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <mutex>

#include "rtkit_client.hpp"
#include "vt/core/error.hpp"

namespace vt {
namespace {

std::mutex g_grantsMutex;
std::vector<ThreadGrant>& grants() {
  static std::vector<ThreadGrant> list;
  return list;
}

void readBack(RealtimeGrant& grant) noexcept {
  sched_param param{};
  int policy = SCHED_OTHER;
  if (pthread_getschedparam(pthread_self(), &policy, &param) == 0) {
    grant.policy = policy & ~SCHED_RESET_ON_FORK;  // RealtimeKit sets it; the policy is what matters
    grant.priority = param.sched_priority;
  }
  const int slack = prctl(PR_GET_TIMERSLACK, 0, 0, 0, 0);
  grant.timerSlack_ns = slack < 0 ? 0 : slack;
}

void record(std::string_view thread, const RealtimeGrant& grant, std::string refusal) {
  const std::lock_guard lock(g_grantsMutex);
  for (ThreadGrant& g : grants()) {
    if (g.thread == thread) {
      g.grant = grant;
      g.refusal = std::move(refusal);
      return;
    }
  }
  grants().push_back(ThreadGrant{std::string(thread), grant, std::move(refusal)});
}

}  // namespace

RealtimeGrant requestRealtime(std::string_view thread, int priority) noexcept {
  RealtimeGrant grant;
  // 1 ns is the smallest slack (0 would restore the default 50 us); it bounds how late the
  // kernel may fire this thread's sleeps for the sake of batching wake-ups.
  prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0);
  try {
    std::string refusal;
    if (priority < 1 || priority > 99) {
      refusal = str("priority ", priority, " outside 1..99");
    } else {
      sched_param param{};
      param.sched_priority = priority;
      const int fifo = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
      if (fifo == 0) {
        grant.method = RealtimeMethod::SchedFifo;
      } else {
        const std::string why = detail::rtkitMakeThreadRealtime(pid_t(syscall(SYS_gettid)), priority);
        if (why.empty()) grant.method = RealtimeMethod::RealtimeKit;
        else refusal = str("SCHED_FIFO: ", std::strerror(fifo), "; RealtimeKit: ", why);
      }
    }
    readBack(grant);
    record(thread, grant, std::move(refusal));
  } catch (...) {  // only allocation can throw here; the grant itself stands
    readBack(grant);
  }
  return grant;
}

std::vector<ThreadGrant> realtimeGrants() {
  const std::lock_guard lock(g_grantsMutex);
  return grants();
}

std::string describeRealtimeGrants() {
  std::string text;
  for (const ThreadGrant& g : realtimeGrants()) {
    if (!text.empty()) text += "; ";
    text += g.thread + ": ";
    if (g.grant.granted()) {
      text += str(schedulingPolicyName(g.grant.policy), " ", g.grant.priority,
                  g.grant.method == RealtimeMethod::RealtimeKit ? " via RealtimeKit" : "");
    } else {
      text += "normal scheduling (" + g.refusal + ")";
    }
    text += str(", slack ", g.grant.timerSlack_ns, " ns");
  }
  return text.empty() ? std::string("no real-time thread asked") : text;
}

std::string_view realtimeMethodName(RealtimeMethod method) noexcept {
  switch (method) {
    case RealtimeMethod::SchedFifo: return "SCHED_FIFO";
    case RealtimeMethod::RealtimeKit: return "RealtimeKit";
    case RealtimeMethod::None: break;
  }
  return "none";
}

std::string_view schedulingPolicyName(int policy) noexcept {
  switch (policy) {
    case SCHED_OTHER: return "SCHED_OTHER";
    case SCHED_FIFO: return "SCHED_FIFO";
    case SCHED_RR: return "SCHED_RR";
    case SCHED_BATCH: return "SCHED_BATCH";
    case SCHED_IDLE: return "SCHED_IDLE";
    default: return "unknown policy";
  }
}

}  // namespace vt
