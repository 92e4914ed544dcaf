#pragma once
// Leveled logging for setup, UI and device threads. Never call from the haptic thread.
#include <functional>
#include <string>
#include <string_view>

#include "vt/core/error.hpp"

namespace vt::log {

enum class Level { Debug = 0, Info = 1, Warn = 2, Error = 3, Off = 4 };

/// Lines below this level are dropped. Default: Info, or the VT_LOG environment variable.
void setLevel(Level level) noexcept;
Level level() noexcept;
/// Parses "debug|info|warn|error|off"; returns false for anything else.
bool parseLevel(std::string_view text, Level& out) noexcept;

/// Replaces stderr as the destination (tests capture lines, the HUD shows them). Empty = stderr.
using Sink = std::function<void(Level, std::string_view)>;
void setSink(Sink sink);

void write(Level level, std::string_view message);

template <class... Args>
void debug(Args&&... args) { if (level() <= Level::Debug) write(Level::Debug, str(std::forward<Args>(args)...)); }
template <class... Args>
void info(Args&&... args) { if (level() <= Level::Info) write(Level::Info, str(std::forward<Args>(args)...)); }
template <class... Args>
void warn(Args&&... args) { if (level() <= Level::Warn) write(Level::Warn, str(std::forward<Args>(args)...)); }
template <class... Args>
void error(Args&&... args) { if (level() <= Level::Error) write(Level::Error, str(std::forward<Args>(args)...)); }

}  // namespace vt::log
