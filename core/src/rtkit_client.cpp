#include "rtkit_client.hpp"

#include <dbus/dbus.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdint>
#include <memory>

#include "vt/core/error.hpp"

namespace vt::detail {
namespace {

constexpr const char* kService = "org.freedesktop.RealtimeKit1";
constexpr const char* kObject = "/org/freedesktop/RealtimeKit1";
constexpr int kCallTimeout_ms = 1000;

struct ConnectionCloser {
  void operator()(DBusConnection* c) const noexcept {
    dbus_connection_close(c);
    dbus_connection_unref(c);
  }
};
using Connection = std::unique_ptr<DBusConnection, ConnectionCloser>;
struct MessageUnref {
  void operator()(DBusMessage* m) const noexcept { dbus_message_unref(m); }
};
using Message = std::unique_ptr<DBusMessage, MessageUnref>;

/// A DBusError freed on every path.
struct Error {
  DBusError e;
  Error() { dbus_error_init(&e); }
  ~Error() { dbus_error_free(&e); }
  Error(const Error&) = delete;
  Error& operator=(const Error&) = delete;
  std::string text(const char* what) const { return str(what, ": ", e.message ? e.message : "unknown error"); }
};

/// Sends `call` and waits for the reply; an empty Message and `error` filled on failure.
Message callMethod(DBusConnection* c, DBusMessage* call, std::string& error, const char* what) {
  Error e;
  Message reply(dbus_connection_send_with_reply_and_block(c, call, kCallTimeout_ms, &e.e));
  if (!reply) error = e.text(what);
  return reply;
}

/// Reads an integer property (RealtimeKit exposes "i" and "x" ones); false and `error` on failure.
bool getIntProperty(DBusConnection* c, const char* name, std::int64_t& out, std::string& error) {
  Message call(dbus_message_new_method_call(kService, kObject, "org.freedesktop.DBus.Properties", "Get"));
  if (!call) return error = "out of memory", false;
  const char* interface = kService;
  dbus_message_append_args(call.get(), DBUS_TYPE_STRING, &interface, DBUS_TYPE_STRING, &name, DBUS_TYPE_INVALID);
  Message reply = callMethod(c, call.get(), error, name);
  if (!reply) return false;
  DBusMessageIter it, variant;
  if (!dbus_message_iter_init(reply.get(), &it) || dbus_message_iter_get_arg_type(&it) != DBUS_TYPE_VARIANT)
    return error = str(name, ": reply is not a variant"), false;
  dbus_message_iter_recurse(&it, &variant);
  switch (dbus_message_iter_get_arg_type(&variant)) {
    case DBUS_TYPE_INT32: {
      dbus_int32_t v = 0;
      dbus_message_iter_get_basic(&variant, &v);
      out = v;
      return true;
    }
    case DBUS_TYPE_INT64: {
      dbus_int64_t v = 0;
      dbus_message_iter_get_basic(&variant, &v);
      out = v;
      return true;
    }
    default:
      return error = str(name, ": unexpected type"), false;
  }
}

}  // namespace

std::string rtkitMakeThreadRealtime(pid_t tid, int priority) {
  Error e;
  // A private connection: closing it after the request leaves the application's own D-Bus use alone.
  Connection c(dbus_bus_get_private(DBUS_BUS_SYSTEM, &e.e));
  if (!c) return e.text("system bus");
  dbus_connection_set_exit_on_disconnect(c.get(), FALSE);  // libdbus would _exit() otherwise

  std::string error;
  std::int64_t maxPriority = 0, rttimeMax_us = 0;
  if (!getIntProperty(c.get(), "MaxRealtimePriority", maxPriority, error)) return error;
  if (!getIntProperty(c.get(), "RTTimeUSecMax", rttimeMax_us, error)) return error;
  if (maxPriority < 1) return str("RealtimeKit allows no real-time priority (MaxRealtimePriority ", maxPriority, ")");

  // RealtimeKit only serves processes whose CPU time in real time is bounded.
  rlimit limit{};
  if (getrlimit(RLIMIT_RTTIME, &limit) != 0) return "getrlimit(RLIMIT_RTTIME) failed";
  if (limit.rlim_max == RLIM_INFINITY || limit.rlim_max > rlim_t(rttimeMax_us)) {
    limit.rlim_cur = limit.rlim_max = rlim_t(rttimeMax_us);
    if (setrlimit(RLIMIT_RTTIME, &limit) != 0) return "setrlimit(RLIMIT_RTTIME) failed";
  }

  Message call(dbus_message_new_method_call(kService, kObject, kService, "MakeThreadRealtime"));
  if (!call) return "out of memory";
  const dbus_uint64_t thread = dbus_uint64_t(tid);
  const dbus_uint32_t asked = dbus_uint32_t(std::min<std::int64_t>(priority, maxPriority));
  dbus_message_append_args(call.get(), DBUS_TYPE_UINT64, &thread, DBUS_TYPE_UINT32, &asked, DBUS_TYPE_INVALID);
  if (!callMethod(c.get(), call.get(), error, "MakeThreadRealtime")) return error;
  return {};
}

}  // namespace vt::detail
