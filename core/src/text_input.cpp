#include "vt/core/text_input.hpp"

#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"

namespace vt {

void checkTextEncoding(std::string_view text, std::string_view source) {
  const auto starts = [&](std::string_view prefix) { return text.substr(0, prefix.size()) == prefix; };
  const char* encoding = nullptr;
  if (starts("\xEF\xBB\xBF")) {
    encoding = "starts with a UTF-8 byte-order mark";
  } else if (starts(std::string_view("\xFF\xFE\0\0", 4)) || starts(std::string_view("\0\0\xFE\xFF", 4))) {
    encoding = "is UTF-32 text";
  } else if (starts("\xFF\xFE") || starts("\xFE\xFF")) {
    encoding = "is UTF-16 text (it starts with a UTF-16 byte-order mark)";
  } else if (text.find('\0') != std::string_view::npos) {
    encoding = "holds NUL bytes (UTF-16 text, or not text at all)";
  }
  if (encoding) fail(source, ": ", encoding, ": save it as plain UTF-8 (or ASCII) text without a byte-order mark");
}

void checkJsonNesting(std::string_view text, std::string_view source, int limit) {
  int depth = 0;
  bool inString = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\') ++i;  // the escaped character cannot end the string
      else if (c == '"') inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limit) fail(source, ": JSON nested deeper than ", limit, " levels at byte ", i, " (docs/RELIABILITY.md)");
    } else if (c == ']' || c == '}') {
      --depth;  // unbalanced text is the parser's to report
    }
  }
}

std::string readInputText(const std::filesystem::path& path, std::string_view what, std::uintmax_t maxBytes) {
  std::string text = readInputFile(path, what, maxBytes);
  checkTextEncoding(text, str(what, " '", path.string(), "'"));
  return text;
}

}  // namespace vt
