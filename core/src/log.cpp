#include "vt/core/log.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <mutex>

namespace vt::log {
namespace {

Level initialLevel() {
  Level parsed = Level::Info;
  if (const char* env = std::getenv("VT_LOG")) parseLevel(env, parsed);
  return parsed;
}

std::atomic<Level> g_level{initialLevel()};
std::mutex g_sinkMutex;
Sink g_sink;

const char* levelName(Level level) {
  switch (level) {
    case Level::Debug: return "debug";
    case Level::Info: return "info";
    case Level::Warn: return "warning";
    case Level::Error: return "error";
    case Level::Off: break;
  }
  return "";
}

}  // namespace

void setLevel(Level level) noexcept { g_level.store(level); }
Level level() noexcept { return g_level.load(std::memory_order_relaxed); }

bool parseLevel(std::string_view text, Level& out) noexcept {
  static constexpr std::pair<std::string_view, Level> kNames[] = {
      {"debug", Level::Debug}, {"info", Level::Info}, {"warn", Level::Warn},
      {"error", Level::Error}, {"off", Level::Off}};
  for (const auto& [name, value] : kNames) {
    if (text == name) {
      out = value;
      return true;
    }
  }
  return false;
}

void setSink(Sink sink) {
  std::lock_guard lock(g_sinkMutex);
  g_sink = std::move(sink);
}

void write(Level level, std::string_view message) {
  std::lock_guard lock(g_sinkMutex);
  if (g_sink) {
    g_sink(level, message);
    return;
  }
  std::fprintf(stderr, "[%s] %.*s\n", levelName(level), static_cast<int>(message.size()), message.data());
}

}  // namespace vt::log
