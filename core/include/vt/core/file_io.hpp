#pragma once
// Reading input files with one-line errors that say what went wrong: not found, a folder where a
// file is expected, a symlink loop, permission denied, larger than its budget. Any thread.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace vt {

/// "'PATH': cannot ACTION: why" for an errno value (disk full, permission, symlink loop, ...).
std::string describeErrno(const std::filesystem::path& path, std::string_view action, int error);

/// Checks that `path` is a regular file (following symlinks) of at most `maxBytes` and returns its
/// size; otherwise throws vt::Error "WHAT 'PATH': problem".
std::uintmax_t checkInputFile(const std::filesystem::path& path, std::string_view what, std::uintmax_t maxBytes);

/// The whole file after checkInputFile; read errors name the file too.
std::string readInputFile(const std::filesystem::path& path, std::string_view what, std::uintmax_t maxBytes);
/// The same into bytes, for callers that keep a byte vector (no second copy of a large file).
std::vector<unsigned char> readInputBytes(const std::filesystem::path& path, std::string_view what,
                                          std::uintmax_t maxBytes);

}  // namespace vt
