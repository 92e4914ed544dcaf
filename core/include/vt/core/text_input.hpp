#pragma once
// Checks on text inputs before any parser sees them (docs/RELIABILITY.md): the encoding (a BOM or
// UTF-16 text is refused as such, not read as data) and JSON nesting (recursive parsers and the
// code that walks their trees recurse once per level). Any thread.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace vt {

/// Throws vt::Error "SOURCE: ..." when `text` starts with a byte-order mark or is UTF-16/32
/// (NUL bytes), saying to save it as plain UTF-8 text.
void checkTextEncoding(std::string_view text, std::string_view source);

/// Throws vt::Error "SOURCE: JSON nested deeper than LIMIT levels at byte N" when arrays and
/// objects (outside strings) nest deeper than `limit`. Linear, no recursion, no allocation.
void checkJsonNesting(std::string_view text, std::string_view source, int limit);

/// readInputFile, then checkTextEncoding (naming "WHAT 'PATH'").
std::string readInputText(const std::filesystem::path& path, std::string_view what, std::uintmax_t maxBytes);

}  // namespace vt
